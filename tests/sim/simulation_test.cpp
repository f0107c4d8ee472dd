// The simulation as a whole: sensor rates and stamps, IMU at rest, odometry against ground
// truth on flat floor and under slip, commands, trouble, and determinism.

#include "sim/simulation.h"

#include <gtest/gtest.h>

#include <thread>

#include <cmath>
#include <cstdio>
#include <map>

#include "core/parallel.h"
#include "import/scenario/scenario.h"
#include "msgs/digest.h"
#include "robots/rescue_robot.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using testing::room_spec;

Simulation make_sim(const WorldSpec& spec, std::uint64_t seed = 1) {
  SimOptions o;
  o.seed = seed;
  return Simulation(compile_world(spec, builtin_models()), o);
}

/// Drives with cmd_vel (v, w) for `seconds`, re-sending it every 0.1 s like a teleop node.
void drive(Simulation& sim, double v, double w, double seconds) {
  const SimTime end = sim.time() + SimTime::from_seconds(seconds);
  while (sim.time() < end) {
    msg::Twist t;
    t.linear.x() = v;
    t.angular.z() = w;
    sim.command_velocity(RobotIndex(0), t);
    sim.step_until(std::min(end, sim.time() + SimTime::from_ms(100)));
  }
}

TEST(Simulation, SensorsPublishAtTheirRatesWithExactStamps) {
  Simulation sim = make_sim(room_spec());
  std::map<std::string, std::vector<SimTime>> stamps;
  sim.bus().subscribe("", [&](const Topic& t, const msg::Message& m) { stamps[t.name].push_back(msg::stamp_of(m)); });
  sim.step_until(SimTime::from_seconds(10.0));
  // a sample at t = 0, then one every period: 10 s at 10 Hz is 101 scans, at 100 Hz 1001
  EXPECT_EQ(stamps["/scan"].size(), 101u);
  EXPECT_EQ(stamps["/imu/data"].size(), 1001u);
  EXPECT_EQ(stamps["/odom"].size(), 501u);
  EXPECT_EQ(stamps["/sonar/front_left"].size(), 101u);
  EXPECT_EQ(stamps["/clock"].size(), 2001u);  // every 5 ms step, and t = 0
  for (std::size_t i = 0; i < stamps["/scan"].size(); ++i) EXPECT_EQ(stamps["/scan"][i].ns, static_cast<std::int64_t>(i) * 100'000'000);
  // tf_static once, with the laser's mount
  EXPECT_EQ(stamps["/tf_static"].size(), 1u);
}

TEST(Simulation, CamerasHaveOpticalFramesOnTfStatic) {
  Simulation sim = make_sim(room_spec());
  msg::TFMessage tf;
  sim.bus().subscribe("/tf_static", [&](const Topic&, const msg::Message& m) { tf = std::get<msg::TFMessage>(m); });
  sim.step();
  const msg::TransformStamped* optical = nullptr;
  for (const auto& t : tf.transforms) {
    if (t.child_frame_id == "camera_color_optical_frame") optical = &t;
  }
  ASSERT_NE(optical, nullptr);
  EXPECT_EQ(optical->header.frame_id, "camera_color");
  // the optical z axis (forward) is the body's x axis; optical x (right) is body -y; optical y (down) is body -z
  EXPECT_TRUE((optical->transform.q * Vec3::UnitZ()).isApprox(Vec3::UnitX(), 1e-12));
  EXPECT_TRUE((optical->transform.q * Vec3::UnitX()).isApprox(-Vec3::UnitY(), 1e-12));
  EXPECT_TRUE((optical->transform.q * Vec3::UnitY()).isApprox(-Vec3::UnitZ(), 1e-12));
  // and camera messages are stamped in it
  for (const auto& s : sim.sensors()) {
    const SensorSpec& spec = sim.world().robots[0].spec.sensors[static_cast<std::size_t>(s.index)];
    if (spec.type == SensorSpec::Type::color_camera) {
      EXPECT_EQ(s.frame_id, "camera_color_optical_frame");
    }
    if (spec.type == SensorSpec::Type::lidar) {
      EXPECT_EQ(s.frame_id, "laser");
    }
  }
}

