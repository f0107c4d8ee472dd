// The control interfaces as data (the endpoint table) and descriptor_message. The codecs are in
// control_cdr_sim.cpp, control_cdr_action.cpp and control_cdr_params.cpp, on the field lists of
// control_cdr_fields.h.

#include "bridges/common/control_cdr.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace rescuesim::control {

namespace {

constexpr InterfaceInfo kInterfaces[] = {
    {Interface::get_simulator_features, EndpointKind::sim_service, "get_simulator_features",
     "simulation_interfaces/srv/GetSimulatorFeatures", "simulation_interfaces::srv::dds_::GetSimulatorFeatures_Request_",
     "simulation_interfaces::srv::dds_::GetSimulatorFeatures_Response_"},
    {Interface::reset_simulation, EndpointKind::sim_service, "reset_simulation",
     "simulation_interfaces/srv/ResetSimulation", "simulation_interfaces::srv::dds_::ResetSimulation_Request_",
     "simulation_interfaces::srv::dds_::ResetSimulation_Response_"},
    {Interface::get_simulation_state, EndpointKind::sim_service, "get_simulation_state",
     "simulation_interfaces/srv/GetSimulationState", "simulation_interfaces::srv::dds_::GetSimulationState_Request_",
     "simulation_interfaces::srv::dds_::GetSimulationState_Response_"},
    {Interface::set_simulation_state, EndpointKind::sim_service, "set_simulation_state",
     "simulation_interfaces/srv/SetSimulationState", "simulation_interfaces::srv::dds_::SetSimulationState_Request_",
     "simulation_interfaces::srv::dds_::SetSimulationState_Response_"},
    {Interface::step_simulation, EndpointKind::sim_service, "step_simulation", "simulation_interfaces/srv/StepSimulation",
     "simulation_interfaces::srv::dds_::StepSimulation_Request_",
     "simulation_interfaces::srv::dds_::StepSimulation_Response_"},
    {Interface::get_entities, EndpointKind::sim_service, "get_entities", "simulation_interfaces/srv/GetEntities",
     "simulation_interfaces::srv::dds_::GetEntities_Request_", "simulation_interfaces::srv::dds_::GetEntities_Response_"},
    {Interface::get_entity_state, EndpointKind::sim_service, "get_entity_state",
     "simulation_interfaces/srv/GetEntityState", "simulation_interfaces::srv::dds_::GetEntityState_Request_",
     "simulation_interfaces::srv::dds_::GetEntityState_Response_"},
    {Interface::get_entities_states, EndpointKind::sim_service, "get_entities_states",
     "simulation_interfaces/srv/GetEntitiesStates", "simulation_interfaces::srv::dds_::GetEntitiesStates_Request_",
     "simulation_interfaces::srv::dds_::GetEntitiesStates_Response_"},
    {Interface::set_entity_state, EndpointKind::sim_service, "set_entity_state",
     "simulation_interfaces/srv/SetEntityState", "simulation_interfaces::srv::dds_::SetEntityState_Request_",
     "simulation_interfaces::srv::dds_::SetEntityState_Response_"},
    {Interface::get_entity_info, EndpointKind::sim_service, "get_entity_info", "simulation_interfaces/srv/GetEntityInfo",
     "simulation_interfaces::srv::dds_::GetEntityInfo_Request_",
     "simulation_interfaces::srv::dds_::GetEntityInfo_Response_"},
    {Interface::get_entity_bounds, EndpointKind::sim_service, "get_entity_bounds",
     "simulation_interfaces/srv/GetEntityBounds", "simulation_interfaces::srv::dds_::GetEntityBounds_Request_",
     "simulation_interfaces::srv::dds_::GetEntityBounds_Response_"},
    {Interface::get_named_poses, EndpointKind::sim_service, "get_named_poses", "simulation_interfaces/srv/GetNamedPoses",
     "simulation_interfaces::srv::dds_::GetNamedPoses_Request_",
     "simulation_interfaces::srv::dds_::GetNamedPoses_Response_"},
    {Interface::get_named_pose_bounds, EndpointKind::sim_service, "get_named_pose_bounds",
     "simulation_interfaces/srv/GetNamedPoseBounds", "simulation_interfaces::srv::dds_::GetNamedPoseBounds_Request_",
     "simulation_interfaces::srv::dds_::GetNamedPoseBounds_Response_"},
    {Interface::get_spawnables, EndpointKind::sim_service, "get_spawnables", "simulation_interfaces/srv/GetSpawnables",
     "simulation_interfaces::srv::dds_::GetSpawnables_Request_",
     "simulation_interfaces::srv::dds_::GetSpawnables_Response_"},
    {Interface::spawn_entity, EndpointKind::sim_service, "spawn_entity", "simulation_interfaces/srv/SpawnEntity",
     "simulation_interfaces::srv::dds_::SpawnEntity_Request_", "simulation_interfaces::srv::dds_::SpawnEntity_Response_"},
    {Interface::delete_entity, EndpointKind::sim_service, "delete_entity", "simulation_interfaces/srv/DeleteEntity",
     "simulation_interfaces::srv::dds_::DeleteEntity_Request_",
     "simulation_interfaces::srv::dds_::DeleteEntity_Response_"},
    {Interface::get_available_worlds, EndpointKind::sim_service, "get_available_worlds",
     "simulation_interfaces/srv/GetAvailableWorlds", "simulation_interfaces::srv::dds_::GetAvailableWorlds_Request_",
     "simulation_interfaces::srv::dds_::GetAvailableWorlds_Response_"},
    {Interface::get_current_world, EndpointKind::sim_service, "get_current_world",
     "simulation_interfaces/srv/GetCurrentWorld", "simulation_interfaces::srv::dds_::GetCurrentWorld_Request_",
     "simulation_interfaces::srv::dds_::GetCurrentWorld_Response_"},
    {Interface::load_world, EndpointKind::sim_service, "load_world", "simulation_interfaces/srv/LoadWorld",
     "simulation_interfaces::srv::dds_::LoadWorld_Request_", "simulation_interfaces::srv::dds_::LoadWorld_Response_"},
    {Interface::unload_world, EndpointKind::sim_service, "unload_world", "simulation_interfaces/srv/UnloadWorld",
     "simulation_interfaces::srv::dds_::UnloadWorld_Request_", "simulation_interfaces::srv::dds_::UnloadWorld_Response_"},
    {Interface::simulate_steps_send_goal, EndpointKind::action_service, "simulate_steps/_action/send_goal",
     "simulation_interfaces/action/SimulateSteps_SendGoal",
     "simulation_interfaces::action::dds_::SimulateSteps_SendGoal_Request_",
     "simulation_interfaces::action::dds_::SimulateSteps_SendGoal_Response_"},
    {Interface::simulate_steps_get_result, EndpointKind::action_service, "simulate_steps/_action/get_result",
     "simulation_interfaces/action/SimulateSteps_GetResult",
     "simulation_interfaces::action::dds_::SimulateSteps_GetResult_Request_",
     "simulation_interfaces::action::dds_::SimulateSteps_GetResult_Response_"},
    {Interface::simulate_steps_cancel_goal, EndpointKind::action_service, "simulate_steps/_action/cancel_goal",
     "action_msgs/srv/CancelGoal", "action_msgs::srv::dds_::CancelGoal_Request_",
     "action_msgs::srv::dds_::CancelGoal_Response_"},
    {Interface::simulate_steps_feedback, EndpointKind::action_topic, "simulate_steps/_action/feedback",
     "simulation_interfaces/action/SimulateSteps_FeedbackMessage",
     "simulation_interfaces::action::dds_::SimulateSteps_FeedbackMessage_", nullptr},
    {Interface::simulate_steps_status, EndpointKind::action_topic, "simulate_steps/_action/status",
     "action_msgs/msg/GoalStatusArray", "action_msgs::msg::dds_::GoalStatusArray_", nullptr},
    {Interface::list_parameters, EndpointKind::node_service, "list_parameters", "rcl_interfaces/srv/ListParameters",
     "rcl_interfaces::srv::dds_::ListParameters_Request_", "rcl_interfaces::srv::dds_::ListParameters_Response_"},
    {Interface::get_parameters, EndpointKind::node_service, "get_parameters", "rcl_interfaces/srv/GetParameters",
     "rcl_interfaces::srv::dds_::GetParameters_Request_", "rcl_interfaces::srv::dds_::GetParameters_Response_"},
    {Interface::set_parameters, EndpointKind::node_service, "set_parameters", "rcl_interfaces/srv/SetParameters",
     "rcl_interfaces::srv::dds_::SetParameters_Request_", "rcl_interfaces::srv::dds_::SetParameters_Response_"},
    {Interface::set_parameters_atomically, EndpointKind::node_service, "set_parameters_atomically",
     "rcl_interfaces/srv/SetParametersAtomically", "rcl_interfaces::srv::dds_::SetParametersAtomically_Request_",
     "rcl_interfaces::srv::dds_::SetParametersAtomically_Response_"},
    {Interface::describe_parameters, EndpointKind::node_service, "describe_parameters",
     "rcl_interfaces/srv/DescribeParameters", "rcl_interfaces::srv::dds_::DescribeParameters_Request_",
     "rcl_interfaces::srv::dds_::DescribeParameters_Response_"},
    {Interface::get_parameter_types, EndpointKind::node_service, "get_parameter_types",
     "rcl_interfaces/srv/GetParameterTypes", "rcl_interfaces::srv::dds_::GetParameterTypes_Request_",
     "rcl_interfaces::srv::dds_::GetParameterTypes_Response_"},
};

}  // namespace

