#pragma once
/// RealtimePacer: where a run paced to the wall clock should stand, the one pacing rule of
/// `rescuesim run` (Session::run, realtime mode), `rescuesim view`'s simulation thread and
/// everything that runs through them (ROS, Foxglove, Python's realtime runs). Sim time advances
/// at `rate` sim seconds per wall second from an anchor.
/// The anchor moves when the rate changes, when the run resumes after a pause, and when the
/// simulation falls more than `max_lag` wall seconds behind: a run that cannot keep up goes as
/// fast as it can without owing the time it lost (as Gazebo's real-time factor drops below
/// its target), instead of racing later to catch up. Paused, it advances only by step
/// requests. Pure arithmetic on the times it is given: tests feed it any clock.

#include <algorithm>

#include "core/sim_time.h"

namespace rescuesim {

class RealtimePacer {
 public:
  explicit RealtimePacer(double max_lag_s = 0.25) : max_lag_(max_lag_s) {}

  /// Asks for `seconds` of sim time more while paused, from `sim` (the simulation's time now)
  /// or from the end of the steps already asked for, whichever is later.
  void request_step(SimTime sim, double seconds) { step_until_ = std::max(step_until_, sim) + SimTime::from_seconds(seconds); }

  /// The sim time to step to at wall time `wall_s` (s, any steady clock), when the simulation
  /// stands at `sim`.
  SimTime target(double wall_s, SimTime sim, double rate, bool paused) {
    if (paused) {
      anchored_ = false;
      return std::max(sim, step_until_);
    }
    if (!anchored_ || rate != rate_) anchor(wall_s, sim, rate);
    const double ahead = rate_ * (wall_s - wall_anchor_);
    if (ahead - (sim - sim_anchor_).seconds() > rate_ * max_lag_) {
      // behind by more than max_lag: drop the debt, keep max_lag of it
      anchor(wall_s - max_lag_, sim, rate);
      return sim + SimTime::from_seconds(rate_ * max_lag_);
    }
    return sim_anchor_ + SimTime::from_seconds(ahead);
  }

  /// The wall time (s, the clock target() is given) at which sim time `sim` is due; call after
  /// target(), which anchors the pacer.
  double wall_due(SimTime sim) const { return wall_anchor_ + (sim - sim_anchor_).seconds() / rate_; }

  /// Starts afresh: the next target() anchors at its own times (after steps taken at once, a
  /// reset, a restore), so the time they took is neither owed nor credited.
  void restart() { anchored_ = false; }

 private:
  void anchor(double wall_s, SimTime sim, double rate) {
    wall_anchor_ = wall_s;
    sim_anchor_ = sim;
    rate_ = rate;
    anchored_ = true;
  }

  double max_lag_;
  bool anchored_ = false;
  double wall_anchor_ = 0, rate_ = 1;
  SimTime sim_anchor_, step_until_;
};

}  // namespace rescuesim
