// The run's control surface over ROS 2, end to end: a Session (the default scenario, no cameras,
// no built-in controller, started PAUSED) runs on its own thread with the ROS 2 bridge; a second
// participant calls every Simulation Interfaces service, the SimulateSteps action and node
// /rescuesim's parameter services the way rmw_cyclonedds does (request header, clientid), and
// checks each answer against what can be worked out by hand: 200 steps of 5 ms are 1.000 s, a
// reset puts the clock at 0 and the robot at its start, a NaN pose is INVALID_POSE, and so on.

#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "bridges/common/cdr_stream.h"
#include "bridges/common/control_cdr.h"
#include "bridges/ros2/dds_action_client.h"
#include "bridges/ros2/dds_participant.h"
#include "bridges/ros2/dds_services.h"
#include "bridges/ros2/ros2_bridge.h"
#include "bridges/ros2/ros2_conventions.h"
#include "robots/rescue_robot.h"
#include "session/session.h"
#include "support/command.h"
#include "bridges/ros2/dds_loopback.h"
#include "support/dds_domain.h"
#include "raycast/free_spot.h"
#include "msgs/serialize.h"
#include <nlohmann/json.hpp>

namespace rescuesim {
namespace {

using namespace std::chrono_literals;
using namespace control;
using ros2::DdsParticipant;
using ros2::ServiceClient;

constexpr auto kTimeout = 10s;

/// A run with the ROS 2 bridge, stepping on a thread of its own until the test ends.
class ControlServicesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::pin_cyclone_to_loopback();
    const ModelMap models = builtin_models();
    Scenario s = default_scenario(models);
    s.duration = 1e9;
    s.realtime = false;
    SessionOptions o;
    o.cameras = false;
    o.controllers = false;
    o.control = true;
    o.control_options.start_paused = true;
    session_ = std::make_unique<Session>(s, models, o);
    Ros2Options ro = options();
    ro.domain_id = testing::leased_dds_domain();
    bridge_ = make_ros2_bridge(ro);
    bridge_->start(session_->sim());
    runner_ = std::thread([this] { session_->run(&stop_); });
    client_ = std::make_unique<DdsParticipant>(ro.domain_id, ros2::participant_user_data());
  }
  /// The bridge's options (the domain is set by SetUp).
  virtual Ros2Options options() const { return {}; }
  void TearDown() override {
    stop_ = true;
    if (runner_.joinable()) runner_.join();
    bridge_->stop();
  }

  /// Calls service S at `name` with `request`; the decoded response.
  template <class S>
  typename S::Response call(const std::string& name, const typename S::Request& request, WireVersion version = WireVersion::v1) {
    ServiceClient c(*client_, ros2::service_topics(name, info(S::id).ros_type));
    EXPECT_TRUE(c.wait_for_server(kTimeout)) << name;
    std::vector<std::uint8_t> body;
    encode_request<S>(request, version, body);
    std::string why;
    const auto reply = c.call(body, kTimeout, &why);
    if (!reply) {
      ADD_FAILURE() << name << ": " << why;
      return {};
    }
    auto decoded = decode_response<S>(*reply, version);
    EXPECT_TRUE(decoded.value) << decoded.problem;
    return decoded.value ? *decoded.value : typename S::Response{};
  }

  EntityState robot_state() {
    const auto r = call<iface::GetEntityState>("/get_entity_state", {"robot"});
    EXPECT_TRUE(r.result.is_ok()) << r.result.error_message;
    return r.state;
  }

  std::unique_ptr<Session> session_;
  std::unique_ptr<Bridge> bridge_;
  std::unique_ptr<DdsParticipant> client_;
  std::atomic<bool> stop_{false};
  std::thread runner_;
};

