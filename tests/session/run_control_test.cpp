// RunControl, the control surface beneath every front end: a reset goes back to the start
// bitwise (state hash), N steps from PAUSED are N lockstep steps, a pause holds the clock,
// teleports move a robot rigidly while its odometry does not notice, filters pick entities by
// name, category and bounds, and every bad request gets its standard result code and a message
// naming what was wrong.

#include "session/run_control.h"

#include <gtest/gtest.h>

#include <cmath>
#include <future>
#include <thread>

#include "robots/rescue_robot.h"
#include "session/session.h"

namespace rescuesim {
namespace {

using namespace control;

/// The default scenario without cameras, its built-in explorer driving, with the control surface.
std::unique_ptr<Session> make_session(bool start_paused = false, double duration = 1e9, bool controllers = true) {
  const ModelMap models = builtin_models();
  Scenario s = default_scenario(models);
  s.duration = duration;
  s.realtime = false;
  SessionOptions o;
  o.cameras = false;
  o.controllers = controllers;
  o.control = true;
  o.control_options.start_paused = start_paused;
  return std::make_unique<Session>(s, models, o);
}

/// Session::run on a thread of its own (the simulation thread), ended by `stop` or QUITTING.
struct Running {
  std::unique_ptr<Session> session;
  std::atomic<bool> stop{false};
  std::thread thread;
  RunResult result;

