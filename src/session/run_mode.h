#pragma once
/// How a run is paced and who drives its robots, resolved once from the command-line flags and
/// the scenario (docs/architecture.md §2, "Modes"), for `rescuesim run` and anything else that
/// starts runs with bridges.
///
/// Precedence, first match wins:
///   1. contradictions are errors: --realtime with --sync, --realtime with --lockstep, and
///      --sync without a live bridge (nothing would answer its scans);
///   2. --sync → sync (lockstep, each laser scan waits for its cmd_vel);
///   3. --lockstep → lockstep;
///   4. --realtime, or a live bridge (ROS 1, ROS 2, Foxglove) → realtime;
///   5. otherwise the scenario's own `realtime:` setting (default lockstep).
/// Built-in controllers run unless --no-controllers, or a live bridge is attached without
/// --keep-controllers (then ROS drives the robots). A live bridge without --duration runs until
/// stopped.

#include <optional>

#include "import/scenario/scenario.h"
#include "session/session.h"

namespace rescuesim {

/// The flags and settings a run mode is resolved from.
struct RunModeRequest {
  bool scenario_realtime = false;  ///< the scenario's `realtime:` setting
  bool realtime = false;           ///< --realtime
  bool lockstep = false;           ///< --lockstep
  std::optional<double> sync;      ///< --sync[=SECONDS]: wall seconds to wait for a cmd_vel
  bool live_bridge = false;        ///< a ROS 1, ROS 2 or Foxglove bridge is attached
  bool no_controllers = false;     ///< --no-controllers
  bool keep_controllers = false;   ///< --keep-controllers
  bool duration_given = false;     ///< --duration was given
};

/// How the simulation is paced.
enum class Pacing {
  lockstep,  ///< as fast as possible, deterministic
  realtime,  ///< paced to the wall clock × rate
  sync,      ///< lockstep, waiting after each laser scan for the cmd_vel answering it
};

/// The resolved mode of a run.
struct RunMode {
  Pacing pacing = Pacing::lockstep;
  bool controllers = true;     ///< the scenario's built-in controllers drive the robots
  double sync_timeout = 0;     ///< s of wall time to wait for a cmd_vel (Pacing::sync only)
  bool until_stopped = false;  ///< run until Ctrl-C (duration infinite)
};

/// Resolves flags to a mode by the precedence above; throws Error naming the flags of a
/// contradiction.
RunMode resolve_run_mode(const RunModeRequest& request);

/// Writes a mode into a scenario (realtime, duration when until_stopped) and session options
/// (controllers, sync_timeout).
void apply_run_mode(const RunMode& mode, Scenario& scenario, SessionOptions& options);

/// "lockstep", "realtime" or "lockstep, synchronous with cmd_vel", as `rescuesim run` prints it.
const char* pacing_name(Pacing pacing);

}  // namespace rescuesim
