// The simulation services on roscpp: raw bytes in and out, a closure posted to the simulation
// thread per call, and a bounded wait for its answer on a thread of their own.

#include "bridges/ros1/ros1_sim_services.h"

#include <ros/advertise_service_options.h>
#include <ros/callback_queue.h>
#include <ros/connection_manager.h>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/node_handle.h>
#include <ros/serialization.h>
#include <ros/service_callback_helper.h>
#include <ros/service_server.h>
#include <ros/this_node.h>
#include <ros/xmlrpc_manager.h>

#include <fmt/format.h>

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

#include "bridges/ros1/ros1_raw_message.h"
#include "core/thread.h"

namespace rescuesim {

namespace {

using Clock = std::chrono::steady_clock;

// a service's MD5 is that of its request's text followed by its response's (genmsg)
constexpr const char* kEmptyMd5 = "d41d8cd98f00b204e9800998ecf8427e";    ///< std_srvs/Empty: MD5 of "" (no fields)
constexpr const char* kTriggerMd5 = "937c9679a518e3a18d831e57125ea522";  ///< std_srvs/Trigger: MD5 of "bool success\nstring message"

/// The name of a simulation_interfaces result code (`set_state`: SetSimulationState's own codes).
std::string code_name(std::uint8_t code, bool set_state) {
  namespace c = control::code;
  switch (code) {
    case c::kFeatureUnsupported: return "FEATURE_UNSUPPORTED";
    case c::kOk: return "OK";
    case c::kNotFound: return "NOT_FOUND";
    case c::kIncorrectState: return "INCORRECT_STATE";
    case c::kOperationFailed: return "OPERATION_FAILED";
    default: break;
  }
  if (set_state) {
    switch (code) {
      case c::kAlreadyInTargetState: return "ALREADY_IN_TARGET_STATE";
      case c::kStateTransitionError: return "STATE_TRANSITION_ERROR";
      case c::kIncorrectTransition: return "INCORRECT_TRANSITION";
      default: break;
    }
  }
  return std::to_string(code);
}

/// "<why> (OPERATION_FAILED)".
std::string describe(const control::Result& r, bool set_state = false) {
  return fmt::format("{} ({})", r.error_message.empty() ? "refused" : r.error_message, code_name(r.result, set_state));
}

/// What a call waits on, shared with the closure that answers it (which may outlive the call).
struct Pending {
  std::mutex mutex;
  std::condition_variable cv;
  bool done = false;
  SimServiceReply reply;

  /// The first answer counts.
  void finish(bool ok, std::string message) {
    {
      std::lock_guard lock(mutex);
      if (done) return;
      done = true;
      reply = {ok, std::move(message)};
    }
    cv.notify_all();
  }
};

/// The work of one call, on the simulation thread.
void serve(control::SimControl& c, SimService which, const std::shared_ptr<Pending>& pending) {
  switch (which) {
    case SimService::reset: {
      const control::Result r = c.reset(control::scope::kAll);
      pending->finish(r.is_ok(), r.is_ok() ? "reset; sim time " + sim_seconds(c.time_ns()) + " s" : describe(r));
      break;
    }
    case SimService::pause:
    case SimService::unpause: {
      const bool pause = which == SimService::pause;
      const control::Result r = c.set_run_state(pause ? control::RunState::paused : control::RunState::playing);
      // gazebo_ros answers a pause of a paused world with success: so do we
      const bool already = r.result == control::code::kAlreadyInTargetState;
      pending->finish(r.is_ok() || already, r.is_ok() || already ? std::string(already ? "already " : "") + (pause ? "paused" : "playing")
                                                                 : describe(r, true));
      break;
    }
    case SimService::step: {
      control::StepJob job;
      job.steps = 1;
      control::SimControl* control = &c;  // done() is called by this SimControl, on its thread
      job.done = [pending, control](const control::Result& r, std::uint64_t completed) {
        pending->finish(r.is_ok(), r.is_ok() ? fmt::format("stepped {} step; sim time {} s", completed, sim_seconds(control->time_ns()))
                                             : fmt::format("{} after {} of 1 steps", describe(r), completed));
      };
      const control::Result r = c.start_steps(std::move(job), false);
      if (!r.is_ok()) pending->finish(false, describe(r));
      break;
    }
  }
}

}  // namespace

const std::vector<SimServiceInfo>& sim_services() {
  static const std::vector<SimServiceInfo> services = {
      {SimService::reset, "/reset_simulation", "std_srvs/Empty", kEmptyMd5},
      {SimService::pause, "/pause_physics", "std_srvs/Empty", kEmptyMd5},
      {SimService::unpause, "/unpause_physics", "std_srvs/Empty", kEmptyMd5},
      {SimService::step, "/step_simulation", "std_srvs/Trigger", kTriggerMd5},
  };
  return services;
}

std::string sim_seconds(std::int64_t ns) {
  const SimTime t{ns};
  return fmt::format("{}.{:09d}", t.sec_part(), t.nsec_part());
}

SimServiceReply call_sim_service(control::SimControl* control, SimService which, std::chrono::milliseconds timeout,
                                 const std::atomic<bool>& stopping) {
  if (control == nullptr) return {false, control::kNoControl};
  auto pending = std::make_shared<Pending>();
  const bool posted = control->post([which, pending](control::SimControl& c) {
    // a failure of the control surface is the client's answer, never the simulation thread's end
    try {
      serve(c, which, pending);
    } catch (const std::exception& e) {
      pending->finish(false, std::string("failed: ") + e.what());
    }
  });
  if (!posted) {
    return {false, fmt::format("the simulation takes no more requests (the run has ended, or {} requests wait already)",
                               control::SimControl::kMaxPosted)};
  }
  // the answer comes at the simulation's next step boundary; wait for it, but not forever
  const auto deadline = Clock::now() + timeout;
  std::unique_lock lock(pending->mutex);
  while (!pending->done) {
    if (stopping.load()) return {false, "rescuesim's ROS 1 bridge is stopping"};
    const auto now = Clock::now();
    if (now >= deadline) {
      return {false, fmt::format("no answer from the simulation within {:g} s; the request stays queued and takes effect at its next "
                                 "step boundary",
                                 std::chrono::duration<double>(timeout).count())};
    }
    pending->cv.wait_until(lock, std::min(deadline, now + std::chrono::milliseconds(50)));
  }
  return pending->reply;
}

namespace {

/// A service of raw bytes: the requests of Empty and Trigger have no fields, so only the answer
/// is built: Empty's (nothing), Trigger's (bool success, string message), or an error.
class RawServiceHelper final : public ros::ServiceCallbackHelper {
 public:
  RawServiceHelper(std::function<SimServiceReply()> serve, bool trigger) : serve_(std::move(serve)), trigger_(trigger) {}

