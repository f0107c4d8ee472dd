// Every codec of bridges/common/control_cdr.h, requests and responses in both wire versions:
// a value with something in every field comes back equal, field for field, from its bytes;
// every shorter prefix of those bytes is refused with a message naming the body's type
// (never a crash, never a value).

#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#include "bridges/common/control_cdr.h"

namespace rescuesim::control {
namespace {

using Bytes = std::vector<std::uint8_t>;

// ---- field-for-field equality (sim_control.h's structs have no operator==) ----

template <class T>
bool eq(const T& a, const T& b, WireVersion v);

bool same(const Vec3& a, const Vec3& b, WireVersion) { return a == b; }
bool same(const Pose3& a, const Pose3& b, WireVersion) { return a.p == b.p && a.q.coeffs() == b.q.coeffs(); }
bool same(const Empty&, const Empty&, WireVersion) { return true; }
bool same(const Result& a, const Result& b, WireVersion) {
  return a.result == b.result && a.error_message == b.error_message;
}
bool same(const SimulatorFeatures& a, const SimulatorFeatures& b, WireVersion) {
  return a.features == b.features && a.spawn_formats == b.spawn_formats && a.custom_info == b.custom_info;
}
bool same(const TagsFilter& a, const TagsFilter& b, WireVersion) {
  return a.tags == b.tags && a.filter_mode == b.filter_mode;
}
bool same(const Bounds& a, const Bounds& b, WireVersion v) { return a.type == b.type && eq(a.points, b.points, v); }
bool same(const EntityFilters& a, const EntityFilters& b, WireVersion v) {
  return a.filter == b.filter && a.categories == b.categories && same(a.tags, b.tags, v) && same(a.bounds, b.bounds, v);
}
bool same(const EntityState& a, const EntityState& b, WireVersion v) {
  return a.stamp_ns == b.stamp_ns && a.frame_id == b.frame_id && same(a.pose, b.pose, v) && a.linear == b.linear &&
         a.angular == b.angular && a.linear_acc == b.linear_acc && a.angular_acc == b.angular_acc;
}
bool same(const EntityInfo& a, const EntityInfo& b, WireVersion) {
  return a.category == b.category && a.description == b.description && a.tags == b.tags;
}
bool same(const NamedPose& a, const NamedPose& b, WireVersion v) {
  return a.name == b.name && a.description == b.description && a.tags == b.tags && same(a.pose, b.pose, v);
}
bool same(const Spawnable& a, const Spawnable& b, WireVersion v) {
  return a.uri == b.uri && a.resource_string == b.resource_string && a.description == b.description &&
         same(a.spawn_bounds, b.spawn_bounds, v);
}
bool same(const WorldResource& a, const WorldResource& b, WireVersion) {
  return a.name == b.name && a.uri == b.uri && a.resource_string == b.resource_string &&
         a.description == b.description && a.tags == b.tags;
}
bool same(const SpawnRequest& a, const SpawnRequest& b, WireVersion v) {
  return a.name == b.name && a.allow_renaming == b.allow_renaming && a.uri == b.uri &&
         a.resource_string == b.resource_string && a.entity_namespace == b.entity_namespace &&
         a.frame_id == b.frame_id && same(a.pose, b.pose, v);
}
bool same(const ParameterValue& a, const ParameterValue& b, WireVersion) {
  return a.type == b.type && a.bool_value == b.bool_value && a.integer_value == b.integer_value &&
         a.double_value == b.double_value && a.string_value == b.string_value &&
         a.byte_array_value == b.byte_array_value && a.bool_array_value == b.bool_array_value &&
         a.integer_array_value == b.integer_array_value && a.double_array_value == b.double_array_value &&
         a.string_array_value == b.string_array_value;
}
bool same(const Parameter& a, const Parameter& b, WireVersion v) {
  return a.name == b.name && same(a.value, b.value, v);
}
bool same(const SetParameterResult& a, const SetParameterResult& b, WireVersion) {
  return a.successful == b.successful && a.reason == b.reason;
}
bool same(const ResetSimulationRequest& a, const ResetSimulationRequest& b, WireVersion) { return a.scope == b.scope; }
bool same(const SetSimulationStateRequest& a, const SetSimulationStateRequest& b, WireVersion) {
  return a.state == b.state;
}
bool same(const GetSimulationStateResponse& a, const GetSimulationStateResponse& b, WireVersion v) {
  return a.state == b.state && same(a.result, b.result, v);
}
bool same(const StepSimulationRequest& a, const StepSimulationRequest& b, WireVersion) { return a.steps == b.steps; }
bool same(const EntityRequest& a, const EntityRequest& b, WireVersion) { return a.entity == b.entity; }
bool same(const SetEntityStateRequest& a, const SetEntityStateRequest& b, WireVersion v) {
  return a.entity == b.entity && same(a.state, b.state, v) && a.set_pose == b.set_pose && a.set_twist == b.set_twist &&
         a.set_acceleration == b.set_acceleration;
}
bool same(const NamedPoseBoundsRequest& a, const NamedPoseBoundsRequest& b, WireVersion) { return a.name == b.name; }
bool same(const GetSpawnablesRequest& a, const GetSpawnablesRequest& b, WireVersion) {
  return a.sources == b.sources;
}
bool same(const GetAvailableWorldsRequest& a, const GetAvailableWorldsRequest& b, WireVersion v) {
  return a.additional_sources == b.additional_sources && same(a.filter, b.filter, v) &&
         a.offline_only == b.offline_only && a.continue_on_error == b.continue_on_error;
}
bool same(const LoadWorldRequest& a, const LoadWorldRequest& b, WireVersion) {
  return a.uri == b.uri && a.resource_string == b.resource_string &&
         a.fail_on_unsupported_element == b.fail_on_unsupported_element &&
         a.ignore_missing_or_unsupported_assets == b.ignore_missing_or_unsupported_assets;
}
bool same(const GetEntitiesResponse& a, const GetEntitiesResponse& b, WireVersion v) {
  return same(a.result, b.result, v) && a.entities == b.entities;
}
bool same(const GetEntityStateResponse& a, const GetEntityStateResponse& b, WireVersion v) {
  return same(a.result, b.result, v) && same(a.state, b.state, v);
}
bool same(const GetEntitiesStatesResponse& a, const GetEntitiesStatesResponse& b, WireVersion v) {
  return same(a.result, b.result, v) && a.entities == b.entities && eq(a.states, b.states, v);
}
bool same(const GetEntityInfoResponse& a, const GetEntityInfoResponse& b, WireVersion v) {
  return same(a.result, b.result, v) && same(a.info, b.info, v);
}
bool same(const BoundsResponse& a, const BoundsResponse& b, WireVersion v) {
  return same(a.result, b.result, v) && same(a.bounds, b.bounds, v);
}
bool same(const GetNamedPosesResponse& a, const GetNamedPosesResponse& b, WireVersion v) {
  return same(a.result, b.result, v) && eq(a.poses, b.poses, v);
}
bool same(const GetSpawnablesResponse& a, const GetSpawnablesResponse& b, WireVersion v) {
  return same(a.result, b.result, v) && eq(a.spawnables, b.spawnables, v);
}
bool same(const SpawnEntityResponse& a, const SpawnEntityResponse& b, WireVersion v) {
  return same(a.result, b.result, v) && a.entity_name == b.entity_name;
}
bool same(const GetAvailableWorldsResponse& a, const GetAvailableWorldsResponse& b, WireVersion v) {
  return same(a.result, b.result, v) && eq(a.worlds, b.worlds, v);
}
bool same(const WorldResponse& a, const WorldResponse& b, WireVersion v) {
  return same(a.result, b.result, v) && same(a.world, b.world, v);
}
bool same(const SendGoalRequest& a, const SendGoalRequest& b, WireVersion) {
  return a.goal_id == b.goal_id && a.steps == b.steps;
}
bool same(const SendGoalResponse& a, const SendGoalResponse& b, WireVersion) {
  return a.accepted == b.accepted && a.stamp_ns == b.stamp_ns;
}
bool same(const GetResultRequest& a, const GetResultRequest& b, WireVersion) { return a.goal_id == b.goal_id; }
bool same(const GetResultResponse& a, const GetResultResponse& b, WireVersion v) {
  return a.status == b.status && same(a.result, b.result, v);
}
bool same(const FeedbackMessage& a, const FeedbackMessage& b, WireVersion) {
  return a.goal_id == b.goal_id && a.completed_steps == b.completed_steps && a.remaining_steps == b.remaining_steps;
}
bool same(const GoalInfo& a, const GoalInfo& b, WireVersion) {
  return a.goal_id == b.goal_id && a.stamp_ns == b.stamp_ns;
}
bool same(const CancelGoalRequest& a, const CancelGoalRequest& b, WireVersion v) {
  return same(a.goal_info, b.goal_info, v);
}
bool same(const CancelGoalResponse& a, const CancelGoalResponse& b, WireVersion v) {
  return a.return_code == b.return_code && eq(a.goals_canceling, b.goals_canceling, v);
}
bool same(const GoalStatus& a, const GoalStatus& b, WireVersion v) {
  return same(a.goal_info, b.goal_info, v) && a.status == b.status;
}
bool same(const GoalStatusArray& a, const GoalStatusArray& b, WireVersion v) {
  return eq(a.status_list, b.status_list, v);
}
bool same(const ListParametersRequest& a, const ListParametersRequest& b, WireVersion) {
  return a.prefixes == b.prefixes && a.depth == b.depth;
}
bool same(const ListParametersResult& a, const ListParametersResult& b, WireVersion) {
  return a.names == b.names && a.prefixes == b.prefixes;
}
bool same(const ParameterNames& a, const ParameterNames& b, WireVersion) { return a.names == b.names; }
bool same(const GetParametersResponse& a, const GetParametersResponse& b, WireVersion v) {
  return eq(a.values, b.values, v);
}
bool same(const SetParametersRequest& a, const SetParametersRequest& b, WireVersion v) {
  return eq(a.parameters, b.parameters, v);
}
bool same(const SetParametersResponse& a, const SetParametersResponse& b, WireVersion v) {
  return eq(a.results, b.results, v);
}
bool same(const FloatingPointRange& a, const FloatingPointRange& b, WireVersion) {
  return a.from_value == b.from_value && a.to_value == b.to_value && a.step == b.step;
}
bool same(const IntegerRange& a, const IntegerRange& b, WireVersion) {
  return a.from_value == b.from_value && a.to_value == b.to_value && a.step == b.step;
}
bool same(const ParameterDescriptorMessage& a, const ParameterDescriptorMessage& b, WireVersion v) {
  return a.name == b.name && a.type == b.type && a.description == b.description &&
         a.additional_constraints == b.additional_constraints && a.read_only == b.read_only &&
         a.dynamic_typing == b.dynamic_typing && eq(a.floating_point_range, b.floating_point_range, v) &&
         eq(a.integer_range, b.integer_range, v);
}
bool same(const DescribeParametersResponse& a, const DescribeParametersResponse& b, WireVersion v) {
  return eq(a.descriptors, b.descriptors, v);
}
bool same(const GetParameterTypesResponse& a, const GetParameterTypesResponse& b, WireVersion) {
  return a.types == b.types;
}

template <class T>
bool eq(const T& a, const T& b, WireVersion v) {
  if constexpr (requires { a.size(); a[0]; typename T::value_type; }) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (!same(a[i], b[i], v)) return false;
    }
    return true;
  } else {
    return same(a, b, v);
  }
}

