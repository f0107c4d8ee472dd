#pragma once
/// The render thread of `rescuesim view`: it owns a headless Renderer for the main view (its own
/// EGL context: one thread cannot hold the window's GLX context and an EGL one at once) and
/// draws State copies handed to it at whatever rate it manages.

#include <condition_variable>
#include <future>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "render/render_scene.h"
#include "render/renderer.h"
#include "world/state.h"
#include "world/world.h"

namespace rescuesim::app {

/// One frame for the render thread: a State copy and where the main camera is.
struct RenderRequest {
  State state;
  CameraView main;
  Quality quality = Quality::low;
};

/// What the render thread hands back: the main view.
struct RenderFrame {
  double time = 0;     ///< sim time of the State drawn (s)
  double seconds = 0;  ///< wall time the frame took to render
  ColorImage main;
};

/// The render thread: one pending request (a newer one replaces it), one finished frame.
/// `world` must outlive it.
class RenderWorker {
 public:
  /// Starts the thread and its renderer; throws Error when no renderer can be made.
  RenderWorker(const World& world, Quality q);
  /// Stops the thread (after the frame it is drawing).
  ~RenderWorker();
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;

  /// True while a request waits or is being drawn.
  bool busy() const;
  /// Queues `r`, replacing a request not yet started.
  void submit(RenderRequest r);
  /// The latest finished frame, once.
  std::optional<RenderFrame> take();
  /// The last rendering problem ("" when none).
  std::string error() const;
  /// The renderer's device string (e.g. "llvmpipe").
  const std::string& device() const { return device_; }

 private:
  void run(Quality q, std::promise<std::string>& started);
  static void draw(Renderer& renderer, RenderScene& scene, const RenderRequest& r, RenderFrame& f);

  const World& world_;
  std::string device_;
  std::thread thread_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<RenderRequest> pending_;
  std::optional<RenderFrame> done_;
  bool drawing_ = false, stop_ = false;
  std::string error_;
};

}  // namespace rescuesim::app