TEST(Simulation, ImuAtRestReadsGravityUp) {
  Simulation sim = make_sim(room_spec());
  sim.step_until(SimTime::from_seconds(1.0));
  Vec3 acc = Vec3::Zero(), gyro = Vec3::Zero();
  int n = 0;
  sim.bus().subscribe("/imu/data", [&](const Topic&, const msg::Message& m) {
    const auto& imu = std::get<msg::Imu>(m);
    acc += imu.linear_acceleration;
    gyro += imu.angular_velocity;
    ++n;
  });
  sim.step_until(SimTime::from_seconds(5.0));
  acc /= n;
  gyro /= n;
  // specific force: +g along the sensor's z at rest; noise 0.02 m/s^2 averages out over 400 samples
  EXPECT_NEAR(acc.z(), 9.81, 0.02);
  EXPECT_NEAR(acc.x(), 0.0, 0.02);
  EXPECT_NEAR(acc.y(), 0.0, 0.02);
  EXPECT_NEAR(gyro.norm(), 0.0, 0.01);
}

TEST(Simulation, ImuSeesTheTurnRate) {
  Simulation sim = make_sim(room_spec());
  double wz = 0;
  int n = 0;
  drive(sim, 0.0, 0.8, 2.0);
  const SubscriptionId h = sim.bus().subscribe("/imu/data", [&](const Topic&, const msg::Message& m) {
    wz += std::get<msg::Imu>(m).angular_velocity.z();
    ++n;
  });
  drive(sim, 0.0, 0.8, 2.0);
  sim.bus().unsubscribe(h);
  EXPECT_NEAR(wz / n, 0.8, 0.04);
}

/// A drive with turns: straight, an arc, a turn on the spot, straight (19 s).
void drive_with_turns(Simulation& sim) {
  drive(sim, 0.5, 0.0, 6.0);
  drive(sim, 0.4, 0.3, 6.0);
  drive(sim, 0.0, -0.6, 3.0);
  drive(sim, 0.5, 0.0, 4.0);
}

/// Pose of the robot relative to its start, by ground truth.
Pose2 truth_from_start(const Simulation& sim) {
  const Pose2 X_W0 = sim.world().robots[0].X_W_start.to_pose2();
  return X_W0.inverse() * sim.state().robots[0].base.X_WB.to_pose2();
}

TEST(Simulation, OdometryMatchesGroundTruthOnFlatFloor) {
  Simulation sim = make_sim(room_spec(30.0));
  drive_with_turns(sim);
  const Pose2 truth = truth_from_start(sim), odom = sim.state().robots[0].odom;
  const double travelled = sim.state().robots[0].distance;
  // wheels roll without slipping on flat floor: well under 2 % of the distance
  EXPECT_GT(travelled, 6.0);
  EXPECT_LT((truth.position() - odom.position()).norm(), 0.02 * travelled);
  EXPECT_NEAR(wrap_angle(truth.yaw - odom.yaw), 0.0, 0.03);
}

TEST(Simulation, TrackOdometrySlipsInTurnsMoreThanWheelOdometry) {
  // the same drive as above for both robots: odometry from the sprockets' speeds counts what
  // the belts move, and a skid-steered track slides sideways along its whole length in a turn
  double error[2] = {0, 0};
  int k = 0;
  for (const char* model : {"rescue_robot", "tracked_robot"}) {
    WorldSpec w = room_spec(30.0);
    w.robots[0].model = model;
    Simulation sim = make_sim(w);
    drive_with_turns(sim);
    const Pose2 truth = truth_from_start(sim), odom = sim.state().robots[0].odom;
    const double travelled = sim.state().robots[0].distance;
    error[k] = (truth.position() - odom.position()).norm() / travelled;
    std::printf("%s: odometry off by %.3f m over %.2f m (%.1f %%), heading off by %.3f rad\n", model,
                (truth.position() - odom.position()).norm(), travelled, 100 * error[k], wrap_angle(truth.yaw - odom.yaw));
    EXPECT_GT(travelled, 6.0);
    EXPECT_NEAR(wrap_angle(truth.yaw - odom.yaw), 0.0, 0.05);  // the heading comes from the gyro
    ++k;
  }
  EXPECT_LT(error[0], 0.02);
  EXPECT_GT(error[1], error[0]);
  EXPECT_LT(error[1], 0.10);
}

