#pragma once
/// The render thread: renders camera sensors from State snapshots while the simulation goes
/// on stepping, and hands the frames back at a fixed delivery time, so what a run publishes
/// never depends on thread timing.
///
/// A camera sampled at time t (its image shows the world at t and is stamped t) is delivered
/// at the first step at or after t + latency. The default latency is one camera period: the
/// render thread has a whole frame's time to finish while physics runs on the other core.
/// Latency 0 renders synchronously. If a frame is not finished by its delivery time, the
/// simulation waits for it.
///
/// Victims: each thermal frame is searched for warm blobs where victims project into it; a
/// victim whose body shows at least `victim_contrast` kelvin above ambient is recorded as seen at
/// the frame's stamp.

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

#include "render/renderer.h"
#include "sim/simulation.h"

namespace rescuesim {

struct CameraServiceOptions {
  Quality quality = Quality::low;
  double latency = -1;             ///< s; < 0: one period of each camera; 0: synchronous
  double victim_contrast = 4.0;    ///< K above ambient that counts as a warm blob
};

class RenderCameraService : public CameraService {
 public:
  /// Starts the render thread and its OpenGL context; throws Error (with the reason from
  /// Renderer::create_headless) when no renderer can be made.
  RenderCameraService(const World& world, const CameraServiceOptions& options = {});
  ~RenderCameraService() override;

  void sample(const World& world, const State& state, const SensorInstance& sensor, SensorSlot& slot) override;
  void deliver(const World& world, State& state, SimTime now, const std::function<void(int, msg::Message)>& publish) override;
  bool detects_victims(int robot) const override;

  /// The GL device in use, e.g. "llvmpipe (…) via EGL surfaceless".
  std::string device() const { return device_; }
  /// The last frame of each camera sensor, by sensor name (for run outputs).
  struct LastFrame {
    int robot = -1;
    std::string sensor;
    msg::Image image;
  };
  std::vector<LastFrame> last_frames() const;

 private:
  struct Job;

  const World& world_;
  CameraServiceOptions options_;
  std::string device_;
  std::thread thread_;
  mutable std::mutex mutex_;
  std::condition_variable work_, done_;
  std::deque<std::shared_ptr<Job>> queue_;   ///< waiting for the render thread
  std::deque<std::shared_ptr<Job>> pending_; ///< in sample order, until delivered
  bool stop_ = false;
  std::string error_;                        ///< set by the render thread when it fails
  std::vector<LastFrame> last_;
  std::vector<bool> thermal_robot_;
};

}  // namespace rescuesim
