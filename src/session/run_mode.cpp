#include "session/run_mode.h"

#include <limits>

#include "core/error.h"

namespace rescuesim {

RunMode resolve_run_mode(const RunModeRequest& r) {
  // contradictions first: say so rather than let one flag silently win
  if (r.realtime && r.sync) {
    throw Error({"", 0, "--realtime --sync"}, "--sync is lockstep (each scan waits for its cmd_vel): drop --realtime or --sync");
  }
  if (r.realtime && r.lockstep) throw Error({"", 0, "--realtime --lockstep"}, "choose one of --realtime and --lockstep");
  if (r.sync && !r.live_bridge) {
    throw Error({"", 0, "--sync"}, "--sync waits for a ROS controller's cmd_vel: use it with --ros1 or --ros2");
  }
  RunMode m;
  // pacing, by precedence
  if (r.sync) {
    m.pacing = Pacing::sync;
    m.sync_timeout = *r.sync;
  } else if (r.lockstep) {
    m.pacing = Pacing::lockstep;
  } else if (r.realtime || r.live_bridge) {
    m.pacing = Pacing::realtime;
  } else {
    m.pacing = r.scenario_realtime ? Pacing::realtime : Pacing::lockstep;
  }
  // with a live bridge, ROS drives the robots: the built-in controllers stay off unless kept
  m.controllers = !r.no_controllers && (!r.live_bridge || r.keep_controllers);
  // like a ROS simulator: until Ctrl-C
  m.until_stopped = r.live_bridge && !r.duration_given;
  return m;
}

void apply_run_mode(const RunMode& mode, Scenario& scenario, SessionOptions& options) {
  scenario.realtime = mode.pacing == Pacing::realtime;
  if (mode.until_stopped) scenario.duration = std::numeric_limits<double>::infinity();
  options.controllers = mode.controllers;
  options.sync_timeout = mode.pacing == Pacing::sync ? mode.sync_timeout : 0;
}

const char* pacing_name(Pacing pacing) {
  switch (pacing) {
    case Pacing::lockstep: return "lockstep";
    case Pacing::realtime: return "realtime";
    case Pacing::sync: return "lockstep, synchronous with cmd_vel";
  }
  return "lockstep";
}

}  // namespace rescuesim
