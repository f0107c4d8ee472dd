// A whole run through Session: the default scenario's explorer finds victims, the outputs
// are written and say so, and two runs with the same seed agree.

#include "session/session.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <map>

#include "msgs/digest.h"
#include "robots/rescue_robot.h"
#include "session/explorer_settings.h"
#include "support/command.h"

namespace rescuesim {
namespace {

SessionOptions no_cameras() {
  SessionOptions o;
  o.cameras = false;
  return o;
}

TEST(Session, TheExplorerFindsVictimsInTheDefaultScenario) {
  const ModelMap models = builtin_models();
  Scenario s = default_scenario(models);
  Session session(s, models, no_cameras());
  const RunResult r = session.run();
  EXPECT_EQ(r.stop_reason, "duration");
  EXPECT_DOUBLE_EQ(r.sim_time, 180.0);
  EXPECT_GE(r.victims_found, 1);
  EXPECT_GT(r.distance, 10.0);
  EXPECT_GT(r.coverage, 0.2);
  EXPECT_FALSE(r.trouble);

  const auto dir = testing::temp_dir("session-out");
  session.write_outputs(dir, r);
  const auto j = nlohmann::json::parse(testing::slurp(dir / "summary.json"));
  EXPECT_EQ(j["victims_found"].get<int>(), r.victims_found);
  EXPECT_EQ(j["seed"].get<std::uint64_t>(), s.seed);
  EXPECT_EQ(j["message_counts"]["/scan"].get<int>(), 1801);  // 10 Hz for 180 s, and t = 0
  for (const char* f : {"overview.png", "trajectory.csv", "world.svg", "sensors/laser.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  }
  // trajectory at 10 Hz: a header and 1801 rows
  const std::string csv = testing::slurp(dir / "trajectory.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1802);
}

TEST(Session, TheExplorerSwingsTheRescueRobotsCameraFromSideToSide) {
  // the built-in explorer swings the mast (the thermal camera's yaw joint) by +-60 degrees
  // every 4 s; the joint moves at most 1.5 rad/s, less than the sine's 1.65 at its middle, so
  // the swing comes out a little smaller but still well past +-45 degrees either way
  const ModelMap models = builtin_models();
  Scenario s = default_scenario(models);
  s.duration = 8.0;
  Session session(s, models, no_cameras());
  double lo = 0, hi = 0;
  session.sim().bus().subscribe("/joint_states", [&](const Topic&, const msg::Message& m) {
    const auto& js = std::get<msg::JointState>(m);
    for (std::size_t i = 0; i < js.name.size(); ++i) {
      if (js.name[i] != "mast_yaw") continue;
      lo = std::min(lo, js.position[i]);
      hi = std::max(hi, js.position[i]);
    }
  });
  const RunResult r = session.run();
  EXPECT_GT(hi, 45 * M_PI / 180);
  EXPECT_LT(lo, -45 * M_PI / 180);
  EXPECT_LT(hi, 61 * M_PI / 180);
  EXPECT_GT(lo, -61 * M_PI / 180);
  // what the explorer did is in the summary
  ASSERT_EQ(r.explorers.size(), 1u);
  EXPECT_EQ(r.explorers[0].first, "robot");
  // 10 Hz for 8 s and t = 0, less any that came before the first odometry or contradicted it
  EXPECT_LE(r.explorers[0].second.scans, 81);
  EXPECT_GE(r.explorers[0].second.scans, 75);
  const auto dir = testing::temp_dir("session-explorer");
  session.write_outputs(dir, r);
  const auto j = nlohmann::json::parse(testing::slurp(dir / "summary.json"));
  EXPECT_EQ(j["explorers"]["robot"]["scans"].get<int>(), r.explorers[0].second.scans);
}

TEST(Session, TheRescueRobotsVictimCameraIsModelledWithItsMast) {
  const autonomy::ExplorerLookConfig look = victim_camera_look(rescue_robot());
  EXPECT_TRUE(look.enabled);
  EXPECT_EQ(look.yaw_joint, "mast_yaw");
  EXPECT_EQ(look.yaw_sign, 1.0);
  EXPECT_NEAR(look.fixed_yaw, 0.0, 1e-9);       // the head looks ahead at the start
  EXPECT_NEAR(look.fan.hfov, 0.85 * 57 * M_PI / 180, 1e-9);
  EXPECT_NEAR(look.fan.range, 0.8 * 6.0, 1e-9);
  EXPECT_NEAR(look.sweep_amplitude, 1.05, 1e-12);  // well inside the mast's +-170 degrees
  // a robot without a thermal camera has nothing to model
  RobotSpec blind = rescue_robot();
  std::erase_if(blind.sensors, [](const SensorSpec& x) { return x.type == SensorSpec::Type::thermal_camera; });
  EXPECT_FALSE(victim_camera_look(blind).enabled);
  // a camera fixed to the body: modelled, but nothing to swing
  RobotSpec fixed = rescue_robot();
  for (auto& x : fixed.sensors) {
    if (x.type == SensorSpec::Type::thermal_camera) x.link = "base_link";
  }
  const autonomy::ExplorerLookConfig f = victim_camera_look(fixed);
  EXPECT_TRUE(f.enabled);
  EXPECT_TRUE(f.yaw_joint.empty());
  // without a swing (the ROS navigation node cannot command the mast) the camera stays where it
  // starts: with the mast started 0.3 rad to the left, the camera looks 0.3 rad to the left
  RobotSpec turned = rescue_robot();
  turned.joints[static_cast<std::size_t>(turned.joint_index("mast_yaw"))].initial = 0.3;
  const autonomy::ExplorerLookConfig still = victim_camera_look(turned, /*swing=*/false);
  EXPECT_TRUE(still.enabled);
  EXPECT_TRUE(still.yaw_joint.empty());
  EXPECT_NEAR(still.fixed_yaw, 0.3, 1e-9);
  EXPECT_NEAR(still.fan.range, 0.8 * 6.0, 1e-9);
  // with it, the swing is about the body's ahead whatever the mast's start
  const autonomy::ExplorerLookConfig swung = victim_camera_look(turned);
  EXPECT_EQ(swung.yaw_joint, "mast_yaw");
  EXPECT_NEAR(swung.fixed_yaw, 0.0, 1e-9);
}

TEST(Session, StopsWhenAllVictimsAreFoundIfAsked) {
  // the default maze with one victim, seeded 16: the victim lies in the thermal camera's view
  // from the start, so it is found at the first check whatever the explorer does (with the
  // default seed 7 the explorer never finds it in 180 s; with seeds 1-15 it finds it only for 8 and 11)
  const ModelMap models = builtin_models();
  Scenario s = default_scenario(models);
  s.seed = 16;
  s.maze->seed = 16;
  s.maze->victims = 1;
  s.stop_when_all_found = true;
  Session session(s, models, no_cameras());
  const RunResult r = session.run();
  ASSERT_EQ(r.victims_found, 1) << "the explorer missed the only victim in " << r.sim_time << " s";
  EXPECT_EQ(r.stop_reason, "all victims found");
  EXPECT_EQ(r.victims[0].time, 0.0);
  EXPECT_LT(r.sim_time, 0.1);  // stopped right after the check that found it
}

/// Samples of a run of the default scenario for `seconds` with at most `cap` trajectory points.
std::vector<TrajectoryPoint> capped_trajectory(std::size_t cap, double seconds, SimTime* interval) {
  const ModelMap models = builtin_models();
  Scenario s = default_scenario(models);
  s.duration = seconds;
  SessionOptions o = no_cameras();
  o.trajectory_max_points = cap;
  Session session(s, models, o);
  session.run();
  *interval = session.record_interval();
  return session.trajectory();
}

TEST(Session, ALongTrajectoryIsThinnedEvenlyWithinItsCap) {
  // 10 Hz, at most 20 points, 10 s. By hand: 0..1.9 s fill it; at 2.0 every other one goes
  // (0, 0.2, .., 1.8) and the rate halves; 0..3.8 by 0.2 fill it again, at 4.0 -> 0.4 s;
  // 0..7.6 by 0.4, at 8.0 -> 0.8 s: 0, 0.8, .., 7.2, 8.0, 8.8, 9.6 = 13 points
  SimTime interval;
  const auto traj = capped_trajectory(20, 10.0, &interval);
  ASSERT_EQ(traj.size(), 13u);
  EXPECT_EQ(interval, SimTime::from_seconds(0.8));
  for (std::size_t i = 0; i < traj.size(); ++i) EXPECT_NEAR(traj[i].t, 0.8 * static_cast<double>(i), 1e-6) << i;

  // 21 points: the first thinning comes with an odd count (0..2.0 s, 21 samples) so the sample
  // due at 2.1 s falls between the kept ones (0, 0.2, .., 2.0) and is skipped: still even spacing
  const auto odd = capped_trajectory(21, 5.0, &interval);
  EXPECT_EQ(interval, SimTime::from_seconds(0.4));
  ASSERT_GE(odd.size(), 2u);
  EXPECT_LE(odd.size(), 21u);
  for (std::size_t i = 0; i < odd.size(); ++i) EXPECT_NEAR(odd[i].t, 0.4 * static_cast<double>(i), 1e-6) << i;
}

TEST(Session, InvalidWorldIsRefusedWithItsProblems) {
  const ModelMap models = builtin_models();
  Scenario s = default_scenario(models);
  s.robots[0].start = Pose2{0.0, 0.0, 0.0};  // on the corner of the outer walls
  try {
    Session session(s, models);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("clearance"), std::string::npos) << e.what();
  }
}

TEST(SessionCameras, ThermalImagesFindVictimsAndFramesAreWritten) {
  const ModelMap models = builtin_models();
  Scenario s = default_scenario(models);
  s.duration = 10;
  Session session(s, models);
  if (session.render_device().empty()) GTEST_SKIP() << "no renderer";
  std::map<std::string, int> counts;
  session.sim().bus().subscribe("", [&](const Topic& t, const msg::Message&) { ++counts[t.name]; });
  const RunResult r = session.run();
  // 10 Hz for 10 s and the frame at t = 0; the last frames are delivered when the run ends
  for (const char* t : {"/camera/color/image_raw", "/camera/depth/image_raw", "/camera/depth/points", "/thermal/image_raw",
                        "/thermal/image_mono8", "/thermal/camera_info"}) {
    EXPECT_EQ(counts[t], 101) << t;
  }
  // the maze's first victim lies in the start cell's neighbour, in the head's view from the start
  EXPECT_GE(r.victims_found, 1);
  const auto dir = testing::temp_dir("session-cams");
  session.write_outputs(dir, r);
  for (const char* f : {"sensors/color_camera.png", "sensors/depth_camera.png", "sensors/thermal_camera.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  }
}

TEST(SessionCameras, SameSeedGivesIdenticalImages) {
  const ModelMap models = builtin_models();
  auto digest_of_run = [&] {
    Scenario s = default_scenario(models);
    s.duration = 3;
    Session session(s, models);
    std::uint64_t all = 0;
    session.sim().bus().subscribe("", [&](const Topic& t, const msg::Message& m) {
      all = all * 1099511628211ull ^ (msg::digest(m) + static_cast<std::uint64_t>(t.id));
    });
    session.run();
    return all;
  };
  EXPECT_EQ(digest_of_run(), digest_of_run());
}

}  // namespace
}  // namespace rescuesim
