// Sonar against a wall: the head-on distance, specular loss at grazing incidence worked out by
// hand, REP-117 limits, the robot's own body unheard, and the cone's ray pattern.

#include "sensors/sonar.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sensors/ray_sensor_world.h"

namespace rescuesim {
namespace {

using namespace rescuesim::testing;

/// A sonar 5 cm above base_link (inside the robot's own box), turned `yaw` from the robot's x axis.
SensorSpec test_sonar(double yaw = 0.0) {
  SensorSpec s;
  s.name = "sonar_front";
  s.type = SensorSpec::Type::sonar;
  s.link = "base_link";
  s.X_LS = Pose3::from_rpy(Vec3(0, 0, 0.05), 0, 0, yaw);
  s.rate = 10;
  s.frame_id = "sonar_front";
  s.sonar.fov = 0.5;
  s.sonar.rays = 5;
  s.sonar.min_range = 0.03;
  s.sonar.max_range = 4.0;
  s.sonar.max_incidence = 1.05;
  s.sonar.noise = {0.0, 0.0, 0.0};
  return s;
}

/// The reading of `s` on a robot at the origin facing +x, with a wall whose face is x = d.
msg::Range read(const SensorSpec& s, double d, Rng& rng, const RobotSpec* model = nullptr) {
  WorldSpec spec = empty_spec();
  spec.walls.push_back(wall_facing_west(d));
  spec.robots.push_back({"r", "box_bot", {0, 0, 0}, {}});
  const World world = compile_with(spec, model ? *model : box_robot({s}));
  const RayScene scene(world);
  return sample_sonar(world, initial_state(world), scene, RobotIndex(0), s, SimTime::from_ms(300), rng);
}

TEST(SonarWall, HeadOnReadsTheAxisDistance) {
  // against a plane met head-on the axis ray is the shortest of the cone, so the reading is the
  // distance itself. The cone's lowest ray (pitch −0.25 rad) meets the floor, 0.2 m down, 0.82 m
  // away at 75.7° (1.32 rad) from its normal: steeper than max_incidence, so no echo.
  Rng rng(1, "sonar");
  const msg::Range r = read(test_sonar(), 1.5, rng);
  EXPECT_NEAR(r.range, 1.5, 1e-3);
  EXPECT_EQ(r.radiation_type, msg::Range::kUltrasound);
  EXPECT_FLOAT_EQ(r.field_of_view, 0.5f);
  EXPECT_FLOAT_EQ(r.min_range, 0.03f);
  EXPECT_FLOAT_EQ(r.max_range, 4.0f);
  EXPECT_EQ(r.header.frame_id, "sonar_front");
  EXPECT_EQ(r.header.stamp, SimTime::from_ms(300));
}

// The sonar turned 60° from the wall's normal, fov 0.25 rad, 5 × 5 rays: the grid angles are
// {−0.125, −0.0625, 0, 0.0625, 0.125} rad in yaw y and pitch p, and the 13 inside the cone
// (angle to the axis acos(cos p cos y) ≤ 0.125) are the axis row and column plus (±0.0625,
// ±0.0625). With the wall face x = 1, a ray meets it at incidence acos(cos p cos(60° + y)) and
// distance 1 / (cos p cos(60° + y)):
//   y = −0.125,  p = 0       : 52.84°, 0.9222 rad, 1.6556 m   (the least steep ray)
//   y = −0.0625, p = 0       : 56.42°, 0.9852 rad
//   y = −0.0625, p = ±0.0625 :         0.9864 rad
//   y = 0,       p = 0       : 60.00°, 1.0472 rad
//   y = 0,       p = ±0.0625 :         1.0484 rad
//   y = 0,       p = ±0.125  :         1.0507 rad             (misses 1.05 by a hair)
//   y > 0                    : ≥ 63.6°, ≥ 1.110 rad
// With max_incidence 1.05 six rays echo and the nearest is the first: 1 / cos(60° − 0.125 rad).
// With 0.9 none does (the least steep is 0.9222 rad), so there is no echo: +inf.
TEST(SonarIncidence, GrazingWallEchoesOnlyUnderTheWiderLimit) {
  SensorSpec s = test_sonar(M_PI / 3);
  s.sonar.fov = 0.25;
  Rng rng(1, "sonar");
  s.sonar.max_incidence = 1.05;
  EXPECT_NEAR(read(s, 1.0, rng).range, 1.0 / std::cos(M_PI / 3 - 0.125), 1e-4);
  s.sonar.max_incidence = 0.9;
  const float none = read(s, 1.0, rng).range;
  EXPECT_TRUE(std::isinf(none) && none > 0);
}

TEST(SonarIncidence, ConeHasTheRaysWorkedOutAbove) {
  SonarSpec cone;
  cone.fov = 0.25;
  cone.rays = 5;
  std::vector<Vec3> d;
  sonar_directions(cone, d);
  EXPECT_EQ(d.size(), 13u);
  for (const Vec3& v : d) {
    EXPECT_NEAR(v.norm(), 1.0, 1e-12);
    EXPECT_LE(std::acos(std::min(1.0, v.x())), 0.125 + 1e-9);
  }
  // an even grid has no axis ray of its own, so the axis is added: 2 × 2 within the cone + 1
  cone.rays = 2;
  sonar_directions(cone, d);
  EXPECT_EQ(d.size(), 1u);  // the four corners sit at 0.177 rad, outside the 0.125 rad cone
  EXPECT_EQ(d[0], Vec3::UnitX());
  cone.rays = 1;
  sonar_directions(cone, d);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0], Vec3::UnitX());
}