TEST_F(ControlServicesTest, StateStepsResetAndEntitiesOverTheWire) {
  const SimulatorFeatures f = call<iface::GetSimulatorFeatures>("/get_simulator_features", {});
  for (std::uint16_t want : {feature::kSimulationReset, feature::kSimulationStatePause, feature::kStepSimulationMultiple,
                             feature::kStepSimulationAction, feature::kEntityStateSetting}) {
    EXPECT_NE(std::find(f.features.begin(), f.features.end(), want), f.features.end()) << want;
  }
  EXPECT_NE(std::find(f.features.begin(), f.features.end(), feature::kSpawning), f.features.end());
  EXPECT_EQ(f.spawn_formats, (std::vector<std::string>{"urdf", "sdf", "yaml"}));

  // started PAUSED: the clock stands at 0
  GetSimulationStateResponse st = call<iface::GetSimulationState>("/get_simulation_state", {});
  EXPECT_EQ(st.state, RunState::paused);
  EXPECT_EQ(robot_state().stamp_ns, 0);
  Result r = call<iface::SetSimulationState>("/set_simulation_state", {RunState::paused});
  EXPECT_EQ(r.result, code::kAlreadyInTargetState);

  // 200 steps of 5 ms: 1.000 s, answered when they are done
  r = call<iface::StepSimulation>("/step_simulation", {200});
  EXPECT_TRUE(r.is_ok()) << r.error_message;
  EXPECT_EQ(robot_state().stamp_ns, 1'000'000'000);

  // teleport: the robot is where it was put (its start, turned a quarter)
  const Pose3 start = session_->sim().world().robots[0].X_W_start;
  SetEntityStateRequest set;
  set.entity = "robot";
  set.state.pose.p = start.p;
  set.state.pose.q = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ())) * start.q;
  r = call<iface::SetEntityState>("/set_entity_state", set);
  ASSERT_TRUE(r.is_ok()) << r.error_message;
  EXPECT_NEAR(robot_state().pose.q.angularDistance(set.state.pose.q), 0.0, 1e-9);
  // bad poses and names get their codes
  set.state.pose.p.x() = std::nan("");
  r = call<iface::SetEntityState>("/set_entity_state", set);
  EXPECT_EQ(r.result, code::kInvalidPose);
  set.state.pose.p = start.p;
  set.state.pose.q = Quat(0.1, 0.1, 0.1, 0.1);
  r = call<iface::SetEntityState>("/set_entity_state", set);
  EXPECT_EQ(r.result, code::kInvalidPose);
  set.entity = "ghost";
  set.state.pose.q = Quat::Identity();
  r = call<iface::SetEntityState>("/set_entity_state", set);
  EXPECT_EQ(r.result, code::kNotFound);
  EXPECT_NE(r.error_message.find("ghost"), std::string::npos);

  // entities by category; the victims are HUMANs
  EntityFilters robots;
  robots.categories = {category::kRobot};
  const GetEntitiesResponse e = call<iface::GetEntities>("/get_entities", robots);
  EXPECT_EQ(e.entities, std::vector<std::string>{"robot"});
  EntityFilters humans;
  humans.categories = {category::kHuman};
  const GetEntitiesStatesResponse h = call<iface::GetEntitiesStates>("/get_entities_states", humans);
  EXPECT_EQ(h.entities.size(), session_->sim().world().victims.size());
  EXPECT_EQ(h.states.size(), h.entities.size());
  const GetEntityInfoResponse info = call<iface::GetEntityInfo>("/get_entity_info", {"robot"});
  EXPECT_EQ(info.info.category, category::kRobot);
  const BoundsResponse b = call<iface::GetEntityBounds>("/get_entity_bounds", {"robot"});
  EXPECT_EQ(b.bounds.type, Bounds::kBox);
  const GetNamedPosesResponse poses = call<iface::GetNamedPoses>("/get_named_poses", {});
  ASSERT_EQ(poses.poses.size(), 1u);
  EXPECT_EQ(poses.poses[0].name, "robot_start");

  // reset: the clock at 0, the robot back at its start
  r = call<iface::ResetSimulation>("/reset_simulation", {scope::kDefault});
  EXPECT_TRUE(r.is_ok()) << r.error_message;
  const EntityState after = robot_state();
  EXPECT_EQ(after.stamp_ns, 0);
  EXPECT_NEAR((after.pose.p - start.p).norm(), 0.0, 1e-6);

  // stepping while PLAYING is refused as the standard says
  r = call<iface::SetSimulationState>("/set_simulation_state", {RunState::playing});
  EXPECT_TRUE(r.is_ok());
  r = call<iface::StepSimulation>("/step_simulation", {1});
  EXPECT_EQ(r.result, code::kOperationFailed);
  EXPECT_NE(r.error_message.find("PAUSED"), std::string::npos);

  // a file that is not there is NO_RESOURCE, and says where it looked; worlds: the current one is the scenario
  SpawnRequest spawn;
  spawn.name = "p3at";
  spawn.uri = "file:///nowhere/p3at.urdf";
  const SpawnEntityResponse sp = call<iface::SpawnEntity>("/spawn_entity", spawn);
  EXPECT_EQ(sp.result.result, code::kNoResource);
  EXPECT_NE(sp.result.error_message.find("/nowhere/p3at.urdf"), std::string::npos) << sp.result.error_message;
  // a built-in box 2 m above the robot's start: spawned, listed as DYNAMIC_OBJECT, then deleted
  spawn.name = "crate";
  spawn.uri = "box";
  spawn.pose = Pose3{session_->sim().world().robots[0].X_W_start.p + Vec3(0, 0, 2), Quat::Identity()};
  const SpawnEntityResponse crate = call<iface::SpawnEntity>("/spawn_entity", spawn);
  ASSERT_TRUE(crate.result.is_ok()) << crate.result.error_message;
  EXPECT_EQ(crate.entity_name, "crate");
  EntityFilters dynamic;
  dynamic.filter = "^crate$";
  dynamic.categories = {category::kDynamicObject};
  EXPECT_EQ(call<iface::GetEntities>("/get_entities", dynamic).entities, std::vector<std::string>{"crate"});
  EXPECT_EQ(call<iface::SpawnEntity>("/spawn_entity", spawn).result.result, code::kNameNotUnique);
  EXPECT_TRUE(call<iface::DeleteEntity>("/delete_entity", {"crate"}).is_ok());
  EXPECT_TRUE(call<iface::GetEntities>("/get_entities", dynamic).entities.empty());
  EXPECT_EQ(call<iface::DeleteEntity>("/delete_entity", {"robot"}).result, code::kOperationFailed);
  const GetSpawnablesResponse spawnables = call<iface::GetSpawnables>("/get_spawnables", {});
  ASSERT_TRUE(spawnables.result.is_ok());
  EXPECT_TRUE(
      std::any_of(spawnables.spawnables.begin(), spawnables.spawnables.end(), [](const Spawnable& s) { return s.uri == "rescue_robot"; }));
  const WorldResponse w = call<iface::GetCurrentWorld>("/get_current_world", {});
  EXPECT_TRUE(w.result.is_ok());
  EXPECT_EQ(w.world.name, session_->scenario().name);
}

