#pragma once
/// The render thread: renders camera sensors from State snapshots while the simulation goes
/// on stepping, and hands the frames back at a fixed delivery time, so what a run publishes
/// never depends on thread timing. Part of rs_sensors_camera, the only target linking the
/// renderer (OpenGL through EGL); Session constructs it when a scenario has cameras.
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
#include <string>
#include <thread>
#include <vector>

#include "render/renderer.h"
#include "sensors/camera_service.h"

namespace rescuesim {

struct CameraServiceOptions {
  Quality quality = Quality::low;
  double latency = -1;             ///< s; < 0: one period of each camera; 0: synchronous
  double victim_contrast = 4.0;    ///< K above ambient that counts as a warm blob
};

class RenderCameraService : public CameraService {
 public:
  /// Starts the render thread and its OpenGL context; throws Error (with the reason from
  /// Renderer::create_headless) when no renderer can be made. Keeps a reference to `world`,
  /// which must outlive the service (Session passes its Simulation's world).
  RenderCameraService(const World& world, const CameraServiceOptions& options = {});
  ~RenderCameraService() override;

  void sample(const World& world, const State& state, const SensorInstance& sensor, SensorSlot& slot) override;
  void deliver(const World& world, State& state, SimTime now, const std::function<void(TopicId, msg::Message)>& publish) override;
  /// True when this service finds `robot`'s victims in its thermal images (it has an enabled
  /// thermal camera): Session then picks ThermalImageDetector (sensors/victim_detector.h).
  bool detects_victims(RobotIndex robot) const;

  /// The GL device in use, e.g. "llvmpipe (…) via EGL surfaceless".
  std::string device() const { return device_; }
  /// The last frame of each camera sensor, by sensor name (for run outputs).
  struct LastFrame {
    RobotIndex robot;
    std::string sensor;
    msg::Image image;
  };
  std::vector<LastFrame> last_frames() const;
  /// The last frame of robot `robot`'s camera `sensor`, or nullptr before its first; valid until
  /// the next deliver().
  const msg::Image* last_frame(RobotIndex robot, const std::string& sensor) const;

  struct Job;
  /// The frames sampled and not yet delivered, as what to render (the State each shows, its
  /// noise stream as drawn at sample time, when it is due), in sample order: the part of a run
  /// that a State snapshot does not hold (Session::snapshot keeps it beside the State).
  struct InFlight {
    std::vector<std::shared_ptr<const Job>> frames;
  };
  InFlight in_flight() const;
  /// Drops every frame in flight (the one being rendered is finished and thrown away), then
  /// queues `frames` to be rendered anew; they come out bitwise as they would have the first time.
  /// For Session::restore. The last frames (last_frames) are not rewound.
  void restore(const InFlight& frames);

 private:

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
  std::uint64_t generation_ = 0;             ///< counts restores: the render thread redraws its scene after one
  std::vector<LastFrame> last_;
  std::vector<bool> thermal_robot_;
};

}  // namespace rescuesim