TEST(SonarRep117, NoEchoIsPlusInfinityAndTooNearIsMinusInfinity) {
  Rng rng(1, "sonar");
  // facing away from the wall: nothing but the floor, which is too steep to echo
  const float away = read(test_sonar(M_PI), 1.5, rng).range;
  EXPECT_TRUE(std::isinf(away) && away > 0);
  // the wall beyond max_range
  const float far = read(test_sonar(), 4.5, rng).range;
  EXPECT_TRUE(std::isinf(far) && far > 0);
  // the wall nearer than min_range
  SensorSpec near = test_sonar();
  near.sonar.min_range = 2.0;
  const float too_near = read(near, 1.5, rng).range;
  EXPECT_TRUE(std::isinf(too_near) && too_near < 0);
}

TEST(SonarSelf, RobotNeverHearsItsOwnLinks) {
  // a plate 0.3 m in front of the sonar on the robot's own link, square to the axis
  const SensorSpec s = test_sonar();
  RobotSpec model = box_robot({s});
  model.links[0].shapes.push_back({Geometry::box({0.05, 0.6, 0.3}), Pose3{Vec3(0.3, 0, 0.05), Quat::Identity()}, "robot_body", true});
  Rng rng(1, "sonar");
  EXPECT_NEAR(read(s, 1.5, rng, &model).range, 1.5, 1e-3);
}

TEST(SonarNoise, SameSeedSameReadingAndNoiseStaysInRange) {
  SensorSpec s = test_sonar();
  s.sonar.noise = {0.01, 0.0, 0.0};
  Rng a(5, "sonar"), b(5, "sonar");
  const float ra = read(s, 1.5, a).range, rb = read(s, 1.5, b).range;
  EXPECT_EQ(ra, rb);
  EXPECT_NE(ra, 1.5f);
  EXPECT_NEAR(ra, 1.5, 0.06);
  // a wall right at max_range: noise never carries the reading past it
  s.sonar.max_range = 1.5001;
  for (int k = 0; k < 50; ++k) EXPECT_LE(read(s, 1.5, a).range, 1.5001f);
}

}  // namespace
}  // namespace rescuesim
