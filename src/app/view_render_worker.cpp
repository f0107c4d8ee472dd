// The viewer's render thread: waits for a request, draws it, keeps the frame for the UI thread.

#include "app/view_render_worker.h"

#include <chrono>
#include <utility>

#include "core/error.h"
#include "core/thread.h"

namespace rescuesim::app {

RenderWorker::RenderWorker(const World& world, Quality q) : world_(world) {
  // the renderer is made on the thread that uses it; wait for it to say whether that worked
  std::promise<std::string> started;
  auto result = started.get_future();
  thread_ = start_named_thread("view-render", [this, q, &started] { run(q, started); });
  const std::string error = result.get();
  if (!error.empty()) {
    thread_.join();
    throw Error(error);
  }
}

RenderWorker::~RenderWorker() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

bool RenderWorker::busy() const {
  const std::lock_guard lock(mutex_);
  return pending_.has_value() || drawing_;
}

void RenderWorker::submit(RenderRequest r) {
  {
    const std::lock_guard lock(mutex_);
    pending_ = std::move(r);
  }
  wake_.notify_all();
}

std::optional<RenderFrame> RenderWorker::take() {
  const std::lock_guard lock(mutex_);
  return std::exchange(done_, std::nullopt);
}

std::string RenderWorker::error() const {
  const std::lock_guard lock(mutex_);
  return error_;
}

void RenderWorker::run(Quality q, std::promise<std::string>& started) {
  std::unique_ptr<Renderer> renderer;
  RenderScene scene;
  try {
    renderer = Renderer::create_headless(q);
    scene = build_render_scene(world_);
    renderer->load(scene);
    device_ = renderer->device();
  } catch (const std::exception& e) {
    started.set_value(e.what());
    return;
  }
  started.set_value("");
  for (;;) {
    // the newest request, or stop
    RenderRequest r;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || pending_.has_value(); });
      if (stop_) return;
      r = std::move(*pending_);
      pending_.reset();
      drawing_ = true;
    }
    // draw it outside the lock, then publish the frame or the problem
    RenderFrame f;
    std::string problem;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      draw(*renderer, scene, r, f);
    } catch (const std::exception& e) {
      problem = e.what();
    }
    f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::lock_guard lock(mutex_);
    drawing_ = false;
    error_ = problem;
    if (problem.empty()) done_ = std::move(f);
  }
}

void RenderWorker::draw(Renderer& renderer, RenderScene& scene, const RenderRequest& r, RenderFrame& f) {
  update_render_scene(scene, r.state);
  renderer.update(scene);
  renderer.set_quality(r.quality);
  f.time = r.state.time.seconds();
  renderer.color(r.main, f.main);
}

}  // namespace rescuesim::app
