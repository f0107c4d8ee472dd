// The control interfaces' CDR bodies (bridges/common/control_cdr.h): bytes worked out by hand
// from the interface texts (XCDR1 little endian: each primitive aligned to its size counted
// from after the 4-byte encapsulation header; string = uint32 length with the NUL, bytes, NUL;
// sequence = uint32 count, elements aligned only when there is one), the errors a malformed
// body gets, the interface table. Round trips and truncations of every codec are in
// control_cdr_round_trip_test.cpp.

#include "bridges/common/control_cdr.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"

namespace rescuesim::control {
namespace {

using Bytes = std::vector<std::uint8_t>;
using V = WireVersion;

template <class S>
Bytes request_bytes(const typename S::Request& r, WireVersion v) {
  Bytes out;
  encode_request<S>(r, v, out);
  return out;
}
template <class S>
Bytes response_bytes(const typename S::Response& r, WireVersion v) {
  Bytes out;
  encode_response<S>(r, v, out);
  return out;
}

// ---- requests ----

TEST(ControlCdr, ResetSimulationRequestIsTheScopeByte) {
  const Bytes expected = {
      0x00, 0x01, 0x00, 0x00,  // encapsulation: CDR_LE, no options
      0x04,                    // scope = SCOPE_SPAWNED
  };
  EXPECT_EQ(request_bytes<iface::ResetSimulation>({scope::kSpawned}, V::v1), expected);
  EXPECT_EQ(request_bytes<iface::ResetSimulation>({scope::kSpawned}, V::v2), expected);
  const auto d = decode_request<iface::ResetSimulation>(expected, V::v1);
  ASSERT_TRUE(d.value) << d.problem;
  EXPECT_EQ(d.value->scope, scope::kSpawned);
  EXPECT_EQ(d.problem, "");
}

TEST(ControlCdr, StepSimulationRequestIsOneUint64) {
  const Bytes expected = {
      0x00, 0x01, 0x00, 0x00,                          // encapsulation
      0xc8, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // steps = 200 (offset 0: aligned)
  };
  EXPECT_EQ(request_bytes<iface::StepSimulation>({200}, V::v1), expected);
  const auto d = decode_request<iface::StepSimulation>(expected, V::v2);
  ASSERT_TRUE(d.value) << d.problem;
  EXPECT_EQ(d.value->steps, 200u);
  // the struct's default is the .srv's default (`uint64 steps 1`)
  EXPECT_EQ(StepSimulationRequest{}.steps, 1u);
}

TEST(ControlCdr, AnEmptyRequestIsTheOneByteRosidlAddsToAnEmptyStruct) {
  const Bytes expected = {0x00, 0x01, 0x00, 0x00, 0x00};  // structure_needs_at_least_one_member = 0
  EXPECT_EQ(request_bytes<iface::GetSimulatorFeatures>({}, V::v1), expected);
  EXPECT_EQ(request_bytes<iface::GetSimulationState>({}, V::v1), expected);
  EXPECT_TRUE(decode_request<iface::UnloadWorld>(expected, V::v2).value);
  const auto none = decode_request<iface::GetCurrentWorld>(Bytes{0x00, 0x01, 0x00, 0x00}, V::v2);
  EXPECT_FALSE(none.value);
  EXPECT_EQ(none.problem,
            "simulation_interfaces/srv/GetCurrentWorld_Request: structure_needs_at_least_one_member: 1 byte needed, 0 "
            "left");
}

/// r1 teleported to (1, 2, 3), facing +x, moving 0.5 m/s forward and turning 0.25 rad/s; stamp 1.5 s.
SetEntityStateRequest teleport() {
  SetEntityStateRequest r;
  r.entity = "r1";
  r.state.stamp_ns = 1'500'000'000;
  r.state.pose.p = Vec3(1, 2, 3);
  r.state.pose.q = Quat::Identity();
  r.state.linear = Vec3(0.5, 0, 0);
  r.state.angular = Vec3(0, 0, 0.25);
  r.set_pose = true;
  r.set_twist = false;
  r.set_acceleration = true;
  return r;
}

// SetEntityState_Request in 1.x: entity, state (EntityState: Header, Pose, Twist, Accel).
const Bytes kTeleportV1 = {
    0x00, 0x01, 0x00, 0x00,                          // encapsulation
    0x03, 0x00, 0x00, 0x00, 'r', '1', 0x00,          //  0: entity: length 3, "r1", NUL
    0x00,                                            //  7: padding to 4
    0x01, 0x00, 0x00, 0x00,                          //  8: state.header.stamp.sec = 1
    0x00, 0x65, 0xcd, 0x1d,                          // 12: state.header.stamp.nanosec = 500000000
    0x01, 0x00, 0x00, 0x00, 0x00,                    // 16: state.header.frame_id: length 1, "" + NUL
    0x00, 0x00, 0x00,                                // 21: padding to 8
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf0, 0x3f,  // 24: state.pose.position.x = 1.0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x40,  // 32: .y = 2.0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x08, 0x40,  // 40: .z = 3.0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 48: state.pose.orientation.x = 0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 56: .y = 0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 64: .z = 0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf0, 0x3f,  // 72: .w = 1.0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xe0, 0x3f,  // 80: state.twist.linear.x = 0.5
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 88: .y
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 96: .z
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 104: state.twist.angular.x
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 112: .y
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xd0, 0x3f,  // 120: .z = 0.25
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 128: state.acceleration.linear.x
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 136: .y
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 144: .z
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 152: state.acceleration.angular.x
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 160: .y
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 168: .z; 176 bytes in all
};

TEST(ControlCdr, SetEntityStateRequestIn1xIsEntityThenState) {
  EXPECT_EQ(kTeleportV1.size(), 4u + 176);
  EXPECT_EQ(request_bytes<iface::SetEntityState>(teleport(), V::v1), kTeleportV1);  // the flags are not on the wire
  const auto d = decode_request<iface::SetEntityState>(kTeleportV1, V::v1);
  ASSERT_TRUE(d.value) << d.problem;
  const SetEntityStateRequest& r = *d.value;
  EXPECT_EQ(r.entity, "r1");
  EXPECT_EQ(r.state.stamp_ns, 1'500'000'000);
  EXPECT_EQ(r.state.frame_id, "");
  EXPECT_EQ(r.state.pose.p, Vec3(1, 2, 3));
  EXPECT_EQ(r.state.pose.q.coeffs(), Quat::Identity().coeffs());
  EXPECT_EQ(r.state.linear, Vec3(0.5, 0, 0));
  EXPECT_EQ(r.state.angular, Vec3(0, 0, 0.25));
  EXPECT_EQ(r.state.linear_acc, Vec3::Zero());
  // a 1.x request sets pose and twist
  EXPECT_TRUE(r.set_pose);
  EXPECT_TRUE(r.set_twist);
  EXPECT_FALSE(r.set_acceleration);
}

TEST(ControlCdr, SetEntityStateRequestIn2xAddsTheThreeFlags) {
  Bytes expected = kTeleportV1;
  expected.insert(expected.end(), {
                                      0x01,  // 176: set_pose = true
                                      0x00,  // 177: set_twist = false
                                      0x01,  // 178: set_acceleration = true
                                  });
  EXPECT_EQ(request_bytes<iface::SetEntityState>(teleport(), V::v2), expected);
  const auto d = decode_request<iface::SetEntityState>(expected, V::v2);
  ASSERT_TRUE(d.value) << d.problem;
  EXPECT_TRUE(d.value->set_pose);
  EXPECT_FALSE(d.value->set_twist);
  EXPECT_TRUE(d.value->set_acceleration);
  // each version refuses the other's request: 3 bytes too many, or the flags missing
  const auto as_v1 = decode_request<iface::SetEntityState>(expected, V::v1);
  EXPECT_EQ(as_v1.problem, "simulation_interfaces/srv/SetEntityState_Request: 3 trailing bytes after the message");
  const auto as_v2 = decode_request<iface::SetEntityState>(kTeleportV1, V::v2);
  EXPECT_EQ(as_v2.problem, "simulation_interfaces/srv/SetEntityState_Request: set_pose: 1 byte needed, 0 left");
}

TEST(ControlCdr, ATruncatedRequestNamesTheFieldItEndsIn) {
  // orientation.w sits at body offset 72..79: keep 2 of its bytes
  const Bytes cut(kTeleportV1.begin(), kTeleportV1.begin() + 4 + 74);
  const auto d = decode_request<iface::SetEntityState>(cut, V::v1);
  EXPECT_FALSE(d.value);
  EXPECT_EQ(d.problem, "simulation_interfaces/srv/SetEntityState_Request: state.pose.orientation.w: 8 bytes needed, 2 left");
  // inside the padding before position.x (body offset 21..23, then the double at 24)
  const Bytes in_pad(kTeleportV1.begin(), kTeleportV1.begin() + 4 + 22);
  EXPECT_EQ(decode_request<iface::SetEntityState>(in_pad, V::v1).problem,
            "simulation_interfaces/srv/SetEntityState_Request: state.pose.position.x: 11 bytes needed (3 of them "
            "alignment padding), 1 left");
}

TEST(ControlCdr, NanPosesPassThroughTheCodec) {
  SetEntityStateRequest r = teleport();
  r.state.pose.q.w() = std::nan("");
  const auto d = decode_request<iface::SetEntityState>(request_bytes<iface::SetEntityState>(r, V::v2), V::v2);
  ASSERT_TRUE(d.value) << d.problem;
  EXPECT_TRUE(std::isnan(d.value->state.pose.q.w()));
}

TEST(ControlCdr, SpawnEntityAndLoadWorldRequestsAreTheSameBytesInBothVersions) {
  SpawnRequest s;
  s.name = "p3at";
  s.allow_renaming = true;
  s.uri = "package://p3at/p3at.urdf";
  s.entity_namespace = "team";
  s.frame_id = "world";
  s.pose.p = Vec3(1, -1, 0);
  EXPECT_EQ(request_bytes<iface::SpawnEntity>(s, V::v1), request_bytes<iface::SpawnEntity>(s, V::v2));
  LoadWorldRequest w;
  w.resource_string = "<sdf/>";
  w.ignore_missing_or_unsupported_assets = true;
  EXPECT_EQ(request_bytes<iface::LoadWorld>(w, V::v1), request_bytes<iface::LoadWorld>(w, V::v2));
  // but the field names in errors are each version's
  const Bytes only_name = {0x00, 0x01, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00, 0x01};  // name "", allow_renaming
  EXPECT_EQ(decode_request<iface::SpawnEntity>(only_name, V::v1).problem,
            "simulation_interfaces/srv/SpawnEntity_Request: uri: 6 bytes needed (2 of them alignment padding), 0 left");
  EXPECT_EQ(decode_request<iface::SpawnEntity>(only_name, V::v2).problem,
            "simulation_interfaces/srv/SpawnEntity_Request: entity_resource.uri: 6 bytes needed (2 of them alignment "
            "padding), 0 left");
}

TEST(ControlCdr, SpawnablesDifferBetweenVersions) {
  GetSpawnablesResponse r;
  r.spawnables.push_back({"package://a.urdf", "<robot/>", "a", {}});
  const Bytes v1 = response_bytes<iface::GetSpawnables>(r, V::v1);
  const Bytes v2 = response_bytes<iface::GetSpawnables>(r, V::v2);
  // body: 0 result.result, 4 result.error_message (4 + 1), 12 spawnables count, 16 [0].uri (4 + 17);
  // 1.x: 40 description (4 + 2), 46 spawn_bounds.type, 48 points count: 52 bytes;
  // 2.x: 40 entity_resource.resource_string (4 + 9), 56 description, 62 type, 64 count: 68 bytes
  EXPECT_EQ(v1.size(), 4u + 52);
  EXPECT_EQ(v2.size(), 4u + 68);
  const auto d1 = decode_response<iface::GetSpawnables>(v1, V::v1);
  ASSERT_TRUE(d1.value) << d1.problem;
  EXPECT_EQ(d1.value->spawnables.at(0).uri, "package://a.urdf");
  EXPECT_EQ(d1.value->spawnables.at(0).resource_string, "");  // 1.x has no place for it
  const auto d2 = decode_response<iface::GetSpawnables>(v2, V::v2);
  ASSERT_TRUE(d2.value) << d2.problem;
  EXPECT_EQ(d2.value->spawnables.at(0).resource_string, "<robot/>");
}

// ---- responses ----

TEST(ControlCdr, GetEntityStateResponse) {
  GetEntityStateResponse r;
  r.result = Result::ok();
  r.state.stamp_ns = 3'000'000'007;
  r.state.frame_id = "world";
  r.state.pose.p = Vec3(-1, 0, 0.5);
  r.state.linear = Vec3(0, 2, 0);
  r.state.angular_acc = Vec3(0, 0, -0.5);
  const Bytes expected = {
      0x00, 0x01, 0x00, 0x00,                          // encapsulation
      0x01,                                            //  0: result.result = RESULT_OK
      0x00, 0x00, 0x00,                                //  1: padding to 4
      0x01, 0x00, 0x00, 0x00, 0x00,                    //  4: result.error_message: length 1, ""
      0x00, 0x00, 0x00,                                //  9: padding to 4
      0x03, 0x00, 0x00, 0x00,                          // 12: state.header.stamp.sec = 3
      0x07, 0x00, 0x00, 0x00,                          // 16: state.header.stamp.nanosec = 7
      0x06, 0x00, 0x00, 0x00, 'w', 'o', 'r', 'l', 'd', 0x00,  // 20: state.header.frame_id "world"
      0x00, 0x00,                                      // 30: padding to 8
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf0, 0xbf,  // 32: state.pose.position.x = -1.0
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 40: .y = 0
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xe0, 0x3f,  // 48: .z = 0.5
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 56: orientation.x
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 64: .y
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 72: .z
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf0, 0x3f,  // 80: .w = 1.0
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 88: state.twist.linear.x
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x40,  // 96: .y = 2.0
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 104: .z
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 112: state.twist.angular.x
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 120: .y
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 128: .z
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 136: state.acceleration.linear.x
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 144: .y
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 152: .z
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 160: state.acceleration.angular.x
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 168: .y
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xe0, 0xbf,  // 176: .z = -0.5; 184 bytes in all
  };
  EXPECT_EQ(expected.size(), 4u + 184);
  EXPECT_EQ(response_bytes<iface::GetEntityState>(r, V::v1), expected);
  const auto d = decode_response<iface::GetEntityState>(expected, V::v2);
  ASSERT_TRUE(d.value) << d.problem;
  EXPECT_EQ(d.value->result.result, code::kOk);
  EXPECT_EQ(d.value->state.stamp_ns, 3'000'000'007);
  EXPECT_EQ(d.value->state.frame_id, "world");
  EXPECT_EQ(d.value->state.pose.p, Vec3(-1, 0, 0.5));
  EXPECT_EQ(d.value->state.linear, Vec3(0, 2, 0));
  EXPECT_EQ(d.value->state.angular_acc, Vec3(0, 0, -0.5));
}

TEST(ControlCdr, GetSimulatorFeaturesResponse) {
  SimulatorFeatures f;
  f.features = {feature::kSpawning, feature::kSimulationReset, feature::kStepSimulationAction};
  f.spawn_formats = {"urdf", "sdf"};
  f.custom_info = "rescuesim";
  const Bytes expected = {
      0x00, 0x01, 0x00, 0x00,                    // encapsulation
      0x03, 0x00, 0x00, 0x00,                    //  0: features.features: 3 elements
      0x00, 0x00, 0x14, 0x00, 0x21, 0x00,        //  4: 0 SPAWNING, 20 SIMULATION_RESET, 33 STEP_SIMULATION_ACTION
      0x00, 0x00,                                // 10: padding to 4
      0x02, 0x00, 0x00, 0x00,                    // 12: features.spawn_formats: 2 elements
      0x05, 0x00, 0x00, 0x00, 'u', 'r', 'd', 'f', 0x00,  // 16: "urdf"
      0x00, 0x00, 0x00,                          // 25: padding to 4
      0x04, 0x00, 0x00, 0x00, 's', 'd', 'f', 0x00,  // 28: "sdf"
      0x0a, 0x00, 0x00, 0x00,                    // 36: features.custom_info: length 10
      'r', 'e', 's', 'c', 'u', 'e', 's', 'i', 'm', 0x00,  // 40: "rescuesim"; 50 bytes in all
  };
  EXPECT_EQ(response_bytes<iface::GetSimulatorFeatures>(f, V::v2), expected);
  const auto d = decode_response<iface::GetSimulatorFeatures>(expected, V::v1);
  ASSERT_TRUE(d.value) << d.problem;
  EXPECT_EQ(d.value->features, f.features);
  EXPECT_EQ(d.value->spawn_formats, f.spawn_formats);
  EXPECT_EQ(d.value->custom_info, "rescuesim");
}

TEST(ControlCdr, GetSimulationStateResponseHasTheStateFirst) {
  const Bytes expected = {
      0x00, 0x01, 0x00, 0x00,              // encapsulation
      0x02,                                // 0: state.state = STATE_PAUSED
      0x01,                                // 1: result.result = RESULT_OK
      0x00, 0x00,                          // 2: padding to 4
      0x01, 0x00, 0x00, 0x00, 0x00,        // 4: result.error_message ""
  };
  EXPECT_EQ(response_bytes<iface::GetSimulationState>({RunState::paused, Result::ok()}, V::v1), expected);
  const auto d = decode_response<iface::GetSimulationState>(expected, V::v1);
  ASSERT_TRUE(d.value) << d.problem;
  EXPECT_EQ(d.value->state, RunState::paused);
}

TEST(ControlCdr, SendGoalResponseStampIsFlooredAndClampedToInt32Seconds) {
  // accepted, then Time: -1 ns is sec -1 + 999999999 ns
  const Bytes expected = {
      0x00, 0x01, 0x00, 0x00,  // encapsulation
      0x01,                    // 0: accepted
      0x00, 0x00, 0x00,        // 1: padding to 4
      0xff, 0xff, 0xff, 0xff,  // 4: stamp.sec = -1
      0xff, 0xc9, 0x9a, 0x3b,  // 8: stamp.nanosec = 999999999
  };
  EXPECT_EQ(response_bytes<iface::SimulateStepsSendGoal>({true, -1}, V::v1), expected);
  const auto d = decode_response<iface::SimulateStepsSendGoal>(expected, V::v1);
  ASSERT_TRUE(d.value) << d.problem;
  EXPECT_EQ(d.value->stamp_ns, -1);
  // beyond int32 seconds: the largest Time there is
  const Bytes late = response_bytes<iface::SimulateStepsSendGoal>({true, std::int64_t{1} << 62}, V::v1);
  EXPECT_EQ(Bytes(late.begin() + 8, late.end()), (Bytes{0xff, 0xff, 0xff, 0x7f, 0xff, 0xc9, 0x9a, 0x3b}));
}

TEST(ControlCdr, SimulateStepsGoalResultAndFeedbackLayouts) {
  SendGoalRequest g;
  for (int i = 0; i < 16; ++i) g.goal_id[i] = static_cast<std::uint8_t>(0xa0 + i);
  g.steps = 2000;
  const Bytes goal = {
      0x00, 0x01, 0x00, 0x00,                                                          // encapsulation
      0xa0, 0xa1, 0xa2, 0xa3, 0xa4, 0xa5, 0xa6, 0xa7, 0xa8, 0xa9, 0xaa, 0xab, 0xac, 0xad, 0xae, 0xaf,  // goal_id.uuid
      0xd0, 0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,                                  // 16: goal.steps = 2000
  };
  EXPECT_EQ(request_bytes<iface::SimulateStepsSendGoal>(g, V::v1), goal);
  const Bytes result = {
      0x00, 0x01, 0x00, 0x00,                          // encapsulation
      0x04,                                            // 0: status = STATUS_SUCCEEDED
      0x01,                                            // 1: result.result.result = RESULT_OK
      0x00, 0x00,                                      // 2: padding to 4
      0x01, 0x00, 0x00, 0x00, 0x00,                    // 4: result.result.error_message ""
  };
  EXPECT_EQ(response_bytes<iface::SimulateStepsGetResult>({goal_status::kSucceeded, Result::ok()}, V::v1), result);
  FeedbackMessage f;
  f.goal_id = g.goal_id;
  f.completed_steps = 3;
  f.remaining_steps = 1997;
  Bytes feedback(goal.begin(), goal.begin() + 20);  // encapsulation + goal_id
  feedback.insert(feedback.end(), {0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,    // 16: feedback.completed_steps
                                   0xcd, 0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00});  // 24: feedback.remaining_steps
  Bytes out;
  encode_message<iface::SimulateStepsFeedback>(f, V::v1, out);
  EXPECT_EQ(out, feedback);
}

// ---- rcl_interfaces ----

TEST(ControlCdr, SetParametersRequest) {
  SetParametersRequest r;
  r.parameters.push_back({"rate", {}});
  r.parameters[0].value.type = ParameterValue::kDouble;
  r.parameters[0].value.double_value = 2.0;
  r.parameters.push_back({"use_sim_time", {}});
  r.parameters[1].value.type = ParameterValue::kBool;
  r.parameters[1].value.bool_value = true;
  const Bytes expected = {
      0x00, 0x01, 0x00, 0x00,                          // encapsulation
      0x02, 0x00, 0x00, 0x00,                          //   0: parameters: 2 elements
      0x05, 0x00, 0x00, 0x00, 'r', 'a', 't', 'e', 0x00,  //   4: [0].name "rate"
      0x03,                                            //  13: [0].value.type = PARAMETER_DOUBLE
      0x00,                                            //  14: .bool_value
      0x00,                                            //  15: padding to 8
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //  16: .integer_value
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x40,  //  24: .double_value = 2.0
      0x01, 0x00, 0x00, 0x00, 0x00,                    //  32: .string_value ""
      0x00, 0x00, 0x00,                                //  37: padding to 4
      0x00, 0x00, 0x00, 0x00,                          //  40: .byte_array_value: 0 elements
      0x00, 0x00, 0x00, 0x00,                          //  44: .bool_array_value: 0
      0x00, 0x00, 0x00, 0x00,                          //  48: .integer_array_value: 0 (no alignment to 8 when empty)
      0x00, 0x00, 0x00, 0x00,                          //  52: .double_array_value: 0
      0x00, 0x00, 0x00, 0x00,                          //  56: .string_array_value: 0
      0x0d, 0x00, 0x00, 0x00,                          //  60: [1].name: length 13
      'u', 's', 'e', '_', 's', 'i', 'm', '_', 't', 'i', 'm', 'e', 0x00,  //  64: "use_sim_time"
      0x01,                                            //  77: [1].value.type = PARAMETER_BOOL
      0x01,                                            //  78: .bool_value = true
      0x00,                                            //  79: padding to 8
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //  80: .integer_value
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //  88: .double_value
      0x01, 0x00, 0x00, 0x00, 0x00,                    //  96: .string_value ""
      0x00, 0x00, 0x00,                                // 101: padding to 4
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 104: byte_array, bool_array
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 112: integer_array, double_array
      0x00, 0x00, 0x00, 0x00,                          // 120: string_array; 124 bytes in all
  };
  EXPECT_EQ(request_bytes<iface::SetParameters>(r, V::v1), expected);
  EXPECT_EQ(request_bytes<iface::SetParametersAtomically>(r, V::v1), expected);  // the same request type
  const auto d = decode_request<iface::SetParameters>(expected, V::v1);
  ASSERT_TRUE(d.value) << d.problem;
  ASSERT_EQ(d.value->parameters.size(), 2u);
  EXPECT_EQ(d.value->parameters[0].name, "rate");
  EXPECT_EQ(d.value->parameters[0].value.type, ParameterValue::kDouble);
  EXPECT_EQ(d.value->parameters[0].value.double_value, 2.0);
  EXPECT_EQ(d.value->parameters[1].name, "use_sim_time");
  EXPECT_TRUE(d.value->parameters[1].value.bool_value);
}

TEST(ControlCdr, GetParametersResponse) {
  GetParametersResponse r;
  r.values.resize(2);
  r.values[0].type = ParameterValue::kString;
  r.values[0].string_value = "sim";
  r.values[1].type = ParameterValue::kIntegerArray;
  r.values[1].integer_array_value = {-1, 5};
  const Bytes expected = {
      0x00, 0x01, 0x00, 0x00,                          // encapsulation
      0x02, 0x00, 0x00, 0x00,                          //   0: values: 2 elements
      0x04,                                            //   4: [0].type = PARAMETER_STRING
      0x00,                                            //   5: .bool_value
      0x00, 0x00,                                      //   6: padding to 8
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //   8: .integer_value
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //  16: .double_value
      0x04, 0x00, 0x00, 0x00, 's', 'i', 'm', 0x00,     //  24: .string_value "sim"
      0x00, 0x00, 0x00, 0x00,                          //  32: .byte_array_value: 0
      0x00, 0x00, 0x00, 0x00,                          //  36: .bool_array_value: 0
      0x00, 0x00, 0x00, 0x00,                          //  40: .integer_array_value: 0
      0x00, 0x00, 0x00, 0x00,                          //  44: .double_array_value: 0
      0x00, 0x00, 0x00, 0x00,                          //  48: .string_array_value: 0
      0x07,                                            //  52: [1].type = PARAMETER_INTEGER_ARRAY
      0x00,                                            //  53: .bool_value
      0x00, 0x00,                                      //  54: padding to 8
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //  56: .integer_value
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //  64: .double_value
      0x01, 0x00, 0x00, 0x00, 0x00,                    //  72: .string_value ""
      0x00, 0x00, 0x00,                                //  77: padding to 4
      0x00, 0x00, 0x00, 0x00,                          //  80: .byte_array_value: 0
      0x00, 0x00, 0x00, 0x00,                          //  84: .bool_array_value: 0
      0x02, 0x00, 0x00, 0x00,                          //  88: .integer_array_value: 2 elements
      0x00, 0x00, 0x00, 0x00,                          //  92: padding to 8 (the sequence is not empty)
      0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff,  //  96: -1
      0x05, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 104: 5
      0x00, 0x00, 0x00, 0x00,                          // 112: .double_array_value: 0
      0x00, 0x00, 0x00, 0x00,                          // 116: .string_array_value: 0; 120 bytes in all
  };
  EXPECT_EQ(response_bytes<iface::GetParameters>(r, V::v1), expected);
  const auto d = decode_response<iface::GetParameters>(expected, V::v1);
  ASSERT_TRUE(d.value) << d.problem;
  ASSERT_EQ(d.value->values.size(), 2u);
  EXPECT_EQ(d.value->values[0].string_value, "sim");
  EXPECT_EQ(d.value->values[1].integer_array_value, (std::vector<std::int64_t>{-1, 5}));
}

TEST(ControlCdr, ParameterDescriptorRangesAreBoundedToOne) {
  ParameterDescriptor rate{"realtime_rate", ParameterValue::kDouble, "wall-clock factor", false, std::pair{0.0, 100.0}};
  const ParameterDescriptorMessage m = descriptor_message(rate);
  ASSERT_EQ(m.floating_point_range.size(), 1u);
  EXPECT_EQ(m.floating_point_range[0].to_value, 100.0);
  EXPECT_TRUE(m.integer_range.empty());
  const ParameterDescriptorMessage i =
      descriptor_message({"seed", ParameterValue::kInteger, "", true, std::pair{0.4, 10.6}});
  ASSERT_EQ(i.integer_range.size(), 1u);
  EXPECT_EQ(i.integer_range[0].from_value, 0);
  EXPECT_EQ(i.integer_range[0].to_value, 11);
  EXPECT_TRUE(i.read_only);

  // two ranges: the encoder refuses, the decoder names the field
  DescribeParametersResponse two;
  two.descriptors.push_back(m);
  two.descriptors[0].floating_point_range.push_back({1, 2, 0});
  Bytes out;
  EXPECT_THROW(encode_response<iface::DescribeParameters>(two, V::v1, out), Error);
  DescribeParametersResponse one;
  one.descriptors.push_back(m);
  Bytes bytes = response_bytes<iface::DescribeParameters>(one, V::v1);
  // body: 0 descriptors count; 4 [0].name (4 + 14); 22 type; 23 padding; 24 description (4 + 18);
  // 46 padding; 48 additional_constraints (4 + 1); 53 read_only; 54 dynamic_typing; 55 padding;
  // 56 floating_point_range count
  const std::size_t count_at = 4 + 56;
  ASSERT_EQ(bytes.at(count_at), 1);
  bytes[count_at] = 2;
  EXPECT_EQ(decode_response<iface::DescribeParameters>(bytes, V::v1).problem,
            "rcl_interfaces/srv/DescribeParameters_Response: descriptors[0].floating_point_range: sequence of 2 "
            "elements, but it is bounded to 1");
}

// ---- malformed input ----

TEST(ControlCdr, AbsurdSequenceLengthsNameTheField) {
  const Bytes spawnables = {0x00, 0x01, 0x00, 0x00, 0xff, 0xff, 0xff, 0xff};
  EXPECT_EQ(decode_request<iface::GetSpawnables>(spawnables, V::v2).problem,
            "simulation_interfaces/srv/GetSpawnables_Request: sources: sequence of 4294967295 elements needs at least "
            "21474836475 bytes, 0 left");
  // Parameter: at least name (5) + ParameterValue (1 + 1 + 8 + 8 + 5 + 5 * 4) = 48 bytes
  EXPECT_EQ(decode_request<iface::SetParameters>(spawnables, V::v1).problem,
            "rcl_interfaces/srv/SetParameters_Request: parameters: sequence of 4294967295 elements needs at least "
            "206158430160 bytes, 0 left");
  EXPECT_EQ(decode_response<iface::GetSimulatorFeatures>(spawnables, V::v1).problem,
            "simulation_interfaces/srv/GetSimulatorFeatures_Response: features.features: sequence of 4294967295 "
            "elements needs 8589934590 bytes, 0 left");
  const Bytes categories = {0x00, 0x01, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00,  // filters.filter ""
                            0x00, 0x00, 0x00,                                      // padding
                            0xff, 0xff, 0xff, 0xff};                               // filters.categories
  EXPECT_EQ(decode_request<iface::GetEntities>(categories, V::v1).problem,
            "simulation_interfaces/srv/GetEntities_Request: filters.categories: sequence of 4294967295 elements needs "
            "at least 4294967295 bytes, 0 left");
  const Bytes entity = {0x00, 0x01, 0x00, 0x00, 0xff, 0xff, 0xff, 0xff, 'r', '1', 0x00};
  EXPECT_EQ(decode_request<iface::DeleteEntity>(entity, V::v1).problem,
            "simulation_interfaces/srv/DeleteEntity_Request: entity: 4294967295 bytes needed, 3 left");
  // a tag string element
  const Bytes tags = {0x00, 0x01, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x05, 0x00, 0x00, 0x00, 'a', 'b'};
  EXPECT_EQ(decode_request<iface::GetNamedPoses>(tags, V::v1).problem,
            "simulation_interfaces/srv/GetNamedPoses_Request: tags.tags[0]: 5 bytes needed, 2 left");
}

TEST(ControlCdr, BadStringsAndEncapsulationsAreRefused) {
  EXPECT_EQ(decode_request<iface::DeleteEntity>(Bytes{0x00, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, V::v1).problem,
            "simulation_interfaces/srv/DeleteEntity_Request: entity: string length 0 (a CDR string counts its "
            "terminating NUL)");
  EXPECT_EQ(decode_request<iface::DeleteEntity>(Bytes{0x00, 0x01, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 'a', 'b'}, V::v1)
                .problem,
            "simulation_interfaces/srv/DeleteEntity_Request: entity: string of 2 bytes does not end in NUL");
  EXPECT_EQ(decode_request<iface::ResetSimulation>(Bytes{0x00, 0x00, 0x00, 0x00, 0x01}, V::v1).problem,
            "simulation_interfaces/srv/ResetSimulation_Request: encapsulation 00 00 (big-endian CDR) is not supported; "
            "expected 00 01 (XCDR1 little endian)");
  EXPECT_EQ(decode_request<iface::ResetSimulation>(Bytes{0x00, 0x01, 0x00}, V::v1).problem,
            "simulation_interfaces/srv/ResetSimulation_Request: CDR data of 3 bytes is shorter than the 4-byte "
            "encapsulation header");
}

TEST(ControlCdr, TrailingBytesOnlyAsPaddingAnnouncedOrToAMultipleOfFour) {
  using RS = iface::ResetSimulation;
  // rmw_cyclonedds rounds a sample up to 4 bytes with zeros and announces nothing
  EXPECT_TRUE(decode_request<RS>(Bytes{0x00, 0x01, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00}, V::v1).value);
  // ... but a fourth byte, or one that is not zero, is not that
  EXPECT_EQ(decode_request<RS>(Bytes{0x00, 0x01, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x00}, V::v1).problem,
            "simulation_interfaces/srv/ResetSimulation_Request: 4 trailing bytes after the message");
  EXPECT_EQ(decode_request<RS>(Bytes{0x00, 0x01, 0x00, 0x00, 0x02, 0x00, 0x07, 0x00}, V::v1).problem,
            "simulation_interfaces/srv/ResetSimulation_Request: 3 trailing bytes after the message");
  // padding the options announce (their two low bits), whatever its bytes
  EXPECT_TRUE(decode_request<RS>(Bytes{0x00, 0x01, 0x00, 0x03, 0x02, 0xaa, 0xbb, 0xcc}, V::v1).value);
  EXPECT_EQ(decode_request<RS>(Bytes{0x00, 0x01, 0x00, 0x01, 0x02, 0xaa, 0xbb}, V::v1).problem,
            "simulation_interfaces/srv/ResetSimulation_Request: 2 trailing bytes after the message (the encapsulation "
            "options allow 1)");
}

// ---- the interface table ----

TEST(ControlCdr, TheTableListsEveryInterfaceInOrderWithRmwTypeNames) {
  const auto all = interfaces();
  ASSERT_EQ(all.size(), static_cast<std::size_t>(Interface::get_parameter_types) + 1);
  EXPECT_EQ(std::tuple_size_v<AllServices> + std::tuple_size_v<AllMessages>, all.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    const InterfaceInfo& e = all[i];
    EXPECT_EQ(static_cast<std::size_t>(e.id), i);
    EXPECT_EQ(&info(e.id), &e);
    // "pkg/kind/Name" -> "pkg::kind::dds_::Name_Request_" (rmw_cyclonedds namespace_prefix, make_fqtopic)
    const std::string ros = e.ros_type;
    const auto a = ros.find('/'), b = ros.rfind('/');
    ASSERT_NE(a, b) << ros;
    const std::string prefix = ros.substr(0, a) + "::" + ros.substr(a + 1, b - a - 1) + "::dds_::" + ros.substr(b + 1);
    if (e.kind == EndpointKind::action_topic) {
      EXPECT_EQ(e.dds_request, prefix + "_") << ros;
      EXPECT_EQ(e.dds_response, nullptr);
    } else {
      EXPECT_EQ(e.dds_request, prefix + "_Request_") << ros;
      ASSERT_NE(e.dds_response, nullptr);
      EXPECT_EQ(e.dds_response, prefix + "_Response_") << ros;
    }
    for (std::size_t j = 0; j < i; ++j) EXPECT_STRNE(all[j].name, e.name);
  }
  EXPECT_STREQ(info(Interface::reset_simulation).dds_request, "simulation_interfaces::srv::dds_::ResetSimulation_Request_");
  EXPECT_STREQ(info(Interface::reset_simulation).ros_type, "simulation_interfaces/srv/ResetSimulation");
  EXPECT_STREQ(info(Interface::simulate_steps_send_goal).dds_response,
               "simulation_interfaces::action::dds_::SimulateSteps_SendGoal_Response_");
  EXPECT_STREQ(info(Interface::simulate_steps_status).dds_request, "action_msgs::msg::dds_::GoalStatusArray_");
  EXPECT_STREQ(info(Interface::list_parameters).name, "list_parameters");
  EXPECT_EQ(info(Interface::list_parameters).kind, EndpointKind::node_service);
}

}  // namespace
}  // namespace rescuesim::control
