// Service calls (capability `services`, binary 0x02): the Simulation Interfaces operations of
// sim_services.h. Nobody waits on anybody:
//   - the I/O thread checks a call (service id, encoding, the request's JSON) and hands
//     SimControl a closure (post), then goes on serving;
//   - the closure runs on the simulation thread at a step boundary, calls the control methods
//     and hands the response back to the I/O thread (WsServer::post) through the ServiceLink;
//     a StepSimulation answers from its job's done(), after its steps;
//   - the I/O thread sends the response to the client if it is still connected, and drops it
//     silently otherwise.
// Whatever is wrong with a call is answered with a serviceCallFailure naming it, and counted.

#include <atomic>
#include <memory>

#include "bridges/foxglove/bridge_impl.h"
#include "core/error.h"
#include "core/log.h"

namespace rescuesim::foxglove {

namespace {

/// A call between its hand-over to SimControl and its answer, shared by the closures that may
/// answer it. The first answer wins; a call never answered (SimControl destroyed its closure
/// unrun, as a run ends) is answered with a failure when the last closure goes.
class PendingCall {
 public:
  PendingCall(std::shared_ptr<ServiceLink> link, ClientId client, std::uint32_t service, std::uint32_t call, std::string name)
      : link_(std::move(link)), client_(client), service_(service), call_(call), name_(std::move(name)) {}
  ~PendingCall() { fail(name_ + ": the run ended before it could answer"); }
  PendingCall(const PendingCall&) = delete;
  PendingCall& operator=(const PendingCall&) = delete;

  void answer(SimResponse response) {
    if (answered_.exchange(true)) return;
    deliver({client_, service_, call_, std::move(response), {}});
  }
  void fail(std::string why) {
    if (answered_.exchange(true)) return;
    deliver({client_, service_, call_, std::nullopt, std::move(why)});
  }

 private:
  /// To the I/O thread, while the bridge runs; otherwise nowhere.
  void deliver(CallAnswer answer) {
    std::lock_guard lock(link_->mutex);
    if (!link_->server || !link_->finish) return;
    link_->server->post([finish = link_->finish, answer = std::move(answer)]() mutable { finish(std::move(answer)); });
  }

  std::shared_ptr<ServiceLink> link_;
  ClientId client_;
  std::uint32_t service_, call_;
  std::string name_;
  std::atomic<bool> answered_{false};
};

/// A client's string as a message shows it: at most 40 characters, control characters blanked.
std::string shown(std::string_view s) {
  std::string out(s.substr(0, 40));
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
  }
  return s.size() > 40 ? out + "..." : out;
}

/// "1 /reset_simulation, 2 /get_simulation_state, ...".
std::string offered() {
  std::string list;
  for (const Service& s : sim_services()) list += (list.empty() ? "" : ", ") + std::to_string(s.id) + " " + s.name;
  return list;
}

}  // namespace

void FoxgloveBridge::service_call(ClientId client, const ServiceCallRequest& r) {
  if (!control_) return fail_call(client, r.service, r.call, std::string("no services: ") + control::kNoControl);
  const std::optional<SimService> service = sim_service_of(r.service);
  if (!service) {
    return fail_call(client, r.service, r.call, "unknown service id " + std::to_string(r.service) + " (offered: " + offered() + ")");
  }
  const std::string& name = sim_service_name(*service);
  if (r.encoding != "json") {
    return fail_call(client, r.service, r.call, name + ": encoding '" + shown(r.encoding) + "' is not supported (its requests are json)");
  }
  SimRequest request;
  try {
    request = decode_sim_request(*service, r.payload);
  } catch (const Error& e) {
    return fail_call(client, r.service, r.call, e.message());
  }
  bool full = false;
  {
    std::lock_guard lock(mutex_);
    const auto it = clients_.find(client);
    if (it == clients_.end()) return;
    full = it->second.calls_in_flight >= kMaxCallsInFlight;
    if (!full) ++it->second.calls_in_flight;
  }
  if (full) {
    return fail_call(client, r.service, r.call,
                     name + ": " + std::to_string(kMaxCallsInFlight) +
                         " calls of this connection are waiting for the simulation already; wait for their answers");
  }
  auto call = std::make_shared<PendingCall>(link_, client, r.service, r.call, name);
  const bool posted = control_->post([call, request = std::move(request)](control::SimControl& c) {
    run_sim_request(request, c, [call](SimResponse response) { call->answer(std::move(response)); });
  });
  if (!posted) {
    call->fail(name + ": the simulation takes no requests now (the run has ended, or " + std::to_string(control::SimControl::kMaxPosted) +
               " requests are waiting)");
  }
}

void FoxgloveBridge::fail_call(ClientId client, std::uint32_t service, std::uint32_t call, const std::string& message) {
  ++rejected_;
  server_->send_status(client, service_call_failure(service, call, message));
  std::uint64_t held = 0;
  if (client_log_.allow(&held)) log::info("foxglove: client {}: service call {} failed: {}", client, call, message);
}

void FoxgloveBridge::finish_call(CallAnswer answer) {
  {
    std::lock_guard lock(mutex_);
    const auto it = clients_.find(answer.client);
    if (it == clients_.end()) return;  // disconnected meanwhile: nobody to answer
    if (it->second.calls_in_flight > 0) --it->second.calls_in_flight;
  }
  if (!answer.response) return fail_call(answer.client, answer.service, answer.call, answer.failure);
  ++received_;
  server_->send_reply(answer.client, service_call_response(answer.service, answer.call, "json", encode_sim_response(*answer.response)));
}

}  // namespace rescuesim::foxglove