std::span<const InterfaceInfo> interfaces() { return kInterfaces; }

const InterfaceInfo& info(Interface id) {
  const auto i = static_cast<std::size_t>(id);
  RS_DEMAND(i < std::size(kInterfaces) && kInterfaces[i].id == id, "control::info: interface table out of order");
  return kInterfaces[i];
}

ParameterDescriptorMessage descriptor_message(const ParameterDescriptor& d) {
  ParameterDescriptorMessage m;
  m.name = d.name;
  m.type = d.type;
  m.description = d.description;
  m.read_only = d.read_only;
  if (d.range) {
    if (d.type == ParameterValue::kInteger) {
      // rounded and held inside int64 (a bound beyond it is no bound an int64 can pass)
      const auto to_int = [](double x) {
        constexpr double lo = -9223372036854775808.0, hi = 9223372036854774784.0;  // largest double below 2^63
        if (std::isnan(x)) return std::int64_t{0};
        return static_cast<std::int64_t>(std::llround(std::clamp(x, lo, hi)));
      };
      m.integer_range.push_back({to_int(d.range->first), to_int(d.range->second), 0});
    } else {
      m.floating_point_range.push_back({d.range->first, d.range->second, 0.0});
    }
  }
  return m;
}

}  // namespace rescuesim::control