TEST_F(ControlServicesTest, AMalformedRequestIsAnsweredWithWhatWasWrong) {
  // a ResetSimulation request without its scope byte: only the encapsulation header
  ServiceClient c(*client_, ros2::service_topics("/reset_simulation", "simulation_interfaces/srv/ResetSimulation"));
  ASSERT_TRUE(c.wait_for_server(kTimeout));
  const std::vector<std::uint8_t> empty = {0x00, 0x01, 0x00, 0x00};
  std::string why;
  const auto reply = c.call(empty, kTimeout, &why);
  ASSERT_TRUE(reply) << why;
  const auto r = decode_response<iface::ResetSimulation>(*reply, WireVersion::v1);
  ASSERT_TRUE(r.value);
  EXPECT_EQ(r.value->result, code::kOperationFailed);
  EXPECT_NE(r.value->error_message.find("malformed request"), std::string::npos) << r.value->error_message;
  // the run is still there
  EXPECT_EQ(call<iface::GetSimulationState>("/get_simulation_state", {}).state, RunState::paused);
}

TEST_F(ControlServicesTest, SimulateStepsReportsFeedbackAndCanBeCancelled) {
  ros2::ActionClient a(*client_, ros2::action_topics("/simulate_steps", "simulation_interfaces/action/SimulateSteps"));
  ASSERT_TRUE(a.wait_for_server(kTimeout));
  const auto goal = [](std::uint64_t steps) {
    std::vector<std::uint8_t> out;
    cdr::Writer w(out, "SimulateSteps_Goal");
    w.value("steps", steps);
    return out;
  };
  // 400 steps: feedback on the way, SUCCEEDED, and the clock at 2.000 s
  ros2::GoalId id{};
  id[0] = 1;
  std::string why;
  const auto accepted = a.send_goal(id, goal(400), kTimeout, &why);
  ASSERT_TRUE(accepted) << why;
  EXPECT_TRUE(accepted->accepted);
  const auto result = a.get_result(id, kTimeout, &why);
  ASSERT_TRUE(result) << why;
  const auto res = decode_response<iface::SimulateStepsGetResult>(*result, WireVersion::v1);
  ASSERT_TRUE(res.value) << res.problem;
  EXPECT_EQ(res.value->status, goal_status::kSucceeded);
  EXPECT_TRUE(res.value->result.is_ok());
  EXPECT_EQ(robot_state().stamp_ns, 2'000'000'000);
  a.wait_feedback(2s);
  const auto fb = a.take_feedback();
  ASSERT_FALSE(fb.empty());
  // the last feedback says 400 done, 0 left
  cdr::Reader last(fb.back().feedback, "SimulateSteps_Feedback");
  std::uint64_t done = 0, left = 1;
  last.value("completed_steps", done);
  last.value("remaining_steps", left);
  EXPECT_EQ(done, 400u);
  EXPECT_EQ(left, 0u);

  // a goal far too long, cancelled: CANCELED, and the run stays PAUSED where it stopped
  ros2::GoalId long_id{};
  long_id[0] = 2;
  ASSERT_TRUE(a.send_goal(long_id, goal(100'000'000), kTimeout, &why)) << why;
  const auto cancel = a.cancel(ros2::GoalInfo{long_id, {}}, kTimeout, &why);
  ASSERT_TRUE(cancel) << why;
  EXPECT_EQ(cancel->return_code, ros2::cancel_code::kNone);
  const auto cancelled = a.get_result(long_id, kTimeout, &why);
  ASSERT_TRUE(cancelled) << why;
  const auto cres = decode_response<iface::SimulateStepsGetResult>(*cancelled, WireVersion::v1);
  ASSERT_TRUE(cres.value);
  EXPECT_EQ(cres.value->status, goal_status::kCanceled);
  EXPECT_EQ(call<iface::GetSimulationState>("/get_simulation_state", {}).state, RunState::paused);

  // while PLAYING a goal is rejected
  ASSERT_TRUE(call<iface::SetSimulationState>("/set_simulation_state", {RunState::playing}).is_ok());
  ros2::GoalId third{};
  third[0] = 3;
  const auto rejected = a.send_goal(third, goal(10), kTimeout, &why);
  ASSERT_TRUE(rejected) << why;
  EXPECT_FALSE(rejected->accepted);
}

TEST_F(ControlServicesTest, ParametersOfNodeRescuesim) {
  const ListParametersResult list = call<iface::ListParameters>("/rescuesim/list_parameters", {});
  EXPECT_NE(std::find(list.names.begin(), list.names.end(), "use_sim_time"), list.names.end());
  EXPECT_NE(std::find(list.names.begin(), list.names.end(), "real_time_factor"), list.names.end());

  const GetParametersResponse got = call<iface::GetParameters>("/rescuesim/get_parameters", {{"use_sim_time", "seed", "nope"}});
  ASSERT_EQ(got.values.size(), 3u);
  EXPECT_EQ(got.values[0].type, ParameterValue::kBool);
  EXPECT_TRUE(got.values[0].bool_value);
  EXPECT_EQ(got.values[1].integer_value, static_cast<std::int64_t>(session_->scenario().seed));
  EXPECT_EQ(got.values[2].type, ParameterValue::kNotSet);

  const GetParameterTypesResponse types = call<iface::GetParameterTypes>("/rescuesim/get_parameter_types", {{"step_size"}});
  EXPECT_EQ(types.types, std::vector<std::uint8_t>{ParameterValue::kDouble});
  const DescribeParametersResponse d = call<iface::DescribeParameters>("/rescuesim/describe_parameters", {{"seed"}});
  ASSERT_EQ(d.descriptors.size(), 1u);
  EXPECT_TRUE(d.descriptors[0].read_only);

  SetParametersRequest set;
  Parameter seed{"seed", {}};
  seed.value.type = ParameterValue::kInteger;
  seed.value.integer_value = 9;
  Parameter rate{"real_time_factor", {}};
  rate.value.type = ParameterValue::kDouble;
  rate.value.double_value = 2.5;
  set.parameters = {seed, rate};
  const SetParametersResponse res = call<iface::SetParameters>("/rescuesim/set_parameters", set);
  ASSERT_EQ(res.results.size(), 2u);
  EXPECT_FALSE(res.results[0].successful);
  EXPECT_NE(res.results[0].reason.find("read-only"), std::string::npos);
  EXPECT_TRUE(res.results[1].successful) << res.results[1].reason;
  EXPECT_DOUBLE_EQ(call<iface::GetParameters>("/rescuesim/get_parameters", {{"real_time_factor"}}).values.at(0).double_value, 2.5);

  // atomically: the bad one undoes the good one
  rate.value.double_value = 7;
  set.parameters = {rate, seed};
  const SetParameterResult atomic = call<iface::SetParametersAtomically>("/rescuesim/set_parameters_atomically", set);
  EXPECT_FALSE(atomic.successful);
  EXPECT_DOUBLE_EQ(call<iface::GetParameters>("/rescuesim/get_parameters", {{"real_time_factor"}}).values.at(0).double_value, 2.5);
}

/// Where Gazebo serves them (--sim-services-ns /gzserver) and in the 2.x layouts (--ros2-distro
/// rolling): SetEntityState's set_pose / set_twist flags say what changes.
class ControlServicesGzNamesV2Test : public ControlServicesTest {
 protected:
  Ros2Options options() const override {
    Ros2Options o;
    o.sim_services_ns = "/gzserver";
    o.sim_interfaces_v2 = true;
    return o;
  }
};

TEST_F(ControlServicesGzNamesV2Test, ServicesLiveUnderTheNamespaceAndTheFlagsPickWhatIsSet) {
  // nothing at the root
  ServiceClient root(*client_, ros2::service_topics("/reset_simulation", "simulation_interfaces/srv/ResetSimulation"));
  EXPECT_FALSE(root.wait_for_server(1s));
  // 100 steps with the robot driving forward at 0.3 m/s, so it has a twist to keep or to lose
  ASSERT_TRUE(session_->sim().command_velocity(RobotIndex(0), msg::Twist{Vec3(0.3, 0, 0), Vec3::Zero()}));
  EXPECT_TRUE(call<iface::StepSimulation>("/gzserver/step_simulation", {100}, WireVersion::v2).is_ok());
  const auto moving = call<iface::GetEntityState>("/gzserver/get_entity_state", {"robot"}, WireVersion::v2);
  ASSERT_GT(moving.state.linear.norm(), 0.05);
  // the pose only (set_twist false): the robot keeps its velocity
  SetEntityStateRequest set;
  set.entity = "robot";
  set.state.pose = moving.state.pose;
  set.state.pose.p.y() += 0.2;
  set.set_pose = true;
  set.set_twist = false;
  set.set_acceleration = false;
  Result r = call<iface::SetEntityState>("/gzserver/set_entity_state", set, WireVersion::v2);
  ASSERT_TRUE(r.is_ok()) << r.error_message;
  auto after = call<iface::GetEntityState>("/gzserver/get_entity_state", {"robot"}, WireVersion::v2).state;
  EXPECT_NEAR(after.pose.p.y(), moving.state.pose.p.y() + 0.2, 1e-9);
  EXPECT_NEAR((after.linear - moving.state.linear).norm(), 0.0, 1e-9);
  // the twist only (set_pose false): the pose stays, the robot stops
  set.set_pose = false;
  set.set_twist = true;
  set.state.pose.p.x() += 5.0;  // ignored
  set.state.linear = Vec3::Zero();
  r = call<iface::SetEntityState>("/gzserver/set_entity_state", set, WireVersion::v2);
  ASSERT_TRUE(r.is_ok()) << r.error_message;
  const auto stopped = call<iface::GetEntityState>("/gzserver/get_entity_state", {"robot"}, WireVersion::v2).state;
  EXPECT_NEAR(stopped.pose.p.x(), after.pose.p.x(), 1e-9);
  EXPECT_NEAR(stopped.linear.norm(), 0.0, 1e-12);
  // an acceleration cannot be set
  set.set_acceleration = true;
  EXPECT_EQ(call<iface::SetEntityState>("/gzserver/set_entity_state", set, WireVersion::v2).result, code::kFeatureUnsupported);
  // the parameters stay the node's
  EXPECT_FALSE(call<iface::ListParameters>("/rescuesim/list_parameters", {}).names.empty());
}

/// As a user runs it: `rescuesim run --ros2 --paused` in a process of its own, driven from this one
/// over loopback: 200 steps, a reset, 100 steps, then QUITTING ends the run, which writes its
/// outputs with 100 steps of sim time (0.5 s) and says why it stopped.
TEST(ControlServicesCli, APausedRunIsSteppedResetAndEndedByItsClient) {
  testing::pin_cyclone_to_loopback();
  const int domain = testing::leased_dds_domain();
  const auto dir = testing::temp_dir("ros2-control-cli");
  testing::CommandResult run;
  std::thread sim([&] {
    run = testing::rescuesim("run --ros2 --paused --no-cameras --quiet --ros-domain " + std::to_string(domain) + " --out " +
                             testing::quoted(dir / "out"));
  });
  DdsParticipant client(domain, ros2::participant_user_data());
  const auto call = [&](const char* name, const char* type, const std::vector<std::uint8_t>& body) {
    ServiceClient c(client, ros2::service_topics(name, type));
    EXPECT_TRUE(c.wait_for_server(30s)) << name;  // the run starts within seconds
    std::string why;
    auto reply = c.call(body, kTimeout, &why);
    EXPECT_TRUE(reply) << name << ": " << why;
    return reply ? *reply : std::vector<std::uint8_t>{};
  };
  const auto result_of = [](const std::vector<std::uint8_t>& reply) {
    auto r = decode_response<iface::StepSimulation>(reply, WireVersion::v1);
    return r.value ? *r.value : Result::fail(255, r.problem);
  };
  std::vector<std::uint8_t> body;
  encode_request<iface::StepSimulation>({200}, WireVersion::v1, body);
  EXPECT_TRUE(result_of(call("/step_simulation", "simulation_interfaces/srv/StepSimulation", body)).is_ok());
  body.clear();
  encode_request<iface::ResetSimulation>({scope::kDefault}, WireVersion::v1, body);
  const auto reset = decode_response<iface::ResetSimulation>(call("/reset_simulation", "simulation_interfaces/srv/ResetSimulation", body),
                                                             WireVersion::v1);
  EXPECT_TRUE(reset.value && reset.value->is_ok());
  body.clear();
  encode_request<iface::StepSimulation>({100}, WireVersion::v1, body);
  EXPECT_TRUE(result_of(call("/step_simulation", "simulation_interfaces/srv/StepSimulation", body)).is_ok());

  // a rescue robot spawned where the default scenario's floor is clear: its odometry is on the
  // wire under /p3at as soon as steps are taken (checked after the run has ended, so that a
  // failure here still ends it)
  const ModelMap models = builtin_models();
  const Scenario scenario = default_scenario(models);
  const World world = compile_scenario(scenario, build_world(scenario), models);
  const auto spot = free_spot(world, initial_state(world), 0.45, {world.robots[0].X_W_start.p.head<2>()});
  EXPECT_TRUE(spot);
  SpawnRequest spawn;
  spawn.name = "p3at";
  spawn.uri = "rescue_robot";
  if (spot) spawn.pose = Pose3{Vec3(spot->x(), spot->y(), 0), Quat::Identity()};
  body.clear();
  encode_request<iface::SpawnEntity>(spawn, WireVersion::v1, body);
  const auto spawned =
      decode_response<iface::SpawnEntity>(call("/spawn_entity", "simulation_interfaces/srv/SpawnEntity", body), WireVersion::v1);
  EXPECT_TRUE(spawned.value && spawned.value->result.is_ok()) << (spawned.value ? spawned.value->result.error_message : spawned.problem);
  const int odom = client.create_reader("rt/p3at/odom", "nav_msgs::msg::dds_::Odometry_", {});
  const auto matched_by = std::chrono::steady_clock::now() + 20s;
  while (client.matched_writers(odom) == 0 && std::chrono::steady_clock::now() < matched_by) std::this_thread::sleep_for(20ms);
  EXPECT_GT(client.matched_writers(odom), 0) << "no writer on rt/p3at/odom";
  // 10 steps (0.05 s, 2 or 3 odometry messages at 50 Hz) at a time until they arrive: the bridge
  // sends a topic once it has noticed its reader (within 0.1 s of matching)
  std::vector<std::string> frames;
  int steps = 0;
  body.clear();
  encode_request<iface::StepSimulation>({10}, WireVersion::v1, body);
  for (int i = 0; i < 100 && frames.empty(); ++i) {
    EXPECT_TRUE(result_of(call("/step_simulation", "simulation_interfaces/srv/StepSimulation", body)).is_ok());
    steps += 10;
    std::this_thread::sleep_for(50ms);
    client.take(odom, [&](std::span<const std::uint8_t> bytes) {
      frames.push_back(std::get<msg::Odometry>(msg::from_cdr(*msg::find_type("nav_msgs/Odometry"), bytes)).header.frame_id);
    });
  }

  body.clear();
  encode_request<iface::SetSimulationState>({RunState::quitting}, WireVersion::v1, body);
  const auto quit = decode_response<iface::SetSimulationState>(
      call("/set_simulation_state", "simulation_interfaces/srv/SetSimulationState", body), WireVersion::v1);
  EXPECT_TRUE(quit.value && quit.value->is_ok());
  sim.join();
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  ASSERT_FALSE(frames.empty()) << "no odometry from the spawned robot\n" << run.out << run.err;
  EXPECT_EQ(frames.back(), "p3at/odom");
  const auto summary = nlohmann::json::parse(testing::slurp(dir / "out" / "summary.json"), nullptr, false);
  ASSERT_FALSE(summary.is_discarded()) << run.out << run.err;
  EXPECT_EQ(summary["stop_reason"], "quit by request");
  EXPECT_NEAR(summary["sim_time_s"].get<double>(), 0.5 + 0.005 * steps, 1e-9);
}

}  // namespace
}  // namespace rescuesim