  bool call(ros::ServiceCallbackHelperCallParams& params) override {
    namespace ser = ros::serialization;
    const SimServiceReply reply = serve_();
    if (trigger_) {
      ros1_wire::RawMessage body;
      const auto n = static_cast<std::uint32_t>(reply.message.size());
      body.bytes.push_back(reply.ok ? 1 : 0);
      for (int i = 0; i < 4; ++i) body.bytes.push_back(static_cast<std::uint8_t>(n >> (8 * i)));
      body.bytes.insert(body.bytes.end(), reply.message.begin(), reply.message.end());
      params.response = ser::serializeServiceResponse(true, body);
    } else if (reply.ok) {
      params.response = ser::serializeServiceResponse(true, ros1_wire::RawMessage{});
    } else {
      // the error answer of the TCPROS service protocol (ok byte 0, then the reason as a string),
      // which clients show ("responded with an error: ..."); roscpp sends the same for a callback
      // that throws, but with an error line in our log for a client's refused request
      params.response = ser::serializeServiceResponse(false, reply.message);
    }
    return true;
  }

 private:
  std::function<SimServiceReply()> serve_;
  bool trigger_;
};

}  // namespace

struct Ros1SimServices::Impl {
  Impl(BridgeHost& h, std::chrono::milliseconds t) : host(h), timeout(t) {}

  BridgeHost& host;
  std::chrono::milliseconds timeout;
  ros::CallbackQueue queue;
  std::vector<ros::ServiceServer> servers;
  std::thread thread;
  std::atomic<bool> stopping{false};
};

Ros1SimServices::Ros1SimServices(BridgeHost& host, std::chrono::milliseconds timeout) : impl_(std::make_unique<Impl>(host, timeout)) {}

Ros1SimServices::~Ros1SimServices() { stop(); }

void Ros1SimServices::advertise(ros::NodeHandle& nh) {
  Impl* impl = impl_.get();
  for (const SimServiceInfo& s : sim_services()) {
    ros::AdvertiseServiceOptions ops;
    ops.service = s.name;
    ops.md5sum = s.md5;
    ops.datatype = s.type;
    ops.req_datatype = std::string(s.type) + "Request";
    ops.res_datatype = std::string(s.type) + "Response";
    const SimService which = s.which;
    ops.helper = boost::make_shared<RawServiceHelper>(
        [impl, which] { return call_sim_service(impl->host.control(), which, impl->timeout, impl->stopping); }, which == SimService::step);
    ops.callback_queue = &impl->queue;
    impl->servers.push_back(nh.advertiseService(ops));
  }
  impl->thread = start_named_thread("ros1-services", [impl] {
    while (!impl->stopping.load()) impl->queue.callAvailable(ros::WallDuration(0.05));
  });
}

bool Ros1SimServices::register_again() {
  // what ServiceManager::advertiseService tells the master
  const std::string service_api =
      "rosrpc://" + ros::network::getHost() + ":" + std::to_string(ros::ConnectionManager::instance()->getTCPPort());
  for (const SimServiceInfo& s : sim_services()) {
    XmlRpc::XmlRpcValue args, result, payload;
    args[0] = ros::this_node::getName();
    args[1] = s.name;
    args[2] = service_api;
    args[3] = ros::XMLRPCManager::instance()->getServerURI();
    if (!ros::master::execute("registerService", args, result, payload, false)) return false;
  }
  return true;
}

void Ros1SimServices::stop() {
  if (!impl_) return;
  impl_->stopping = true;
  if (impl_->thread.joinable()) impl_->thread.join();
  for (ros::ServiceServer& s : impl_->servers) s.shutdown();
  impl_->servers.clear();
}

}  // namespace rescuesim
