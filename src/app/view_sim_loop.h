#pragma once
/// ViewSimLoop: `rescuesim view`'s simulation thread. It steps a Session paced to the wall clock
/// (session/realtime_pacer.h) with the controls the UI thread last set, so the window keeps its
/// frame rate whatever a step costs, and a heavy scenario runs at its own pace behind it.
///
/// Locking: the loop holds lock() while it steps, in spans of at most kSpan of wall time, and
/// Bus callbacks run on its thread under it. The UI thread takes lock() to read the simulation
/// (state, ray scene, time) or call its command_* functions; while it waits, the loop lets it
/// in before stepping on.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "msgs/messages.h"
#include "session/session.h"

namespace rescuesim::app {

/// What the UI asks of the simulation thread.
struct ViewControls {
  bool paused = false;
  double rate = 1.0;       ///< sim seconds per wall second
  bool autonomous = true;  ///< false: `teleop` is robot 0's command after every step, overruling its controller
  msg::Twist teleop;
};

class ViewSimLoop {
 public:
  /// Longest span of stepping under lock() before the loop lets the UI in.
  static constexpr std::chrono::milliseconds kSpan{4};

  /// Starts the thread; it steps `session` (which must outlive it) with `controls`.
  ViewSimLoop(Session& session, const ViewControls& controls);
  /// Stops and joins the thread.
  ~ViewSimLoop();
  ViewSimLoop(const ViewSimLoop&) = delete;
  ViewSimLoop& operator=(const ViewSimLoop&) = delete;

  /// Holds the simulation still for the UI thread while the returned lock lives.
  std::unique_lock<std::mutex> lock();

  /// Replaces the controls (from the next span of steps on).
  void set_controls(const ViewControls& controls);
  /// Steps `seconds` of sim time more while paused.
  void request_step(double seconds);

  /// Sim seconds stepped per wall second over the last second or so.
  double real_time_factor() const { return rtf_.load(); }
  /// Why stepping stopped for good (an exception from the simulation), or "".
  std::string error() const;

 private:
  void run();

  Session& session_;
  std::mutex sim_mutex_;
  std::atomic<int> ui_waiting_{0};  // UI threads queued on sim_mutex_: the loop yields to them

  mutable std::mutex control_mutex_;
  std::condition_variable wake_;
  ViewControls controls_;
  double step_request_ = 0;  // s, not yet handed to the pacer
  bool stop_ = false;
  std::string error_;

  std::atomic<double> rtf_{0};
  std::thread thread_;
};

}  // namespace rescuesim::app