TEST(Simulation, OdometryOverestimatesWhenWheelsSlipOnASteepSlope) {
  // a 21 degree ramp (0.3 m over 0.8 m) of a slippery material: tan 21 = 0.38 is more than the
  // 0.3 x 1.0 friction of wheel on ramp, so the wheels spin and the robot hardly climbs
  WorldSpec w = room_spec(20.0);
  MaterialSpec slick = *w.find_material("raised");
  slick.name = "slick";
  slick.friction = 0.3;
  w.set_material(slick);
  RaisedAreaSpec r;
  r.outline = {{2.0, -1.5}, {8.0, -1.5}, {8.0, 1.5}, {2.0, 1.5}};
  r.height = 0.3;
  r.ramp_length = 0.8;
  r.material = "slick";
  r.ramp_edges = {3};
  w.raised_areas.push_back(r);
  Simulation sim = make_sim(w);
  drive(sim, 0.5, 0.0, 8.0);
  const double odom_x = sim.state().robots[0].odom.x;
  const double true_x = truth_from_start(sim).x;
  std::printf("odometry x %.3f m, true x %.3f m, z %.3f m\n", odom_x, true_x, sim.state().robots[0].base.X_WB.p.z());
  // the wheels spin on the slope: odometry counts ground the robot never covered
  EXPECT_GT(odom_x, true_x + 0.5);
}

TEST(Simulation, NonFiniteCommandsAreRejected) {
  Simulation sim = make_sim(room_spec());
  msg::Twist t;
  t.linear.x() = std::nan("");
  EXPECT_FALSE(sim.command_velocity(RobotIndex(0), t));
  EXPECT_FALSE(sim.command_head(RobotIndex(0), {0, 0, INFINITY, 0}));
  EXPECT_FALSE(sim.command_head(RobotIndex(0), {0, 0}));  // wrong count
  EXPECT_FALSE(sim.command_velocity(RobotIndex(3), msg::Twist{}));
  EXPECT_TRUE(sim.command_head(RobotIndex(0), {0.1, 0, 1.5, -1.2}));
}

TEST(Simulation, CommandTimeoutStopsTheRobot) {
  Simulation sim = make_sim(room_spec());
  drive(sim, 0.5, 0.0, 2.0);
  sim.step_until(sim.time() + SimTime::from_seconds(1.5));  // silence: 0.5 s timeout, then braking
  EXPECT_LT(sim.state().robots[0].base.v_WB.norm(), 0.02);
}

TEST(Simulation, AnIdleRobotStaysWhereItStandsAndSoDoesItsOdometry) {
  // 200 s without a command: the drive brakes the wheels where they stopped, so neither the
  // robot nor its odometry wanders (without the brake: 0.7 mm/s forward, odometry yaw 0.26 rad)
  Simulation sim = make_sim(room_spec());
  sim.step_until(SimTime::from_seconds(1.0));  // settled on its wheels
  const Pose3 X0 = sim.state().robots[0].base.X_WB;
  const Pose2 odom0 = sim.state().robots[0].odom;
  sim.step_until(SimTime::from_seconds(201.0));
  const RobotState& r = sim.state().robots[0];
  EXPECT_LT((r.base.X_WB.p - X0.p).norm(), 1e-3);
  EXPECT_LT(std::abs(r.base.X_WB.to_pose2().yaw - X0.to_pose2().yaw), 0.01);
  EXPECT_LT(std::hypot(r.odom.x - odom0.x, r.odom.y - odom0.y), 1e-3);
  EXPECT_LT(std::abs(r.odom.yaw - odom0.yaw), 0.01);
  EXPECT_TRUE(r.braking);

  // and after standing, it drives off as usual and brakes again when told to stop
  drive(sim, 0.5, 0.0, 2.0);
  EXPECT_FALSE(sim.state().robots[0].braking);
  EXPECT_GT(truth_from_start(sim).x, 0.5);
  sim.step_until(sim.time() + SimTime::from_seconds(2.0));
  EXPECT_TRUE(sim.state().robots[0].braking);
  EXPECT_LT(sim.state().robots[0].base.v_WB.norm(), 1e-3);
}

TEST(Simulation, DiscardedCommandsAreNeverApplied) {
  Simulation sim = make_sim(room_spec());
  msg::Twist t;
  t.linear.x() = 0.5;
  ASSERT_TRUE(sim.command_velocity(RobotIndex(0), t));
  ASSERT_TRUE(sim.command_head(RobotIndex(0), {0.4, 0, 1.5, -1.2}));
  EXPECT_EQ(sim.discard_commands(), 2u);
  EXPECT_EQ(sim.discard_commands(), 0u);
  sim.step_until(SimTime::from_seconds(0.5));
  // no command reached the drive: the robot still stands where it started
  EXPECT_LT(sim.state().robots[0].base.v_WB.norm(), 1e-3);
  EXPECT_LT(truth_from_start(sim).x, 1e-3);
}

