// The run's control surface on ROS 2: the services of the ROS 2 Simulation Interfaces, the
// SimulateSteps action, and node /rescuesim's six parameter services, on the bridge's
// ServiceRegistry. Every request is decoded on the bridge's receive thread (bridges/common/
// control_cdr.h), handed to the simulation thread (SimControl::post) and answered from there; a
// StepSimulation answers when its steps are done, a SimulateSteps goal reports feedback as it
// goes. Nothing here waits: a client that vanishes leaves a reply nobody reads.

#include "bridges/ros2/control_services.h"

#include <algorithm>
#include <memory>

#include "bridges/common/cdr_stream.h"
#include "bridges/common/control_cdr.h"
#include "core/log.h"
#include "core/throttle.h"

namespace rescuesim::ros2 {

namespace {

using control::SimControl;
using control::WireVersion;
namespace iface = control::iface;

/// What every handler shares: the control surface, the wire version, the warning throttle.
struct Context {
  SimControl* control = nullptr;
  WireVersion version = WireVersion::v1;
  Throttle warning;
  std::atomic<std::uint64_t> undecodable{0};
};

/// `/<ns>/<name>` with one slash between the parts ("/" + "reset_simulation" -> "/reset_simulation").
std::string join(const std::string& ns, const std::string& name) {
  std::string base = ns.empty() ? "/" : ns;
  if (base.front() != '/') base.insert(base.begin(), '/');
  if (base.back() != '/') base += '/';
  return base + name;
}

/// A response that says `result` when the type has a Result (the others have nothing to say it with).
template <class S>
std::optional<typename S::Response> failure(const control::Result& r) {
  typename S::Response response{};
  if constexpr (std::is_same_v<typename S::Response, control::Result>) {
    return r;
  } else if constexpr (requires { response.result = r; }) {
    response.result = r;
    return response;
  } else {
    return std::nullopt;
  }
}

template <class S>
void reply(const ReplyHandle& handle, const typename S::Response& response, WireVersion version) {
  std::vector<std::uint8_t> bytes;
  control::encode_response<S>(response, version, bytes);
  handle.send(bytes);
}

/// Registers service S under `name`: `compute(request, control)` runs on the simulation thread and
/// returns the response. A request that does not decode is answered with OPERATION_FAILED and the
/// decoder's words where the response has a Result, and dropped otherwise; either way it is counted.
template <class S, class F>
void serve(ServiceRegistry& registry, const std::shared_ptr<Context>& ctx, const std::string& name, F compute) {
  const control::InterfaceInfo& info = control::info(S::id);
  registry.add_service(
      name, info.ros_type, [ctx, name, compute](const RequestHeader&, std::span<const std::uint8_t> body, ReplyHandle handle) {
        auto decoded = control::decode_request<S>(body, ctx->version);
        if (!decoded.value) {
          ++ctx->undecodable;
          std::uint64_t held = 0;
          if (ctx->warning.allow(&held)) {
            log::warn("ROS 2 bridge: {}: malformed request: {} ({} more held back)", name, decoded.problem, held);
          }
          if (auto r = failure<S>(control::Result::fail(control::code::kOperationFailed, "malformed request: " + decoded.problem))) {
            reply<S>(handle, *r, ctx->version);
          }
          return;
        }
        const bool posted = ctx->control->post([ctx, handle, compute, request = std::move(*decoded.value)](SimControl& c) {
          reply<S>(handle, compute(request, c), ctx->version);
        });
        if (!posted) {
          if (auto r = failure<S>(
                  control::Result::fail(control::code::kOperationFailed,
                                        "the simulation takes no requests now (the run has ended, or too many requests wait)"))) {
            reply<S>(handle, *r, ctx->version);
          }
        }
      });
}

/// StepSimulation: answered when its steps are done (or refused at once).
void serve_step(ServiceRegistry& registry, const std::shared_ptr<Context>& ctx, const std::string& name) {
  using S = iface::StepSimulation;
  registry.add_service(
      name, control::info(S::id).ros_type,
      [ctx, name](const RequestHeader&, std::span<const std::uint8_t> body, const ReplyHandle& handle) {
        auto decoded = control::decode_request<S>(body, ctx->version);
        if (!decoded.value) {
          ++ctx->undecodable;
          reply<S>(handle, control::Result::fail(control::code::kOperationFailed, "malformed request: " + decoded.problem), ctx->version);
          return;
        }
        const std::uint64_t steps = decoded.value->steps;
        const bool posted = ctx->control->post([ctx, handle, steps](SimControl& c) {
          control::StepJob job;
          job.steps = steps;
          job.done = [ctx, handle](const control::Result& r, std::uint64_t) { reply<S>(handle, r, ctx->version); };
          const control::Result r = c.start_steps(std::move(job), false);
          if (!r.is_ok()) reply<S>(handle, r, ctx->version);
        });
        if (!posted) {
          reply<S>(handle, control::Result::fail(control::code::kOperationFailed, "the simulation takes no requests now"), ctx->version);
        }
      });
}

/// `<A>_Feedback` {uint64 completed_steps, uint64 remaining_steps} as a CDR message.
std::vector<std::uint8_t> feedback_body(std::uint64_t completed, std::uint64_t remaining) {
  std::vector<std::uint8_t> out;
  cdr::Writer w(out, "simulation_interfaces/action/SimulateSteps_Feedback");
  w.value("completed_steps", completed);
  w.value("remaining_steps", remaining);
  return out;
}

std::vector<std::uint8_t> result_response(std::int8_t status, const control::Result& r, WireVersion v) {
  std::vector<std::uint8_t> out;
  control::encode_response<iface::SimulateStepsGetResult>(control::GetResultResponse{status, r}, v, out);
  return out;
}

/// The SimulateSteps action: a goal runs as a stepping job from PAUSED, with feedback every
/// `feedback_every` steps; cancel ends the job.
void serve_simulate_steps(ServiceRegistry& registry, const std::shared_ptr<Context>& ctx, const std::string& name) {
  ActionCallbacks cb;
  cb.unknown_result_response =
      result_response(control::goal_status::kUnknown, control::Result::fail(control::code::kNotFound, "unknown goal"), ctx->version);
  cb.on_goal = [ctx](GoalHandle goal) {
    std::uint64_t steps = 0;
    try {
      cdr::Reader r(goal.goal(), "simulation_interfaces/action/SimulateSteps_Goal");
      r.value("steps", steps);
      r.finish();
    } catch (const std::exception& e) {
      ++ctx->undecodable;
      goal.reject();
      return;
    }
    const bool posted = ctx->control->post([ctx, goal, steps](SimControl& c) mutable {
      // accepted only when it can run (PAUSED): otherwise rejected, as rclcpp servers reject
      // goals they cannot take
      control::StepJob job;
      job.steps = steps;
      job.feedback_every = std::max<std::uint64_t>(1, steps / 100);  // about a hundred reports, and the last
      job.feedback = [goal](std::uint64_t done, std::uint64_t left) mutable { goal.publish_feedback(feedback_body(done, left)); };
      job.done = [ctx, goal](const control::Result& r, std::uint64_t) mutable {
        if (r.is_ok()) {
          goal.succeed(result_response(control::goal_status::kSucceeded, r, ctx->version));
        } else if (goal.is_canceling()) {
          goal.canceled(result_response(control::goal_status::kCanceled, r, ctx->version));
        } else {
          goal.abort(result_response(control::goal_status::kAborted, r, ctx->version));
        }
      };
      if (c.run_state() != control::RunState::paused && c.run_state() != control::RunState::stopped) {
        goal.reject();
        return;
      }
      goal.accept();
      const control::Result r = c.start_steps(std::move(job), true);
      if (!r.is_ok()) goal.abort(result_response(control::goal_status::kAborted, r, ctx->version));
    });
    if (!posted) goal.reject();
  };
  cb.on_cancel = [ctx](GoalHandle) {
    // the job ends at the next step boundary; its done() sees the goal CANCELING and says CANCELED
    return ctx->control->post([](SimControl& c) { c.cancel_steps(); });
  };
  registry.add_action(name, "simulation_interfaces/action/SimulateSteps", std::move(cb));
}

/// The parameter services of node `node` (rclcpp's: ListParameters, GetParameters, ...).
void serve_parameters(ServiceRegistry& registry, const std::shared_ptr<Context>& ctx, const std::string& node) {
  serve<iface::ListParameters>(registry, ctx, join(node, "list_parameters"), [](const control::ListParametersRequest& q, SimControl& c) {
    control::ListParametersResult out;
    for (const auto& d : c.parameter_descriptors()) {
      const bool wanted = q.prefixes.empty() || std::any_of(q.prefixes.begin(), q.prefixes.end(), [&](const std::string& p) {
                            return d.name == p || d.name.starts_with(p + ".");
                          });
      if (wanted) out.names.push_back(d.name);  // every name is flat: no prefixes to report
    }
    return out;
  });
  serve<iface::GetParameters>(registry, ctx, join(node, "get_parameters"), [](const control::ParameterNames& q, SimControl& c) {
    control::GetParametersResponse out;
    for (const auto& n : q.names) out.values.push_back(c.parameter(n));
    return out;
  });
  serve<iface::GetParameterTypes>(registry, ctx, join(node, "get_parameter_types"), [](const control::ParameterNames& q, SimControl& c) {
    control::GetParameterTypesResponse out;
    for (const auto& n : q.names) out.types.push_back(c.parameter(n).type);
    return out;
  });
  serve<iface::DescribeParameters>(registry, ctx, join(node, "describe_parameters"), [](const control::ParameterNames& q, SimControl& c) {
    control::DescribeParametersResponse out;
    const auto all = c.parameter_descriptors();
    for (const auto& n : q.names) {
      const auto d = std::find_if(all.begin(), all.end(), [&](const control::ParameterDescriptor& x) { return x.name == n; });
      control::ParameterDescriptorMessage m;
      if (d != all.end()) {
        m = control::descriptor_message(*d);
      } else {
        m.name = n;  // NOT_SET, as rclcpp describes an undeclared name when undeclared ones are allowed
      }
      out.descriptors.push_back(std::move(m));
    }
    return out;
  });
  serve<iface::SetParameters>(registry, ctx, join(node, "set_parameters"), [](const control::SetParametersRequest& q, SimControl& c) {
    control::SetParametersResponse out;
    for (const auto& p : q.parameters) out.results.push_back(c.set_parameter(p));
    return out;
  });
  serve<iface::SetParametersAtomically>(registry, ctx, join(node, "set_parameters_atomically"),
                                        [](const control::SetParametersRequest& q, SimControl& c) {
                                          // all or none: check every one against a copy of the values first
                                          std::vector<control::Parameter> before;
                                          for (const auto& p : q.parameters) before.push_back({p.name, c.parameter(p.name)});
                                          for (std::size_t i = 0; i < q.parameters.size(); ++i) {
                                            const control::SetParameterResult r = c.set_parameter(q.parameters[i]);
                                            if (!r.successful) {
                                              for (std::size_t k = 0; k < i; ++k) c.set_parameter(before[k]);
                                              return control::SetParameterResult{false, r.reason};
                                            }
                                          }
                                          return control::SetParameterResult{true, ""};
                                        });
}

}  // namespace

std::function<std::uint64_t()> register_control_services(ServiceRegistry& services, BridgeHost& host, const Ros2Options& options) {
  control::SimControl* c = host.control();
  if (!c) return [] { return std::uint64_t{0}; };  // a replay: nothing to control, nothing offered
  auto ctx = std::make_shared<Context>();
  ctx->control = c;
  ctx->version = options.sim_interfaces_v2 ? WireVersion::v2 : WireVersion::v1;
  const std::string& ns = options.sim_services_ns;
  using R = control::Result;

  serve<iface::GetSimulatorFeatures>(services, ctx, join(ns, "get_simulator_features"),
                                     [](const control::Empty&, SimControl& s) { return s.features(); });
  serve<iface::ResetSimulation>(services, ctx, join(ns, "reset_simulation"),
                                [](const control::ResetSimulationRequest& q, SimControl& s) { return s.reset(q.scope); });
  serve<iface::GetSimulationState>(services, ctx, join(ns, "get_simulation_state"), [](const control::Empty&, SimControl& s) {
    return control::GetSimulationStateResponse{s.run_state(), R::ok()};
  });
  serve<iface::SetSimulationState>(services, ctx, join(ns, "set_simulation_state"),
                                   [](const control::SetSimulationStateRequest& q, SimControl& s) { return s.set_run_state(q.state); });
  serve_step(services, ctx, join(ns, "step_simulation"));
  serve<iface::GetEntities>(services, ctx, join(ns, "get_entities"), [](const control::EntityFilters& f, SimControl& s) {
    control::GetEntitiesResponse out;
    out.result = s.entities(f, out.entities);
    return out;
  });
  serve<iface::GetEntityState>(services, ctx, join(ns, "get_entity_state"), [](const control::EntityRequest& q, SimControl& s) {
    control::GetEntityStateResponse out;
    out.result = s.entity_state(q.entity, out.state);
    return out;
  });
  serve<iface::GetEntitiesStates>(services, ctx, join(ns, "get_entities_states"), [](const control::EntityFilters& f, SimControl& s) {
    control::GetEntitiesStatesResponse out;
    out.result = s.entities(f, out.entities);
    for (const auto& n : out.entities) {
      control::EntityState st;
      s.entity_state(n, st);
      out.states.push_back(std::move(st));
    }
    return out;
  });
  serve<iface::SetEntityState>(services, ctx, join(ns, "set_entity_state"), [](const control::SetEntityStateRequest& q, SimControl& s) {
    return s.set_entity_state(q.entity, q.state, q.set_pose, q.set_twist, q.set_acceleration);
  });
  serve<iface::GetEntityInfo>(services, ctx, join(ns, "get_entity_info"), [](const control::EntityRequest& q, SimControl& s) {
    control::GetEntityInfoResponse out;
    out.result = s.entity_info(q.entity, out.info);
    return out;
  });
  serve<iface::GetEntityBounds>(services, ctx, join(ns, "get_entity_bounds"), [](const control::EntityRequest& q, SimControl& s) {
    control::BoundsResponse out;
    out.result = s.entity_bounds(q.entity, out.bounds);
    return out;
  });
  serve<iface::GetNamedPoses>(services, ctx, join(ns, "get_named_poses"), [](const control::TagsFilter& t, SimControl& s) {
    control::GetNamedPosesResponse out;
    out.result = s.named_poses(t, out.poses);
    return out;
  });
  serve<iface::GetNamedPoseBounds>(services, ctx, join(ns, "get_named_pose_bounds"),
                                   [](const control::NamedPoseBoundsRequest& q, SimControl& s) {
                                     control::BoundsResponse out;
                                     out.result = s.named_pose_bounds(q.name, out.bounds);
                                     return out;
                                   });
  serve<iface::GetSpawnables>(services, ctx, join(ns, "get_spawnables"), [](const control::GetSpawnablesRequest& q, SimControl& s) {
    control::GetSpawnablesResponse out;
    out.result = s.spawnables(q.sources, out.spawnables);
    return out;
  });
  serve<iface::SpawnEntity>(services, ctx, join(ns, "spawn_entity"), [](const control::SpawnRequest& q, SimControl& s) {
    control::SpawnEntityResponse out;
    out.result = s.spawn(q, out.entity_name);
    return out;
  });
  serve<iface::DeleteEntity>(services, ctx, join(ns, "delete_entity"),
                             [](const control::EntityRequest& q, SimControl& s) { return s.remove(q.entity); });
  serve<iface::GetAvailableWorlds>(services, ctx, join(ns, "get_available_worlds"),
                                   [](const control::GetAvailableWorldsRequest& q, SimControl& s) {
                                     control::GetAvailableWorldsResponse out;
                                     out.result = s.available_worlds(q.additional_sources, out.worlds);
                                     return out;
                                   });
  serve<iface::GetCurrentWorld>(services, ctx, join(ns, "get_current_world"), [](const control::Empty&, SimControl& s) {
    control::WorldResponse out;
    out.result = s.current_world(out.world);
    return out;
  });
  serve<iface::LoadWorld>(services, ctx, join(ns, "load_world"), [](const control::LoadWorldRequest& q, SimControl& s) {
    control::WorldResponse out;
    control::WorldResource want;
    want.uri = q.uri;
    want.resource_string = q.resource_string;
    out.result = s.load_world(want, out.world);
    return out;
  });
  serve<iface::UnloadWorld>(services, ctx, join(ns, "unload_world"), [](const control::Empty&, SimControl& s) { return s.unload_world(); });
  serve_simulate_steps(services, ctx, join(ns, "simulate_steps"));

  const std::string node = join(options.node_namespace, options.node_name);
  serve_parameters(services, ctx, node);
  log::info("ROS 2 bridge: {} simulation control services and actions under {} (Simulation Interfaces {}), parameters of {}",
            services.size(), ns.empty() ? "/" : ns, options.sim_interfaces_v2 ? "2.x" : "1.x", node);
  return [ctx] { return ctx->undecodable.load(); };
}

}  // namespace rescuesim::ros2
