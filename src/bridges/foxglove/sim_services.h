#pragma once
/// The ROS 2 Simulation Interfaces (bus/sim_control.h) as services of the Foxglove WebSocket
/// protocol, in the `json` encoding, so that Foxglove's Service Call panel resets, pauses,
/// steps a run and spawns and deletes robots in it: the services advertised (root-level ROS 2 names and types, with JSON Schemas of
/// their requests and responses), the decoding of a request, what it does on the simulation
/// thread, and the encoding of the response. Field names are the standard's
/// (ros-simulation/simulation_interfaces `srv/*.srv`, `msg/*.msg`); the panel sends what its user
/// types, `{"state": {"state": 2}}` for SetSimulationState.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "bridges/foxglove/protocol.h"
#include "bus/sim_control.h"

namespace rescuesim::foxglove {

/// The operations offered, in advertisement order (service id = index + 1).
enum class SimService : std::uint8_t {
  reset_simulation,
  get_simulation_state,
  set_simulation_state,
  step_simulation,
  get_entities,
  get_entity_state,
  set_entity_state,
  get_simulator_features,
  spawn_entity,
  delete_entity,
};
inline constexpr std::size_t kSimServiceCount = 10;

/// The advertised services, one per SimService in order, with ids 1..kSimServiceCount: name
/// "/reset_simulation", type "simulation_interfaces/srv/ResetSimulation", request and response
/// in `json` with a `jsonschema` schema named "<type>_Request" / "<type>_Response".
const std::vector<Service>& sim_services();
/// The service an advertised id names, or nullopt.
std::optional<SimService> sim_service_of(std::uint32_t id);
/// The service's name ("/step_simulation").
const std::string& sim_service_name(SimService s);

/// Decoded requests, one alternative per SimService in the same order.
struct ResetRequest {
  std::uint8_t scope = control::scope::kDefault;  ///< ResetSimulation.scope, a bit field
};
struct GetSimulationStateRequest {};
struct SetSimulationStateRequest {
  control::RunState state = control::RunState::playing;
};
struct StepRequest {
  std::uint64_t steps = 1;  ///< the standard's default
};
struct GetEntitiesRequest {
  control::EntityFilters filters;
};
struct GetEntityStateRequest {
  std::string entity;
};
/// SetEntityState: without any of the 2.x flags (a 1.x request), what `state` holds is set
/// (pose if it has "pose", twist if "twist", acceleration if "acceleration"); with a flag, the
/// flags say (a flag left out is false), as in 2.x.
struct SetEntityStateRequest {
  std::string entity;
  control::EntityState state;
  bool set_pose = false, set_twist = false, set_acceleration = false;
};
struct GetSimulatorFeaturesRequest {};
/// SpawnEntity: the 1.x fields (uri, resource_string) or 2.x's `resource: {uri, resource_string}`;
/// initial_pose is a PoseStamped (its header.frame_id: the world, or an entity).
struct SpawnEntityRequest {
  control::SpawnRequest spawn;
};
struct DeleteEntityRequest {
  std::string entity;
};
using SimRequest = std::variant<ResetRequest, GetSimulationStateRequest, SetSimulationStateRequest, StepRequest,
                                GetEntitiesRequest, GetEntityStateRequest, SetEntityStateRequest, GetSimulatorFeaturesRequest,
                                SpawnEntityRequest, DeleteEntityRequest>;

/// Decodes a request of `s` from its JSON payload (an object; an empty payload reads as `{}`).
/// Throws rescuesim::Error naming the service and the field ("/set_simulation_state:
/// state.state: expected an integer 0..5 (a SimulationState), got \"paused\""); keys that are no
/// field of the request are errors too. Values are not judged here (an unknown entity, a
/// non-unit quaternion: SimControl answers those with a Result); null in a float field is NaN.
SimRequest decode_sim_request(SimService s, std::span<const std::uint8_t> payload);

/// What a call answered: the fields of the service's response that it has.
struct SimResponse {
  SimService service = SimService::get_simulator_features;
  control::Result result;
  control::RunState state = control::RunState::stopped;  ///< get_simulation_state
  std::vector<std::string> entities;                     ///< get_entities
  control::EntityState entity_state;                     ///< get_entity_state
  control::SimulatorFeatures features;                   ///< get_simulator_features
  std::string entity_name;                               ///< spawn_entity: the name it got
};

/// The response's JSON text with the standard's field names (`result: {result, error_message}`,
/// stamps as `{sec, nanosec}`); a response without a Result field (GetSimulatorFeatures) has
/// none.
std::string encode_sim_response(const SimResponse& response);

/// Runs `request` on `control`; on the simulation thread (inside a posted task). `reply` is
/// called once, on that thread: at once, or for a StepSimulation that was accepted, when its
/// steps have run (a later step boundary).
void run_sim_request(const SimRequest& request, control::SimControl& control, std::function<void(SimResponse)> reply);

}  // namespace rescuesim::foxglove