// ---- values with something in every field (what a version carries) ----

Pose3 pose(double k) { return {Vec3(k, -2 * k, 0.25), Quat(0.5, -0.5, 0.5, 0.5)}; }
EntityState state(double k) {
  EntityState s;
  s.stamp_ns = -2'500'000'001;  // sec -3, nanosec 499999999
  s.frame_id = "odom";
  s.pose = pose(k);
  s.linear = Vec3(k, 0.5, -0.5);
  s.angular = Vec3(0.125, -k, 3);
  s.linear_acc = Vec3(9.81, -k, 1e-9);
  s.angular_acc = Vec3(-1e300, k, 7);
  return s;
}
Bounds box() { return {Bounds::kBox, {Vec3(-1, -2, -3), Vec3(1, 2, 3.5)}}; }
Result failed() { return Result::fail(code::kNotFound, "no entity 'x'"); }
GoalId goal() {
  GoalId g;
  for (int i = 0; i < 16; ++i) g[i] = static_cast<std::uint8_t>(i * 17 + 3);
  return g;
}
ParameterValue every_value() {
  ParameterValue p;
  p.type = ParameterValue::kStringArray;
  p.bool_value = true;
  p.integer_value = -42;
  p.double_value = 0.1;
  p.string_value = "x";
  p.byte_array_value = {0, 255, 7};
  p.bool_array_value = {true, false, true};
  p.integer_array_value = {std::numeric_limits<std::int64_t>::min(), 3};
  p.double_array_value = {-0.5};
  p.string_array_value = {"", "ab"};
  return p;
}