  explicit Running(std::unique_ptr<Session> s) : session(std::move(s)) {
    thread = std::thread([this] { result = session->run(&stop); });
  }
  ~Running() {
    stop = true;
    if (thread.joinable()) thread.join();
  }
  /// Runs `f` on the simulation thread at the next step boundary and returns what it returns.
  template <class F>
  auto call(F f) {
    using R = decltype(f(std::declval<SimControl&>()));
    auto promise = std::make_shared<std::promise<R>>();
    auto future = promise->get_future();
    EXPECT_TRUE(session->control()->post([promise, f](SimControl& c) mutable { promise->set_value(f(c)); }));
    return future.get();
  }
};

TEST(RunControl, ResetGoesBackToTheStartHashAndReplaysBitwise) {
  auto session = make_session(false, 2.0);
  RunControl& control = *session->control();
  control.arm();
  const std::uint64_t start_hash = control.state_hash();
  session->step_until(SimTime::from_seconds(1.0));
  const std::uint64_t hash_at_1s = control.state_hash();
  EXPECT_NE(hash_at_1s, start_hash);
  EXPECT_GT(session->sim().state().robots[0].distance, 0.05);  // the explorer drove

  ASSERT_TRUE(control.reset(scope::kDefault).is_ok());
  EXPECT_EQ(control.state_hash(), start_hash);
  EXPECT_EQ(control.time_ns(), 0);
  // the same second again: the same state, bitwise
  session->step_until(SimTime::from_seconds(1.0));
  EXPECT_EQ(control.state_hash(), hash_at_1s);
  // ALL is DEFAULT
  ASSERT_TRUE(control.reset(scope::kAll).is_ok());
  EXPECT_EQ(control.state_hash(), start_hash);
}

TEST(RunControl, StateAloneKeepsTheClockAndTimeAloneKeepsTheBodies) {
  auto session = make_session();
  RunControl& control = *session->control();
  control.arm();
  const Pose3 start = session->sim().state().robots[0].base.X_WB;
  session->step_until(SimTime::from_seconds(1.0));
  const Pose3 moved = session->sim().state().robots[0].base.X_WB;
  ASSERT_GT((moved.p - start.p).norm(), 0.02);

  ASSERT_TRUE(control.reset(scope::kState).is_ok());
  EXPECT_EQ(control.time_ns(), 1'000'000'000);
  EXPECT_EQ(session->sim().state().robots[0].base.X_WB.p, start.p);

  session->step_until(SimTime::from_seconds(1.5));
  const Pose3 later = session->sim().state().robots[0].base.X_WB;
  ASSERT_TRUE(control.reset(scope::kTime).is_ok());
  EXPECT_EQ(control.time_ns(), 0);
  EXPECT_EQ(session->sim().state().robots[0].base.X_WB.p, later.p);

  // SPAWNED alone: nothing was spawned, so nothing changes
  const std::uint64_t h = control.state_hash();
  EXPECT_TRUE(control.reset(scope::kSpawned).is_ok());
  EXPECT_EQ(control.state_hash(), h);
}

TEST(RunControl, StepsFromPausedAreTheLockstepSteps) {
  constexpr std::uint64_t kSteps = 300;
  // lockstep: the run plays for exactly kSteps steps of 5 ms
  auto lockstep = make_session(false, kSteps * 0.005);
  lockstep->run();
  const std::uint64_t want = state_hash(lockstep->sim().state());
  ASSERT_EQ(lockstep->sim().state().step, static_cast<std::int64_t>(kSteps));

  Running paused(make_session(true));
  // while paused, the clock holds: two requests in a row see the same time
  const std::int64_t t1 = paused.call([](SimControl& c) { return c.time_ns(); });
  const std::int64_t t2 = paused.call([](SimControl& c) { return c.time_ns(); });
  EXPECT_EQ(t1, 0);
  EXPECT_EQ(t2, 0);
  EXPECT_EQ(paused.call([](SimControl& c) { return c.run_state(); }), RunState::paused);

  // 100 + 200 steps, the second as an action with feedback every 50 steps
  auto done = std::make_shared<std::promise<std::pair<Result, std::uint64_t>>>();
  StepJob one;
  one.steps = 100;
  one.done = [done](const Result& r, std::uint64_t n) { done->set_value({r, n}); };
  EXPECT_TRUE(paused.call([&](SimControl& c) { return c.start_steps(one, false); }).is_ok());
  auto [r1, n1] = done->get_future().get();
  EXPECT_TRUE(r1.is_ok());
  EXPECT_EQ(n1, 100u);

  auto done2 = std::make_shared<std::promise<std::uint64_t>>();
  auto feedback = std::make_shared<std::vector<std::pair<std::uint64_t, std::uint64_t>>>();
  StepJob two;
  two.steps = 200;
  two.feedback_every = 50;
  two.feedback = [feedback](std::uint64_t c, std::uint64_t r) { feedback->emplace_back(c, r); };
  two.done = [done2](const Result&, std::uint64_t n) { done2->set_value(n); };
  EXPECT_TRUE(paused.call([&](SimControl& c) { return c.start_steps(two, true); }).is_ok());
  EXPECT_EQ(done2->get_future().get(), 200u);
  const std::vector<std::pair<std::uint64_t, std::uint64_t>> want_feedback = {{50, 150}, {100, 100}, {150, 50}, {200, 0}};
  EXPECT_EQ(*feedback, want_feedback);

  // the run stays paused where the steps left it, with the lockstep run's state
  EXPECT_EQ(paused.call([](SimControl& c) { return c.steps_taken(); }), static_cast<std::int64_t>(kSteps));
  EXPECT_EQ(paused.call([](SimControl& c) { return c.state_hash(); }), want);
  EXPECT_EQ(paused.call([](SimControl& c) { return c.time_ns(); }), static_cast<std::int64_t>(kSteps) * 5'000'000);

  // QUITTING ends the run
  EXPECT_TRUE(paused.call([](SimControl& c) { return c.set_run_state(RunState::quitting); }).is_ok());
  paused.thread.join();
  EXPECT_EQ(paused.result.stop_reason, "quit by request");
  // and a request after the end is refused, not left waiting
  EXPECT_FALSE(paused.session->control()->post([](SimControl&) {}));
}

TEST(RunControl, StateTransitionsAndStepsWhilePlayingHaveTheirCodes) {
  auto session = make_session();
  RunControl& c = *session->control();
  EXPECT_EQ(c.run_state(), RunState::playing);
  Result r = c.set_run_state(RunState::playing);
  EXPECT_EQ(r.result, code::kAlreadyInTargetState);
  EXPECT_NE(r.error_message.find("PLAYING"), std::string::npos);
  // stepping is for PAUSED only: the service says OPERATION_FAILED, the action INCORRECT_STATE
  EXPECT_EQ(c.start_steps(StepJob{}, false).result, code::kOperationFailed);
  EXPECT_EQ(c.start_steps(StepJob{}, true).result, code::kIncorrectState);
  EXPECT_EQ(c.set_run_state(RunState::no_world).result, code::kIncorrectTransition);
  EXPECT_FALSE(c.cancel_steps());
  // STOPPED: paused at the start
  c.arm();
  const std::uint64_t start = c.state_hash();
  session->step_until(SimTime::from_seconds(0.5));
  EXPECT_TRUE(c.set_run_state(RunState::stopped).is_ok());
  EXPECT_EQ(c.state_hash(), start);
  EXPECT_EQ(c.run_state(), RunState::stopped);
  EXPECT_TRUE(c.set_run_state(RunState::paused).is_ok());
  EXPECT_TRUE(c.set_run_state(RunState::playing).is_ok());
}

TEST(RunControl, TeleportMovesTheRobotRigidlyAndOdometryDoesNotNotice) {
  // no controller: the robot stands still unless commanded
  auto session = make_session(false, 1e9, false);
  RunControl& c = *session->control();
  ASSERT_TRUE(session->sim().command_velocity(RobotIndex(0), msg::Twist{Vec3(0.3, 0, 0), Vec3::Zero()}));
  session->step_until(SimTime::from_seconds(0.5));
  const RobotState before = session->sim().state().robots[0];
  ASSERT_GT(before.odom.x, 0.02);  // it drove, and odometry counted it
  // back to where it started, turned a quarter left (free floor: it just drove over it)
  EntityState want;
  want.pose.p = session->sim().world().robots[0].X_W_start.p;
  want.pose.q = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ())) * before.base.X_WB.q;
  Result r = c.set_entity_state("robot", want, true, true, false);
  ASSERT_TRUE(r.is_ok()) << r.error_message;
  EntityState got;
  ASSERT_TRUE(c.entity_state("robot", got).is_ok());
  EXPECT_NEAR((got.pose.p - want.pose.p).norm(), 0.0, 1e-9);
  EXPECT_NEAR(got.pose.q.angularDistance(want.pose.q), 0.0, 1e-9);
  EXPECT_NEAR(got.linear.norm(), 0.0, 1e-12);  // the twist given: zero
  // every link moved with the base: a link's pose relative to the base is what it was
  const RobotState& after = session->sim().state().robots[0];
  for (std::size_t l = 0; l < after.X_WL.size(); ++l) {
    const Pose3 rel_before = before.base.X_WB.inverse() * before.X_WL[l];
    const Pose3 rel_after = after.base.X_WB.inverse() * after.X_WL[l];
    EXPECT_NEAR((rel_before.p - rel_after.p).norm(), 0.0, 1e-9) << "link " << l;
  }
  // wheel odometry does not see the jump
  EXPECT_EQ(after.odom.x, before.odom.x);
  EXPECT_EQ(after.odom.y, before.odom.y);
  // and the robot stays there (on its wheels, not flung): stopped, 0.5 s later it is within 5 cm
  ASSERT_TRUE(session->sim().command_velocity(RobotIndex(0), msg::Twist{}));
  session->step_until(SimTime::from_seconds(1.0));
  EXPECT_LT((session->sim().state().robots[0].base.X_WB.p - want.pose.p).norm(), 0.05);
}

TEST(RunControl, BadPosesUnknownNamesAndFixedEntitiesAreRefusedWithTheirCodes) {
  auto session = make_session();
  RunControl& c = *session->control();
  EntityState s;
  s.pose.p = Vec3(std::nan(""), 0, 0);
  Result r = c.set_entity_state("robot", s, true, true, false);
  EXPECT_EQ(r.result, code::kInvalidPose);
  EXPECT_NE(r.error_message.find("position is not finite"), std::string::npos);
  s.pose.p = Vec3(1, 1, 0.1);
  s.pose.q = Quat(0.5, 0.5, 0.5, 0.6);  // norm 1.05
  r = c.set_entity_state("robot", s, true, true, false);
  EXPECT_EQ(r.result, code::kInvalidPose);
  EXPECT_NE(r.error_message.find("not a unit quaternion"), std::string::npos);
  r = c.set_entity_state("no_such_thing", EntityState{}, true, true, false);
  EXPECT_EQ(r.result, code::kNotFound);
  EXPECT_NE(r.error_message.find("no_such_thing"), std::string::npos);
  EntityState dummy;
  EXPECT_EQ(c.entity_state("nobody", dummy).result, code::kNotFound);
  s.pose.q = Quat::Identity();
  s.frame_id = "base_link";
  EXPECT_EQ(c.set_entity_state("robot", s, true, true, false).result, code::kOperationFailed);
  s.frame_id.clear();
  EXPECT_EQ(c.set_entity_state("robot", s, true, true, true).result, code::kFeatureUnsupported);
  // a victim is part of the world
  std::vector<std::string> humans;
  EntityFilters f;
  f.categories = {category::kHuman};
  ASSERT_TRUE(c.entities(f, humans).is_ok());
  ASSERT_FALSE(humans.empty());
  EXPECT_EQ(c.set_entity_state(humans[0], s, true, true, false).result, code::kOperationFailed);
  // a spawn without anything to spawn (run_control_spawn_test.cpp has the rest)
  std::string name;
  SpawnRequest spawn;
  spawn.name = "p3at";
  EXPECT_EQ(c.spawn(spawn, name).result, code::kNoResource);
  EXPECT_EQ(c.remove("nobody").result, code::kNotFound);
}

TEST(RunControl, FiltersPickEntitiesByNameCategoryAndBounds) {
  auto session = make_session();
  RunControl& c = *session->control();
  const World& w = session->sim().world();
  std::vector<std::string> names;
  ASSERT_TRUE(c.entities({}, names).is_ok());
  // the robot first, then the victims
  ASSERT_FALSE(names.empty());
  EXPECT_EQ(names[0], "robot");
  EXPECT_GE(names.size(), 1 + w.victims.size());

  EntityFilters robots;
  robots.categories = {category::kRobot};
  ASSERT_TRUE(c.entities(robots, names).is_ok());
  EXPECT_EQ(names, std::vector<std::string>{"robot"});

  EntityFilters by_name;
  by_name.filter = "^rob(o|a)t$";
  ASSERT_TRUE(c.entities(by_name, names).is_ok());
  EXPECT_EQ(names, std::vector<std::string>{"robot"});
  by_name.filter = "([";
  Result r = c.entities(by_name, names);
  EXPECT_EQ(r.result, code::kOperationFailed);
  EXPECT_NE(r.error_message.find("(["), std::string::npos);

  // a sphere of 0.5 m around the robot's start holds the robot and no victim
  EntityFilters near;
  near.bounds.type = Bounds::kSphere;
  near.bounds.points = {w.robots[0].X_W_start.p, Vec3(0.5, 0, 0)};
  near.categories = {category::kRobot, category::kHuman};
  ASSERT_TRUE(c.entities(near, names).is_ok());
  EXPECT_EQ(names, std::vector<std::string>{"robot"});
  near.bounds.type = Bounds::kConvexHull;
  EXPECT_EQ(c.entities(near, names).result, code::kFeatureUnsupported);

  EntityInfo info;
  ASSERT_TRUE(c.entity_info("robot", info).is_ok());
  EXPECT_EQ(info.category, category::kRobot);
  // the robot's box holds its chassis: longer than 0.3 m, lower than 1.5 m, around the base
  Bounds b;
  ASSERT_TRUE(c.entity_bounds("robot", b).is_ok());
  ASSERT_EQ(b.type, Bounds::kBox);
  ASSERT_EQ(b.points.size(), 2u);
  EXPECT_GT(b.points[1].x() - b.points[0].x(), 0.3);
  EXPECT_LT(b.points[1].z() - b.points[0].z(), 1.5);
  EXPECT_LT(b.points[0].x(), 0);
  EXPECT_GT(b.points[1].x(), 0);

  std::vector<NamedPose> poses;
  ASSERT_TRUE(c.named_poses({}, poses).is_ok());
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(poses[0].name, "robot_start");
  EXPECT_EQ(poses[0].pose.p, w.robots[0].X_W_start.p);
}

TEST(RunControl, ParametersAreReadAndTheWritableOnesChecked) {
  auto session = make_session();
  RunControl& c = *session->control();
  EXPECT_EQ(c.parameter("use_sim_time").type, ParameterValue::kBool);
  EXPECT_TRUE(c.parameter("use_sim_time").bool_value);
  EXPECT_EQ(c.parameter("seed").integer_value, static_cast<std::int64_t>(session->scenario().seed));
  EXPECT_DOUBLE_EQ(c.parameter("step_size").double_value, 0.005);
  EXPECT_EQ(c.parameter("nope").type, ParameterValue::kNotSet);

  Parameter p{"seed", {}};
  p.value.type = ParameterValue::kInteger;
  p.value.integer_value = 7;
  SetParameterResult r = c.set_parameter(p);
  EXPECT_FALSE(r.successful);
  EXPECT_NE(r.reason.find("read-only"), std::string::npos);

  p.name = "real_time_factor";
  p.value = {};
  p.value.type = ParameterValue::kString;
  p.value.string_value = "fast";
  r = c.set_parameter(p);
  EXPECT_FALSE(r.successful);
  EXPECT_NE(r.reason.find("is a double; got a string"), std::string::npos);

  p.value = {};
  p.value.type = ParameterValue::kDouble;
  p.value.double_value = -2;
  EXPECT_FALSE(c.set_parameter(p).successful);
  p.value.double_value = 4;
  EXPECT_TRUE(c.set_parameter(p).successful);
  EXPECT_DOUBLE_EQ(c.rate(), 4.0);
  EXPECT_DOUBLE_EQ(c.parameter("real_time_factor").double_value, 4.0);

  p.name = "undeclared";
  r = c.set_parameter(p);
  EXPECT_FALSE(r.successful);
  EXPECT_NE(r.reason.find("not declared"), std::string::npos);
  EXPECT_EQ(c.parameter_descriptors().size(), 9u);
}

}  // namespace
}  // namespace rescuesim

namespace rescuesim {
namespace {

TEST(RunControl, TheStartSnapshotDoesNotChangeTheRun) {
  // a run with the control surface (a live bridge's) takes its start snapshot before the first
  // step; at t = 0 Bullet has no contacts and no warm start to lose, so the run is the same
  constexpr std::uint64_t kSteps = 400;
  auto with = make_session(false, kSteps * 0.005);
  with->run();
  const ModelMap models = builtin_models();
  Scenario s = default_scenario(models);
  s.duration = kSteps * 0.005;
  s.realtime = false;
  SessionOptions o;
  o.cameras = false;
  Session without(s, models, o);
  ASSERT_EQ(without.control(), nullptr);
  without.run();
  EXPECT_EQ(state_hash(with->sim().state()), state_hash(without.sim().state()));
}

}  // namespace
}  // namespace rescuesim