TEST(Simulation, ASynchronousRunWaitsForTheControllersCommand) {
  Simulation sim = make_sim(room_spec());
  const std::uint64_t before = sim.velocity_commands();
  // nobody answers: the wait ends at its timeout, unanswered
  EXPECT_FALSE(sim.wait_for_velocity_commands(before + 1, std::chrono::milliseconds(20)));
  // a controller on another thread answers: the wait ends with its command
  std::thread controller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    msg::Twist t;
    t.linear.x() = 0.2;
    sim.command_velocity(RobotIndex(0), t);
  });
  EXPECT_TRUE(sim.wait_for_velocity_commands(before + 1, std::chrono::seconds(10)));
  controller.join();
  EXPECT_EQ(sim.velocity_commands(), before + 1);
  // a refused command (NaN) is not an answer
  msg::Twist bad;
  bad.angular.z() = std::nan("");
  EXPECT_FALSE(sim.command_velocity(RobotIndex(0), bad));
  EXPECT_EQ(sim.velocity_commands(), before + 1);
}

TEST(Simulation, TroubleStopsTheRunWithAClearMessage) {
  WorldSpec w = room_spec();
  RubbleSpec box;
  box.pose = {3, 3, 0};
  w.rubble.push_back(box);
  Simulation sim = make_sim(w);
  sim.step_until(SimTime::from_seconds(0.1));
  State s = sim.snapshot();
  s.dynamics[0].X_WB.p = Vec3(3, 3, 1e6);  // flung far out of the world
  sim.restore(s);
  EXPECT_FALSE(sim.step_until(SimTime::from_seconds(1.0)));
  EXPECT_TRUE(sim.in_trouble());
  EXPECT_NE(sim.state().trouble.first.find("rubble_0 was flung out of the world"), std::string::npos) << sim.state().trouble.first;
  const SimTime stopped = sim.time();
  sim.step();
  EXPECT_EQ(sim.time(), stopped);  // nothing more is published once in trouble
}

/// Runs the default scenario for `seconds` and returns (state hash, digest of every message).
std::pair<std::uint64_t, std::uint64_t> fingerprint(double seconds) {
  const ModelMap models = builtin_models();
  const Scenario sc = default_scenario(models);
  const WorldSpec spec = build_world(sc);
  SimOptions o;
  o.seed = sc.seed;
  Simulation sim(compile_scenario(sc, spec, models), o);
  std::uint64_t all = 0;
  sim.bus().subscribe("", [&](const Topic& t, const msg::Message& m) {
    all = all * 1099511628211ull ^ (msg::digest(m) + static_cast<std::uint64_t>(t.id));
  });
  // drive a fixed pattern so everything moves: contacts, head, rubble
  for (int k = 0; k < static_cast<int>(seconds * 10); ++k) {
    msg::Twist t;
    t.linear.x() = 0.5;
    t.angular.z() = k % 40 < 20 ? 0.6 : -0.6;
    sim.command_velocity(RobotIndex(0), t);
    if (k % 50 == 0) sim.command_head(RobotIndex(0), {0.3 * std::sin(k), 0.2, 1.4, -1.0});
    sim.step_until(SimTime::from_ms(100 * (k + 1)));
  }
  return {state_hash(sim.state()), all};
}

TEST(Determinism, SameSeedGivesIdenticalStateAndMessages) {
  const auto a = fingerprint(20.0);
  const auto b = fingerprint(20.0);
  EXPECT_EQ(a.first, b.first);
  EXPECT_EQ(a.second, b.second);
}

TEST(Determinism, OneRayThreadOrAllGiveTheSameRun) {
  set_worker_threads(1);
  const auto one = fingerprint(10.0);
  set_worker_threads(0);
  const auto all = fingerprint(10.0);
  EXPECT_EQ(one.first, all.first);
  EXPECT_EQ(one.second, all.second);
}

TEST(Determinism, DifferentSeedsGiveDifferentNoise) {
  WorldSpec w = room_spec();
  Simulation a = make_sim(w, 1), b = make_sim(w, 2);
  std::uint64_t da = 0, db = 0;
  a.bus().subscribe("/scan", [&](const Topic&, const msg::Message& m) { da ^= msg::digest(m); });
  b.bus().subscribe("/scan", [&](const Topic&, const msg::Message& m) { db ^= msg::digest(m); });
  a.step_until(SimTime::from_seconds(1));
  b.step_until(SimTime::from_seconds(1));
  EXPECT_NE(da, db);
}

}  // namespace
}  // namespace rescuesim
