#pragma once
/// The CDR bodies of the control interfaces (bus/sim_control.h) as ROS 2 puts them on the wire:
/// the services of the ROS 2 Simulation Interfaces, the SimulateSteps action (and the action_msgs
/// parts every action has), and the six rcl_interfaces parameter services. Each codec turns a
/// plain CDR message (encapsulation 00 01 00 00 + body; conventions in bridges/common/cdr_stream.h)
/// into the plain structs of rescuesim::control and back. A transport strips or prepends
/// rmw_cyclonedds's 16-byte request header (guid, seq) itself: the codecs never see it. Values
/// are not judged here (a NaN pose passes through; the control layer answers INVALID_POSE).
///
/// Per interface S (a tag in control::iface, listed in AllServices / AllMessages), four functions:
///   decode_request<S>(bytes, version)  -> Decoded<S::Request>     (a server)
///   encode_response<S>(resp, version, out)                        (a server)
///   encode_request<S>(req, version, out), decode_response<S>(bytes, version)  (a client, the bench)
/// and for the two topics of an action, encode_message<S> / decode_message<S>. Encoders append
/// to `out` (the encapsulation header, then the body; never padded) and throw rescuesim::Error
/// only for a sequence longer than a uint32 count or than its bound. interfaces() lists every
/// endpoint with its ROS and DDS type names, so a transport registers them from data.
///
/// The field lists follow the interface texts as read from these snapshots (comments, constants
/// and defaults aside; CDR encodes a bounded sequence as an unbounded one, and a default value is
/// never on the wire):
///   ros-simulation/simulation_interfaces  1.x: tag 1.5.1 = branch jazzy @ a3c60ff2715d (Humble
///       1.4.0 and Kilted 1.6.1 have the same texts); 2.x: tag 2.1.0 = main @ 172a1b1c1b3c.
///       1.x and 2.x differ on the wire only in SetEntityState_Request (2.x adds bool set_pose,
///       set_twist, set_acceleration after `state`) and Spawnable (1.x `string uri`, 2.x
///       `Resource entity_resource` = uri + resource_string); SpawnEntity_Request and
///       LoadWorld_Request take a Resource in 2.x and two strings in 1.x: the same bytes.
///   ros2/rcl_interfaces  jazzy = tag 2.0.2 @ 003987ecb81a (rcl_interfaces, action_msgs,
///       builtin_interfaces; the parameter and action texts are the same on humble 1.2.1).
///   ros2/unique_identifier_msgs  jazzy = tag 2.5.0 @ ced22ce6e0d1 (UUID: uint8[16] uuid).
///   ros2/common_interfaces  jazzy @ 5283bd97b335 (std_msgs/Header: Time stamp, string frame_id;
///       geometry_msgs Pose, Point, Quaternion, Twist, Vector3, Accel, PoseStamped).
///   ros2/rosidl  jazzy = tag 4.6.5 @ 1d92ce395ca9 (rosidl_parser/definition.py: the derived
///       action types <A>_SendGoal_Request {UUID goal_id, <A>_Goal goal} / _Response {bool
///       accepted, Time stamp}, <A>_GetResult_Request {goal_id} / _Response {int8 status,
///       <A>_Result result}, <A>_FeedbackMessage {goal_id, <A>_Feedback feedback}; a struct with
///       no members gets `uint8 structure_needs_at_least_one_member`, so an empty request is one
///       byte).
///
/// Where a struct of sim_control.h is coarser than the wire, the wire value is read and dropped:
/// SpawnEntity's initial_pose.header.stamp (written as 0), and in 1.x a Spawnable's
/// resource_string (written nowhere). Everything else round-trips exactly (a stamp outside
/// int32 seconds is clamped to that range when written).

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "bus/sim_control.h"

