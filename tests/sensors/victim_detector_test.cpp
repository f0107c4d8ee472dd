// Victim detection (sensors/victim_detector.h): line of sight through the thermal camera's
// frustum with a ray test for occlusion, and the thermal-image detector, which leaves robots with
// a rendered thermal camera to the camera service and checks the others by line of sight.

#include "sensors/victim_detector.h"

#include <gtest/gtest.h>

#include <numbers>

#include "raycast/ray_scene.h"
#include "sensors/ray_sensor_world.h"

namespace rescuesim {
namespace {

using namespace rescuesim::testing;

// a thermal camera 0.2 m ahead of and 0.2 m above base_link, looking along +x (hfov 1.2 rad:
// |y| / depth up to tan 0.6 = 0.68; 320 × 240: |z| / depth up to 0.51), range 0.1 .. 10 m
SensorSpec thermal(double max_range = 10.0) {
  SensorSpec s;
  s.name = "thermal";
  s.type = SensorSpec::Type::thermal_camera;
  s.link = "base_link";
  s.X_LS = Pose3{Vec3(0.2, 0, 0.2), Quat::Identity()};
  s.camera.max_range = max_range;
  return s;
}

// one box robot "scout" at the origin facing +x, and a victim lying across the x axis at (x, 0)
struct Scene {
  World world;
  State state;
};
Scene scene(double victim_x, const std::vector<SensorSpec>& sensors, double wall_at = 0) {
  WorldSpec spec = empty_spec();
  if (wall_at > 0) spec.walls.push_back(wall_facing_west(wall_at));
  VictimSpec v;
  v.name = "anna";
  v.pose = {victim_x, 0, std::numbers::pi / 2};
  spec.victims.push_back(v);
  RobotPlacement p;
  p.name = "scout";
  p.model = "box_bot";
  spec.robots.push_back(p);
  Scene s{compile_with(spec, box_robot(sensors)), {}};
  s.state = initial_state(s.world);
  s.state.time = SimTime{2'500'000'000};
  return s;
}

// runs one check and returns the victim's state
VictimState check(const VictimDetector& d, Scene& s) {
  RayScene rays(s.world);
  rays.update(s.state);
  d.check(s.world, s.state, rays);
  return s.state.victims.at(0);
}

TEST(LineOfSight, FindsAVictimInViewAtTheCheckTime) {
  // the torso is 1.3 m ahead of the camera, well inside the frustum and the range
  Scene s = scene(1.5, {thermal()});
  const VictimState v = check(LineOfSightDetector(), s);
  EXPECT_EQ(v.first_seen, SimTime{2'500'000'000});
  EXPECT_EQ(v.seen_by, "scout");
}

TEST(LineOfSight, KeepsTheFirstSighting) {
  Scene s = scene(1.5, {thermal()});
  s.state.victims[0].first_seen = SimTime{1'000'000'000};
  s.state.victims[0].seen_by = "earlier";
  const VictimState v = check(LineOfSightDetector(), s);
  EXPECT_EQ(v.first_seen, SimTime{1'000'000'000});
  EXPECT_EQ(v.seen_by, "earlier");
}

TEST(LineOfSight, MissesVictimsHiddenBehindOutOfRangeOrWithoutACamera) {
  Scene hidden = scene(1.5, {thermal()}, 1.0);  // a 1 m high wall at x = 1 between them
  EXPECT_LT(check(LineOfSightDetector(), hidden).first_seen.ns, 0);
  Scene behind = scene(-1.5, {thermal()});      // depth -1.7 m: behind the camera
  EXPECT_LT(check(LineOfSightDetector(), behind).first_seen.ns, 0);
  Scene far = scene(1.5, {thermal(1.0)});       // 1.3 m ahead, range 1 m
  EXPECT_LT(check(LineOfSightDetector(), far).first_seen.ns, 0);
  Scene blind = scene(1.5, {});                 // no thermal camera
  EXPECT_LT(check(LineOfSightDetector(), blind).first_seen.ns, 0);
}

TEST(LineOfSight, LooksOnlyForTheRobotsItIsGiven) {
  Scene s = scene(1.5, {thermal()});
  EXPECT_LT(check(LineOfSightDetector({false}), s).first_seen.ns, 0);
  EXPECT_EQ(check(LineOfSightDetector({true}), s).seen_by, "scout");
}

TEST(ThermalImages, LeavesRenderedRobotsToTheImagesAndChecksTheOthersByLineOfSight) {
  Scene rendered = scene(1.5, {thermal()});
  EXPECT_LT(check(ThermalImageDetector({true}), rendered).first_seen.ns, 0);
  Scene disabled = scene(1.5, {thermal()});
  EXPECT_EQ(check(ThermalImageDetector({false}), disabled).seen_by, "scout");
}

TEST(VictimDetector, NamesAreTheRunSummaryValues) {
  EXPECT_EQ(LineOfSightDetector().name(), "line of sight");
  EXPECT_EQ(ThermalImageDetector({true}).name(), "thermal images");
}

}  // namespace
}  // namespace rescuesim