void fill(Empty&, WireVersion) {}
void fill(SimulatorFeatures& f, WireVersion) { f = {{0, 1, 50, 65535}, {"urdf", "sdf", "rescuesim"}, "info"}; }
void fill(Result& r, WireVersion) { r = failed(); }
void fill(ResetSimulationRequest& r, WireVersion) { r.scope = scope::kTime | scope::kSpawned; }
void fill(GetSimulationStateResponse& r, WireVersion) { r = {RunState::loading_world, failed()}; }
void fill(SetSimulationStateRequest& r, WireVersion) { r.state = RunState::quitting; }
void fill(StepSimulationRequest& r, WireVersion) { r.steps = 0x0123456789abcdefULL; }
void fill(EntityFilters& f, WireVersion) {
  f.filter = "^r[0-9]+$";
  f.categories = {category::kRobot, category::kStaticObject};
  f.tags = {{"team", "red"}, 1};
  f.bounds = {Bounds::kSphere, {Vec3(1, 2, 3), Vec3(4, 0, 0)}};
}
void fill(GetEntitiesResponse& r, WireVersion) { r = {failed(), {"r1", "victim_3", ""}}; }
void fill(EntityRequest& r, WireVersion) { r.entity = "robot_1"; }
void fill(GetEntityStateResponse& r, WireVersion) { r = {failed(), state(1.5)}; }
void fill(GetEntitiesStatesResponse& r, WireVersion) { r = {failed(), {"a", "b"}, {state(1), state(-2)}}; }
void fill(SetEntityStateRequest& r, WireVersion v) {
  r.entity = "r2";
  r.state = state(0.75);
  if (v == WireVersion::v2) {  // 1.x has no flags: the defaults come back
    r.set_pose = false;
    r.set_twist = true;
    r.set_acceleration = true;
  }
}
void fill(GetEntityInfoResponse& r, WireVersion) { r = {failed(), {category::kHuman, "victim", {"warm", "moving"}}}; }
void fill(BoundsResponse& r, WireVersion) { r = {failed(), box()}; }
void fill(TagsFilter& t, WireVersion) { t = {{"start"}, 0}; }
void fill(GetNamedPosesResponse& r, WireVersion) {
  r = {failed(), {{"start_r1", "first robot's start", {"start"}, pose(2)}, {"b", "", {}, pose(-1)}}};
}
void fill(NamedPoseBoundsRequest& r, WireVersion) { r.name = "start_r1"; }
void fill(GetSpawnablesRequest& r, WireVersion) { r.sources = {"file:///models", "package://x"}; }
void fill(GetSpawnablesResponse& r, WireVersion v) {
  // 1.x carries no resource_string
  const std::string text = v == WireVersion::v2 ? "<robot name='p'/>" : "";
  r = {failed(), {{"package://p3at.urdf", text, "Pioneer 3-AT", box()}, {"builtin://rescue", "", "", {}}}};
}
void fill(SpawnRequest& s, WireVersion) {
  s.name = "p3at";
  s.allow_renaming = true;
  s.uri = "file:///tmp/p3at.urdf";
  s.resource_string = "<robot/>";
  s.entity_namespace = "team_b";
  s.frame_id = "map";
  s.pose = pose(3);
}
void fill(SpawnEntityResponse& r, WireVersion) { r = {failed(), "p3at_1"}; }
void fill(GetAvailableWorldsRequest& r, WireVersion) { r = {{"file:///worlds"}, {{"indoor"}, 1}, true, true}; }
WorldResource world() { return {"team", "file:///worlds/team.yaml", "name: team", "three robots", {"indoor", "maze"}}; }
void fill(GetAvailableWorldsResponse& r, WireVersion) { r = {failed(), {world(), {}}}; }
void fill(WorldResponse& r, WireVersion) { r = {failed(), world()}; }
void fill(LoadWorldRequest& r, WireVersion) { r = {"file:///w.sdf", "<sdf/>", true, false}; }
void fill(SendGoalRequest& r, WireVersion) { r = {goal(), 10000}; }
void fill(SendGoalResponse& r, WireVersion) { r = {true, 12'345'678'901}; }
void fill(GetResultRequest& r, WireVersion) { r.goal_id = goal(); }
void fill(GetResultResponse& r, WireVersion) { r = {goal_status::kAborted, failed()}; }
void fill(CancelGoalRequest& r, WireVersion) { r.goal_info = {goal(), 7}; }
void fill(CancelGoalResponse& r, WireVersion) { r = {cancel::kGoalTerminated, {{goal(), 1}, {GoalId{}, -5}}}; }
void fill(FeedbackMessage& f, WireVersion) { f = {goal(), 3, 9997}; }
void fill(GoalStatusArray& s, WireVersion) {
  s.status_list = {{{goal(), 100}, goal_status::kExecuting}, {{GoalId{}, 0}, goal_status::kCanceled}};
}
void fill(ListParametersRequest& r, WireVersion) { r = {{"sim", "ros"}, 2}; }
void fill(ListParametersResult& r, WireVersion) { r = {{"seed", "use_sim_time"}, {"sim"}}; }
void fill(ParameterNames& r, WireVersion) { r.names = {"seed", "world", "realtime_rate"}; }
void fill(GetParametersResponse& r, WireVersion) { r.values = {every_value(), ParameterValue{}}; }
void fill(SetParametersRequest& r, WireVersion) { r.parameters = {{"a", every_value()}, {"b", {}}}; }
void fill(SetParametersResponse& r, WireVersion) { r.results = {{true, ""}, {false, "read-only"}}; }
void fill(SetParameterResult& r, WireVersion) { r = {false, "type mismatch: expected a double"}; }
void fill(DescribeParametersResponse& r, WireVersion) {
  ParameterDescriptorMessage d{"realtime_rate", ParameterValue::kDouble, "x", "> 0", true, true, {{0, 10, 0.5}}, {}};
  ParameterDescriptorMessage i{"seed", ParameterValue::kInteger, "", "", false, false, {}, {{-3, 9, 2}}};
  r.descriptors = {d, i};
}
void fill(GetParameterTypesResponse& r, WireVersion) { r.types = {0, 3, 9}; }

constexpr WireVersion kVersions[] = {WireVersion::v1, WireVersion::v2};

/// value -> bytes -> value; then every prefix of the bytes is refused.
template <class T, class Encode, class Decode>
void check(const char* what, WireVersion v, Encode encode, Decode decode) {
  SCOPED_TRACE(std::string(what) + (v == WireVersion::v1 ? " 1.x" : " 2.x"));
  T value{};
  fill(value, v);
  Bytes bytes;
  encode(value, bytes);
  Bytes plain;
  encode(T{}, plain);
  if (!std::is_same_v<T, Empty>) {
    EXPECT_NE(bytes, plain) << "the sample value is the default";
  }
  const Decoded<T> back = decode(std::span<const std::uint8_t>(bytes));
  ASSERT_TRUE(back.value) << back.problem;
  EXPECT_TRUE(same(*back.value, value, v));
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const Decoded<T> cut = decode(std::span<const std::uint8_t>(bytes.data(), n));
    ASSERT_FALSE(cut.value) << "a prefix of " << n << " of " << bytes.size() << " bytes decoded";
    ASSERT_EQ(cut.problem.rfind(what, 0), 0u) << cut.problem;
  }
}

template <class S>
void check_service(WireVersion v) {
  const std::string ros = info(S::id).ros_type;
  check<typename S::Request>(
      (ros + "_Request").c_str(), v, [&](const auto& x, Bytes& out) { encode_request<S>(x, v, out); },
      [&](std::span<const std::uint8_t> b) { return decode_request<S>(b, v); });
  check<typename S::Response>(
      (ros + "_Response").c_str(), v, [&](const auto& x, Bytes& out) { encode_response<S>(x, v, out); },
      [&](std::span<const std::uint8_t> b) { return decode_response<S>(b, v); });
}

template <class M>
void check_topic(WireVersion v) {
  check<typename M::Message>(
      info(M::id).ros_type, v, [&](const auto& x, Bytes& out) { encode_message<M>(x, v, out); },
      [&](std::span<const std::uint8_t> b) { return decode_message<M>(b, v); });
}

TEST(ControlCdrRoundTrip, EveryServiceBothWaysInBothVersions) {
  for (const WireVersion v : kVersions) {
    std::apply([&](auto... s) { (check_service<decltype(s)>(v), ...); }, AllServices{});
  }
}

TEST(ControlCdrRoundTrip, EveryActionTopicInBothVersions) {
  for (const WireVersion v : kVersions) {
    std::apply([&](auto... m) { (check_topic<decltype(m)>(v), ...); }, AllMessages{});
  }
}

TEST(ControlCdrRoundTrip, WhatA1xBodyCannotCarryIsDropped) {
  // SpawnEntity's initial_pose stamp is not kept by SpawnRequest; a 1.x Spawnable has no resource_string
  GetSpawnablesResponse r;
  r.spawnables.push_back({"u", "<robot/>", "d", {}});
  Bytes b;
  encode_response<iface::GetSpawnables>(r, WireVersion::v1, b);
  const auto d = decode_response<iface::GetSpawnables>(b, WireVersion::v1);
  ASSERT_TRUE(d.value) << d.problem;
  EXPECT_EQ(d.value->spawnables.at(0).resource_string, "");
  SetEntityStateRequest s;
  s.set_pose = false;
  Bytes e;
  encode_request<iface::SetEntityState>(s, WireVersion::v1, e);
  const auto f = decode_request<iface::SetEntityState>(e, WireVersion::v1);
  ASSERT_TRUE(f.value) << f.problem;
  EXPECT_TRUE(f.value->set_pose);
}

}  // namespace
}  // namespace rescuesim::control
