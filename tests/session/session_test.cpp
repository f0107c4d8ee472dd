// A whole run through Session: the default scenario's explorer finds victims, the outputs
// are written and say so, and two runs with the same seed agree.

#include "session/session.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <map>

#include "msgs/digest.h"
#include "robots/rescue_robot.h"
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
