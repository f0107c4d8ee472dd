#include "app/view_sim_loop.h"

#include <exception>

#include "core/thread.h"
#include "session/realtime_pacer.h"

namespace rescuesim::app {

using Clock = std::chrono::steady_clock;

ViewSimLoop::ViewSimLoop(Session& session, const ViewControls& controls) : session_(session), controls_(controls) {
  thread_ = start_named_thread("sim", [this] { run(); });
}

ViewSimLoop::~ViewSimLoop() {
  {
    std::lock_guard<std::mutex> g(control_mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::unique_lock<std::mutex> ViewSimLoop::lock() {
  ++ui_waiting_;
  std::unique_lock<std::mutex> l(sim_mutex_);
  --ui_waiting_;
  return l;
}

void ViewSimLoop::set_controls(const ViewControls& controls) {
  {
    std::lock_guard<std::mutex> g(control_mutex_);
    controls_ = controls;
  }
  wake_.notify_all();
}

void ViewSimLoop::request_step(double seconds) {
  {
    std::lock_guard<std::mutex> g(control_mutex_);
    step_request_ += seconds;
  }
  wake_.notify_all();
}

std::string ViewSimLoop::error() const {
  std::lock_guard<std::mutex> g(control_mutex_);
  return error_;
}

void ViewSimLoop::run() {
  Simulation& sim = session_.sim();
  RealtimePacer pacer;
  const auto start = Clock::now();
  auto rtf_since = start;
  double rtf_sim = 0;  // sim seconds stepped since rtf_since
  for (;;) {
    ViewControls c;
    double step = 0;
    {
      std::lock_guard<std::mutex> g(control_mutex_);
      if (stop_) return;
      c = controls_;
      step = std::exchange(step_request_, 0.0);
    }
    bool behind = false;
    {
      std::lock_guard<std::mutex> g(sim_mutex_);
      const SimTime before = sim.time();
      if (step > 0) pacer.request_step(before, step);
      const double wall = std::chrono::duration<double>(Clock::now() - start).count();
      const SimTime target = pacer.target(wall, before, c.rate, c.paused || sim.in_trouble());
      const auto span_end = Clock::now() + kSpan;
      try {
        // one Session step at a time: the built-in controllers, the recordings and the mission
        // go with it, as in rescuesim run
        while (sim.time() < target && Clock::now() < span_end && session_.step_until(sim.time() + SimTime{1})) {
          if (!c.autonomous) sim.command_velocity(RobotIndex(0), c.teleop);
        }
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> g2(control_mutex_);
        error_ = e.what();
        return;
      }
      behind = sim.time() < target && !sim.in_trouble();
      rtf_sim += (sim.time() - before).seconds();
    }
    const auto now = Clock::now();
    if (const double window = std::chrono::duration<double>(now - rtf_since).count(); window > 1.0) {
      rtf_ = rtf_sim / window;
      rtf_since = now;
      rtf_sim = 0;
    }
    if (behind) {
      // let a waiting UI thread in before the next span
      while (ui_waiting_.load() > 0) std::this_thread::yield();
    } else {
      // ahead of the clock, paused or stopped by trouble: wait a little, or until the controls change
      std::unique_lock<std::mutex> l(control_mutex_);
      wake_.wait_for(l, std::chrono::milliseconds(2), [this] { return stop_ || step_request_ > 0; });
    }
  }
}

}  // namespace rescuesim::app
