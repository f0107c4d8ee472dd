#pragma once
/// The ROS 1 bridge's simulation services, named and typed as gazebo_ros offers them (there
/// under /gazebo/, here at the root, as the ROS 2 Simulation Interfaces name theirs):
///
///   /reset_simulation   std_srvs/Empty    SimControl::reset(scope::kAll): back to the start, bitwise
///   /pause_physics      std_srvs/Empty    set_run_state(PAUSED); already paused is success
///   /unpause_physics    std_srvs/Empty    set_run_state(PLAYING); already playing is success
///   /step_simulation    std_srvs/Trigger  one step from PAUSED; `message` says the new sim time
///
/// ROS 1 has no standard step service (gazebo_ros has none); std_srvs/Trigger is in stock
/// Debian (python3-std-srvs gives rosservice its Python type), takes no arguments and answers
/// success plus a message, so `rosservice call /step_simulation` works with nothing but Debian
/// packages, and any ROS 1 client can call it without a package of ours. A refused step
/// (not paused) is `success: False` with the reason; the Empty services answer a refusal with
/// a service error carrying the reason (rosservice prints it).
///
/// Each call hands a closure to SimControl::post (bus/sim_control.h), which runs it on the
/// simulation thread at the next step boundary, and waits for its result at most a timeout (5 s
/// by default); a step waits for its StepJob's done(). The wait ends early, with an error, when
/// the bridge stops. The closures own what they share with the waiting call, so a call that gave
/// up leaves nothing dangling.
///
/// Messages travel as bytes (no generated std_srvs headers: Debian's need C++17's
/// std::allocator<void>::rebind, gone in C++20); the MD5s are std_srvs's, which rosservice checks.

#include <atomic>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "bus/bridge_host.h"
#include "bus/sim_control.h"

namespace ros {
class NodeHandle;
}

namespace rescuesim {

/// One of the services.
enum class SimService { reset, pause, unpause, step };

/// What a service is called and of which type.
struct SimServiceInfo {
  SimService which;
  const char* name;  ///< "/pause_physics"
  const char* type;  ///< "std_srvs/Empty"
  const char* md5;   ///< the service's MD5, as `rossrv md5` prints it
};

/// The four services, in the order of the table above.
const std::vector<SimServiceInfo>& sim_services();

/// A service's answer: success, and the text for the client (the new sim time after a step, or
/// why not).
struct SimServiceReply {
  bool ok = false;
  std::string message;
};

/// Runs service `which` on `control` (null: refused with control::kNoControl): posts the closure,
/// then waits up to `timeout` for its answer, giving up at once when `stopping` becomes true.
/// Thread-safe; blocks the calling thread (never the simulation).
SimServiceReply call_sim_service(control::SimControl* control, SimService which, std::chrono::milliseconds timeout,
                                 const std::atomic<bool>& stopping);

/// "12.345000000" (seconds with every nanosecond, as ROS prints time).
std::string sim_seconds(std::int64_t ns);

/// The services on a roscpp node, served by a thread of their own (a call waits for the
/// simulation, so it must not hold up the bridge's command callbacks).
class Ros1SimServices {
 public:
  /// `host.control()` is asked at each call (null: each call is refused with control::kNoControl).
  Ros1SimServices(BridgeHost& host, std::chrono::milliseconds timeout);
  ~Ros1SimServices();
  Ros1SimServices(const Ros1SimServices&) = delete;
  Ros1SimServices& operator=(const Ros1SimServices&) = delete;

  /// Advertises every service on `nh` (after ros::start()) and starts the serving thread.
  /// Throws ros::Exception as NodeHandle::advertiseService does.
  void advertise(ros::NodeHandle& nh);
  /// Tells the master (a new one, after an outage) about every service, through its API, as
  /// roscpp does when it advertises; false when the master does not answer.
  bool register_again();
  /// Ends the calls in progress (with an error), the serving thread and the services.
  void stop();
  std::size_t size() const { return sim_services().size(); }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rescuesim
