// The conformance corpus in physics (tests/data/thirdparty/robots, corpus.yaml): every public
// URDF that loads rests on a floor for 2 s without exploding, and the robots whose files carry
// a drive plugin drive straight as commanded. The loading side is tests/import/urdf/urdf_corpus_test.cpp.

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "import/urdf/urdf_import.h"
#include "sim/simulation.h"

namespace rescuesim {
namespace {

std::filesystem::path corpus_dir() { return std::filesystem::path(RESCUESIM_SOURCE_DIR) / "tests/data/thirdparty/robots"; }

/// name -> the robot, for every URDF of the corpus that loads.
std::vector<std::pair<std::string, RobotSpec>> corpus_robots() {
  std::vector<std::pair<std::string, RobotSpec>> out;
  for (const auto& e : YAML::LoadFile((corpus_dir() / "corpus.yaml").string())) {
    if (e["format"].as<std::string>() != "urdf") continue;
    const std::filesystem::path file = e["file"].as<std::string>();
    UrdfOptions o;
    o.resolver = ResourceResolver({corpus_dir() / file.begin()->string()}, false);
    try {
      out.emplace_back(e["name"].as<std::string>(), load_urdf(corpus_dir() / file, o).spec);
    } catch (const Error&) {
      // the files that do not load are the import test's concern
    }
  }
  return out;
}

World on_a_floor(const RobotSpec& robot) {
  WorldSpec w;
  w.floor_min = {-10, -10};
  w.floor_max = {10, 10};
  w.materials = default_materials();
  RobotPlacement p;
  p.name = "r";
  p.model = "m";
  w.robots.push_back(p);
  return compile_world(w, {{"m", robot}});
}

bool has_collision(const RobotSpec& robot) {
  for (const LinkSpec& l : robot.links) {
    for (const LinkShape& sh : l.shapes) {
      if (sh.collides) return true;
    }
  }
  return false;
}

TEST(UrdfCorpusSim, EveryRobotThatLoadsRestsOnAFloorWithoutExploding) {
  // a robot standing or falling over on a floor: after 2 s no joint turns faster than 20 rad/s
  // (a wheel at 1 m/s with a 5 cm radius), the base moves slower than 2 m/s and stays within
  // 2 m of where it started, and nothing is NaN. A robot without any collision shape (PyBullet's
  // pan-tilt, qb's TwoDofs: meant for a fixed base) falls through the floor as in Gazebo, freely:
  // after 2 s at 9.81 m/s^2 it falls at 19.62 m/s and has fallen 19.62 m
  const auto robots = corpus_robots();
  ASSERT_GE(robots.size(), 25u);
  int resting = 0, falling = 0;
  for (const auto& [name, spec] : robots) {
    SCOPED_TRACE(name);
    Simulation sim(on_a_floor(spec));
    const Vec3 start = sim.state().robots[0].base.X_WB.p;
    while (sim.time() < SimTime::from_seconds(2.0)) sim.step();
    const RobotState& s = sim.state().robots[0];
    ASSERT_TRUE(s.base.X_WB.p.allFinite());
    if (!has_collision(spec)) {
      ++falling;
      EXPECT_NEAR(s.base.v_WB.z(), -19.62, 0.05);
      EXPECT_NEAR(start.z() - s.base.X_WB.p.z(), 19.62, 0.1);
      continue;
    }
    ++resting;
    EXPECT_LT(s.base.v_WB.norm(), 2.0);
    EXPECT_LT((s.base.X_WB.p - start).norm(), 2.0);
    EXPECT_GT(s.base.X_WB.p.z(), -0.05) << "fell through the floor";
    for (std::size_t j = 0; j < s.qd.size(); ++j) {
      EXPECT_TRUE(std::isfinite(s.qd[j])) << spec.joints[j].name;
      EXPECT_LT(std::abs(s.qd[j]), 20.0) << spec.joints[j].name;
    }
  }
  EXPECT_EQ(falling, 2);
  std::printf("URDF corpus in physics: %d robots rest on the floor, %d without collision shapes fall freely\n", resting, falling);
}

TEST(UrdfCorpusSim, RobotsWithADrivePluginDriveAMetreStraight) {
  // the Pioneer 3-AT and Seekur Jr carry Gazebo's skid-steer plugin: 0.25 m/s held for 5 s
  // after a second to get going covers 1.25 m; within 10 %
  int driven = 0;
  for (const auto& [name, spec] : corpus_robots()) {
    if (spec.drive.left_wheels.empty()) continue;
    SCOPED_TRACE(name);
    ++driven;
    Simulation sim(on_a_floor(spec));
    msg::Twist t;
    t.linear = Vec3(0.25, 0, 0);
    auto hold = [&](double seconds) {
      const SimTime end = sim.time() + SimTime::from_seconds(seconds);
      while (sim.time() < end) {
        sim.command_velocity(RobotIndex(0), t);
        sim.step();
      }
    };
    hold(1.0);
    const Vec3 p0 = sim.state().robots[0].base.X_WB.p;
    hold(5.0);
    const Vec3 p1 = sim.state().robots[0].base.X_WB.p;
    EXPECT_NEAR((p1 - p0).head<2>().norm(), 1.25, 0.125);
  }
  EXPECT_EQ(driven, 2);
}

}  // namespace
}  // namespace rescuesim