namespace rescuesim::control {

/// The Simulation Interfaces layout on the wire: 1.x (Humble, Jazzy, Kilted) or 2.x (Rolling).
enum class WireVersion : std::uint8_t { v1, v2 };

/// A decoded body, or why its bytes are not one.
template <class T>
struct Decoded {
  std::optional<T> value;
  /// Empty when `value` is set; else "<ROS type>_Request: <field path>: <what>", e.g.
  /// "simulation_interfaces/srv/SetEntityState_Request: state.pose.orientation.w: 8 bytes
  /// needed, 2 left".
  std::string problem;
};

// ---- bodies that sim_control.h has no struct for ----

/// A request without fields (its one wire byte, structure_needs_at_least_one_member, is 0).
struct Empty {};

/// simulation_interfaces/srv/ResetSimulation request.
struct ResetSimulationRequest {
  std::uint8_t scope = scope::kDefault;  ///< scope::* bits
};
/// simulation_interfaces/srv/SetSimulationState request (`SimulationState state`).
struct SetSimulationStateRequest {
  RunState state = RunState::stopped;
};
/// simulation_interfaces/srv/GetSimulationState response (the state comes first on the wire).
struct GetSimulationStateResponse {
  RunState state = RunState::stopped;
  Result result;
};
/// simulation_interfaces/srv/StepSimulation request.
struct StepSimulationRequest {
  std::uint64_t steps = 1;
};
/// The request of GetEntityState, GetEntityInfo, GetEntityBounds and DeleteEntity.
struct EntityRequest {
  std::string entity;
};
/// simulation_interfaces/srv/SetEntityState request. The flags exist on the wire in 2.x only; a
/// 1.x request means what these defaults say, and a 1.x encoding drops them. (A 2.x client that
/// leaves them out sends false, the ROS default.)
struct SetEntityStateRequest {
  std::string entity;
  EntityState state;
  bool set_pose = true, set_twist = true, set_acceleration = false;
};
/// simulation_interfaces/srv/GetNamedPoseBounds request.
struct NamedPoseBoundsRequest {
  std::string name;
};
/// simulation_interfaces/srv/GetSpawnables request.
struct GetSpawnablesRequest {
  std::vector<std::string> sources;
};
/// simulation_interfaces/srv/GetAvailableWorlds request.
struct GetAvailableWorldsRequest {
  std::vector<std::string> additional_sources;
  TagsFilter filter;
  bool offline_only = false, continue_on_error = false;
};
/// simulation_interfaces/srv/LoadWorld request (1.x: uri, resource_string; 2.x: the same two in
/// `Resource world_resource`).
struct LoadWorldRequest {
  std::string uri, resource_string;
  bool fail_on_unsupported_element = false, ignore_missing_or_unsupported_assets = false;
};

struct GetEntitiesResponse {
  Result result;
  std::vector<std::string> entities;
};
struct GetEntityStateResponse {
  Result result;
  EntityState state;
};
struct GetEntitiesStatesResponse {
  Result result;
  std::vector<std::string> entities;
  std::vector<EntityState> states;
};
struct GetEntityInfoResponse {
  Result result;
  EntityInfo info;
};
/// The response of GetEntityBounds and GetNamedPoseBounds.
struct BoundsResponse {
  Result result;
  Bounds bounds;
};
struct GetNamedPosesResponse {
  Result result;
  std::vector<NamedPose> poses;
};
struct GetSpawnablesResponse {
  Result result;
  std::vector<Spawnable> spawnables;
};
struct SpawnEntityResponse {
  Result result;
  std::string entity_name;
};
struct GetAvailableWorldsResponse {
  Result result;
  std::vector<WorldResource> worlds;
};
/// The response of GetCurrentWorld and LoadWorld.
struct WorldResponse {
  Result result;
  WorldResource world;
};

// ---- the SimulateSteps action and action_msgs ----

/// unique_identifier_msgs/msg/UUID (uint8[16] uuid): a goal's id.
using GoalId = std::array<std::uint8_t, 16>;

/// simulation_interfaces/action/SimulateSteps_SendGoal request: goal_id, goal {uint64 steps}.
struct SendGoalRequest {
  GoalId goal_id{};
  std::uint64_t steps = 0;
};
/// SimulateSteps_SendGoal response.
struct SendGoalResponse {
  bool accepted = false;
  std::int64_t stamp_ns = 0;  ///< builtin_interfaces/Time stamp
};
/// SimulateSteps_GetResult request (goal_id).
struct GetResultRequest {
  GoalId goal_id{};
};
/// action_msgs/msg/GoalStatus status values.
namespace goal_status {
inline constexpr std::int8_t kUnknown = 0, kAccepted = 1, kExecuting = 2, kCanceling = 3, kSucceeded = 4,
                             kCanceled = 5, kAborted = 6;
}
/// SimulateSteps_GetResult response: status, result {Result result}.
struct GetResultResponse {
  std::int8_t status = goal_status::kUnknown;
  Result result;
};
/// simulation_interfaces/action/SimulateSteps_FeedbackMessage: goal_id, feedback
/// {uint64 completed_steps, uint64 remaining_steps}.
struct FeedbackMessage {
  GoalId goal_id{};
  std::uint64_t completed_steps = 0, remaining_steps = 0;
};
/// action_msgs/msg/GoalInfo.
struct GoalInfo {
  GoalId goal_id{};
  std::int64_t stamp_ns = 0;
};
/// action_msgs/srv/CancelGoal request.
struct CancelGoalRequest {
  GoalInfo goal_info;
};
/// action_msgs/srv/CancelGoal return codes.
namespace cancel {
inline constexpr std::int8_t kNone = 0, kRejected = 1, kUnknownGoalId = 2, kGoalTerminated = 3;
}
/// action_msgs/srv/CancelGoal response.
struct CancelGoalResponse {
  std::int8_t return_code = cancel::kNone;
  std::vector<GoalInfo> goals_canceling;
};
/// action_msgs/msg/GoalStatus.
struct GoalStatus {
  GoalInfo goal_info;
  std::int8_t status = goal_status::kUnknown;
};
/// action_msgs/msg/GoalStatusArray (the action's status topic).
struct GoalStatusArray {
  std::vector<GoalStatus> status_list;
};

// ---- rcl_interfaces ----

/// rcl_interfaces/srv/ListParameters request.
struct ListParametersRequest {
  static constexpr std::uint64_t kDepthRecursive = 0;
  std::vector<std::string> prefixes;
  std::uint64_t depth = kDepthRecursive;
};
/// rcl_interfaces/msg/ListParametersResult (ListParameters response `result`).
struct ListParametersResult {
  std::vector<std::string> names, prefixes;
};
/// The request of GetParameters, DescribeParameters and GetParameterTypes (`string[] names`).
struct ParameterNames {
  std::vector<std::string> names;
};
struct GetParametersResponse {
  std::vector<ParameterValue> values;
};
/// The request of SetParameters and SetParametersAtomically (`Parameter[] parameters`).
struct SetParametersRequest {
  std::vector<Parameter> parameters;
};
struct SetParametersResponse {
  std::vector<SetParameterResult> results;
};
/// rcl_interfaces/msg/FloatingPointRange.
struct FloatingPointRange {
  double from_value = 0, to_value = 0, step = 0;
};
/// rcl_interfaces/msg/IntegerRange.
struct IntegerRange {
  std::int64_t from_value = 0, to_value = 0;
  std::uint64_t step = 0;
};
/// rcl_interfaces/msg/ParameterDescriptor, every field (sim_control's ParameterDescriptor is the
/// part a run fills; descriptor_message() widens it).
struct ParameterDescriptorMessage {
  std::string name;
  std::uint8_t type = ParameterValue::kNotSet;
  std::string description, additional_constraints;
  bool read_only = false, dynamic_typing = false;
  std::vector<FloatingPointRange> floating_point_range;  ///< bounded: at most 1
  std::vector<IntegerRange> integer_range;               ///< bounded: at most 1
};
struct DescribeParametersResponse {
  std::vector<ParameterDescriptorMessage> descriptors;
};
struct GetParameterTypesResponse {
  std::vector<std::uint8_t> types;
};

/// A run's descriptor as the message: its range becomes an IntegerRange (bounds rounded) for an
/// integer parameter, a FloatingPointRange otherwise; step 0 (any value in the range).
ParameterDescriptorMessage descriptor_message(const ParameterDescriptor& d);

// ---- the interfaces, as data ----

/// Every endpoint a transport registers.
enum class Interface : std::uint8_t {
  get_simulator_features, reset_simulation, get_simulation_state, set_simulation_state, step_simulation,
  get_entities, get_entity_state, get_entities_states, set_entity_state, get_entity_info, get_entity_bounds,
  get_named_poses, get_named_pose_bounds, get_spawnables, spawn_entity, delete_entity, get_available_worlds,
  get_current_world, load_world, unload_world,
  simulate_steps_send_goal, simulate_steps_get_result, simulate_steps_cancel_goal,
  simulate_steps_feedback, simulate_steps_status,
  list_parameters, get_parameters, set_parameters, set_parameters_atomically, describe_parameters,
  get_parameter_types,
};

/// What kind of endpoint, and so where its name lives.
enum class EndpointKind : std::uint8_t {
  sim_service,     ///< a service under the Simulation Interfaces namespace (root by default)
  action_service,  ///< a service of the SimulateSteps action (same namespace)
  action_topic,    ///< a topic of the SimulateSteps action (same namespace)
  node_service,    ///< a parameter service under the node's name (/rescuesim/list_parameters)
};

/// One endpoint: its name and its ROS and DDS type names.
struct InterfaceInfo {
  Interface id;
  EndpointKind kind;
  /// Relative name, as the standard and rclcpp name it: "reset_simulation",
  /// "simulate_steps/_action/send_goal", "list_parameters".
  const char* name;
  /// ROS type: "simulation_interfaces/srv/ResetSimulation",
  /// "simulation_interfaces/action/SimulateSteps_SendGoal", "action_msgs/msg/GoalStatusArray".
  const char* ros_type;
  /// DDS type of the request, or of the topic's message:
  /// "simulation_interfaces::srv::dds_::ResetSimulation_Request_".
  const char* dds_request;
  /// DDS type of the response; nullptr for a topic.
  const char* dds_response;
};

/// Every endpoint, in Interface order.
std::span<const InterfaceInfo> interfaces();
const InterfaceInfo& info(Interface id);

/// The tags: one per service (Request, Response) or topic (Message), with the field names of
/// a body whose struct is a nested message on the wire (e.g. ResetSimulation's response is
/// `Result result`) or nullptr when the struct is the whole body.
namespace iface {
#define RS_CONTROL_SERVICE(Tag, iid, Req, req_field, Resp, resp_field) \
  struct Tag {                                                          \
    using Request = Req;                                                \
    using Response = Resp;                                              \
    static constexpr Interface id = Interface::iid;                     \
    static constexpr const char* request_field = req_field;            \
    static constexpr const char* response_field = resp_field;          \
  };
RS_CONTROL_SERVICE(GetSimulatorFeatures, get_simulator_features, Empty, nullptr, SimulatorFeatures, "features")
RS_CONTROL_SERVICE(ResetSimulation, reset_simulation, ResetSimulationRequest, nullptr, Result, "result")
RS_CONTROL_SERVICE(GetSimulationState, get_simulation_state, Empty, nullptr, GetSimulationStateResponse, nullptr)
RS_CONTROL_SERVICE(SetSimulationState, set_simulation_state, SetSimulationStateRequest, nullptr, Result, "result")
RS_CONTROL_SERVICE(StepSimulation, step_simulation, StepSimulationRequest, nullptr, Result, "result")
RS_CONTROL_SERVICE(GetEntities, get_entities, EntityFilters, "filters", GetEntitiesResponse, nullptr)
RS_CONTROL_SERVICE(GetEntityState, get_entity_state, EntityRequest, nullptr, GetEntityStateResponse, nullptr)
RS_CONTROL_SERVICE(GetEntitiesStates, get_entities_states, EntityFilters, "filters", GetEntitiesStatesResponse, nullptr)
RS_CONTROL_SERVICE(SetEntityState, set_entity_state, SetEntityStateRequest, nullptr, Result, "result")
RS_CONTROL_SERVICE(GetEntityInfo, get_entity_info, EntityRequest, nullptr, GetEntityInfoResponse, nullptr)
RS_CONTROL_SERVICE(GetEntityBounds, get_entity_bounds, EntityRequest, nullptr, BoundsResponse, nullptr)
RS_CONTROL_SERVICE(GetNamedPoses, get_named_poses, TagsFilter, "tags", GetNamedPosesResponse, nullptr)
RS_CONTROL_SERVICE(GetNamedPoseBounds, get_named_pose_bounds, NamedPoseBoundsRequest, nullptr, BoundsResponse, nullptr)
RS_CONTROL_SERVICE(GetSpawnables, get_spawnables, GetSpawnablesRequest, nullptr, GetSpawnablesResponse, nullptr)
RS_CONTROL_SERVICE(SpawnEntity, spawn_entity, SpawnRequest, nullptr, SpawnEntityResponse, nullptr)
RS_CONTROL_SERVICE(DeleteEntity, delete_entity, EntityRequest, nullptr, Result, "result")
RS_CONTROL_SERVICE(GetAvailableWorlds, get_available_worlds, GetAvailableWorldsRequest, nullptr,
                   GetAvailableWorldsResponse, nullptr)
RS_CONTROL_SERVICE(GetCurrentWorld, get_current_world, Empty, nullptr, WorldResponse, nullptr)
RS_CONTROL_SERVICE(LoadWorld, load_world, LoadWorldRequest, nullptr, WorldResponse, nullptr)
RS_CONTROL_SERVICE(UnloadWorld, unload_world, Empty, nullptr, Result, "result")
RS_CONTROL_SERVICE(SimulateStepsSendGoal, simulate_steps_send_goal, SendGoalRequest, nullptr, SendGoalResponse, nullptr)
RS_CONTROL_SERVICE(SimulateStepsGetResult, simulate_steps_get_result, GetResultRequest, nullptr, GetResultResponse, nullptr)
RS_CONTROL_SERVICE(CancelGoal, simulate_steps_cancel_goal, CancelGoalRequest, nullptr, CancelGoalResponse, nullptr)
RS_CONTROL_SERVICE(ListParameters, list_parameters, ListParametersRequest, nullptr, ListParametersResult, "result")
RS_CONTROL_SERVICE(GetParameters, get_parameters, ParameterNames, nullptr, GetParametersResponse, nullptr)
RS_CONTROL_SERVICE(SetParameters, set_parameters, SetParametersRequest, nullptr, SetParametersResponse, nullptr)
RS_CONTROL_SERVICE(SetParametersAtomically, set_parameters_atomically, SetParametersRequest, nullptr,
                   SetParameterResult, "result")
RS_CONTROL_SERVICE(DescribeParameters, describe_parameters, ParameterNames, nullptr, DescribeParametersResponse, nullptr)
RS_CONTROL_SERVICE(GetParameterTypes, get_parameter_types, ParameterNames, nullptr, GetParameterTypesResponse, nullptr)
#undef RS_CONTROL_SERVICE

/// The SimulateSteps action's feedback topic.
struct SimulateStepsFeedback {
  using Message = FeedbackMessage;
  static constexpr Interface id = Interface::simulate_steps_feedback;
};
/// The SimulateSteps action's status topic.
struct SimulateStepsStatus {
  using Message = control::GoalStatusArray;
  static constexpr Interface id = Interface::simulate_steps_status;
};
}  // namespace iface

/// Every service tag, in Interface order (for code that handles them all alike: tests, fuzzing).
using AllServices = std::tuple<iface::GetSimulatorFeatures, iface::ResetSimulation, iface::GetSimulationState,
                               iface::SetSimulationState, iface::StepSimulation, iface::GetEntities,
                               iface::GetEntityState, iface::GetEntitiesStates, iface::SetEntityState,
                               iface::GetEntityInfo, iface::GetEntityBounds, iface::GetNamedPoses,
                               iface::GetNamedPoseBounds, iface::GetSpawnables, iface::SpawnEntity,
                               iface::DeleteEntity, iface::GetAvailableWorlds, iface::GetCurrentWorld,
                               iface::LoadWorld, iface::UnloadWorld, iface::SimulateStepsSendGoal,
                               iface::SimulateStepsGetResult, iface::CancelGoal, iface::ListParameters,
                               iface::GetParameters, iface::SetParameters, iface::SetParametersAtomically,
                               iface::DescribeParameters, iface::GetParameterTypes>;
/// Every topic tag.
using AllMessages = std::tuple<iface::SimulateStepsFeedback, iface::SimulateStepsStatus>;

// ---- the codecs (instantiated for every tag above) ----

template <class S>
Decoded<typename S::Request> decode_request(std::span<const std::uint8_t> cdr, WireVersion version);
template <class S>
void encode_request(const typename S::Request& request, WireVersion version, std::vector<std::uint8_t>& out);
template <class S>
Decoded<typename S::Response> decode_response(std::span<const std::uint8_t> cdr, WireVersion version);
template <class S>
void encode_response(const typename S::Response& response, WireVersion version, std::vector<std::uint8_t>& out);
template <class M>
Decoded<typename M::Message> decode_message(std::span<const std::uint8_t> cdr, WireVersion version);
template <class M>
void encode_message(const typename M::Message& message, WireVersion version, std::vector<std::uint8_t>& out);

}  // namespace rescuesim::control
