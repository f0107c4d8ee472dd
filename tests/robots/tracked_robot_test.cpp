// The tracked robot: belts driven by contact surface velocity (LinkShape::belt_joint) push it at
// the sprockets' surface speed, turn it in place, and carry it up 40° stairs and over a
// half-cubic stepfield, where the wheeled rescue robot stays at the bottom.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "robots/tracked_robot.h"
#include "support/rig.h"
#include "world/terrain.h"

namespace rescuesim {
namespace {

using testing::Rig;
using testing::room_spec;

WorldSpec with_model(WorldSpec spec, const char* model) {
  spec.robots.at(0).model = model;
  return spec;
}

/// A terrain element across the robot's way: its near edge 1.0 m ahead of the base's centre.
WorldSpec element_ahead(TerrainSpec::Kind kind, const char* model) {
  WorldSpec spec = room_spec();
  TerrainSpec t = TerrainSpec::defaults(kind);
  t.name = "element";
  t.pose = {1.0 + t.length / 2, 0, 0};
  spec.terrain.push_back(t);
  return with_model(spec, model);
}

int joint(const RobotSpec& spec, const char* name) {
  const int j = spec.joint_index(name);
  EXPECT_GE(j, 0) << name;
  return j;
}

/// Sets both flippers' position targets (rad; positive lowers the tips).
void set_flippers(Rig& rig, double q) {
  for (const auto& name : rig.spec().flipper_joints) {
    rig.robot().joint_target[static_cast<std::size_t>(joint(rig.spec(), name.c_str()))] = q;
  }
}

/// Drives at (v, w) until `done` or `seconds` pass; returns the time it took (or `seconds`).
double drive_until(Rig& rig, double v, double w, double seconds, const std::function<bool(const Pose3&)>& done) {
  const long n = std::lround(seconds / rig.dt());
  for (long i = 0; i < n; ++i) {
    if (done(rig.robot().base.X_WB)) return static_cast<double>(i) * rig.dt();
    rig.drive(v, w, rig.dt());
  }
  return seconds;
}

TEST(TrackedRobot, IsABuiltInModelWithTwoTracksTwoFlippersAndTheSensorHead) {
  const RobotSpec r = tracked_robot();
  EXPECT_EQ(r.model, "tracked_robot");
  EXPECT_GT(r.total_mass(), 20.0);
  EXPECT_LT(r.total_mass(), 30.0);
  EXPECT_EQ(r.flipper_joints.size(), 2u);
  EXPECT_EQ(r.head_joints.size(), 4u);
  int belts = 0;
  for (const auto& l : r.links) {
    for (const auto& sh : l.shapes) belts += sh.belt_joint.empty() ? 0 : 1;
  }
  EXPECT_EQ(belts, 4);  // two tracks, two flippers
  EXPECT_NE(r.find_sensor("laser"), nullptr);
  EXPECT_NE(r.find_sensor("thermal_camera"), nullptr);
}

TEST(TrackedRobot, ItsBeltsCarryItAtTheSprocketsSurfaceSpeed) {
  Rig rig(with_model(room_spec(), "tracked_robot"));
  rig.run(0.5);
  EXPECT_NEAR(rig.robot().base.X_WB.p.z(), 0.09, 0.01);  // on its tracks: the sprocket axis 0.09 m up
  const Vec3 start = rig.robot().base.X_WB.p;
  rig.drive(0.5, 0, 4.0);
  const Vec3 end = rig.robot().base.X_WB.p;
  // 0.5 m/s after a 0.2 s ramp at 2.5 m/s^2: 0.5 × 4 − 0.5 × 0.2 / 2 = 1.95 m, on a belt that grips
  EXPECT_NEAR(end.x() - start.x(), 1.95, 0.08);
  EXPECT_NEAR(end.y() - start.y(), 0.0, 0.05);
  // the sprockets turn at v / r on average (the yaw-rate loop trims their difference)
  const auto qd = [&](const char* name) { return rig.robot().qd[static_cast<std::size_t>(joint(rig.spec(), name))]; };
  EXPECT_NEAR(0.5 * (qd("left_sprocket_joint") + qd("right_sprocket_joint")), 0.5 / 0.09, 0.2);
  // and stopped, the brake holds it
  rig.run(1.0);
  const Vec3 parked = rig.robot().base.X_WB.p;
  rig.run(2.0);
  EXPECT_NEAR((rig.robot().base.X_WB.p - parked).norm(), 0.0, 0.002);
}

// On a floor patch the belts grip with the patch's friction (physics_contacts.cpp's floor-contact callback
// reaches the multibody solver too): asked for 1 m/s at once (the drive's ramp lifted), the belts
// run at once and slip until the robot catches up, so it gathers speed at mu g, the friction (the
// belt's 1.0 times the ground's) times g. After 0.2 s: on wet tiles (0.25) 0.49 m/s, on sand (0.4)
// 0.78 m/s; on the floor (0.9) 0.88 m/s after 0.1 s, and then the belts' 1 m/s. Measured 2-5 %
// under mu g t (0.479, 0.766, 0.843 m/s).
TEST(TrackedRobot, OnAFloorPatchItsBeltsSlipAtTheGroundsFriction) {
  for (const auto& [ground, mu] : std::vector<std::pair<std::string, double>>{{"wet_tiles", 0.25}, {"sand", 0.4}, {"", 0.9}}) {
    WorldSpec spec = with_model(room_spec(), "tracked_robot");
    if (!ground.empty()) spec.ground.push_back({"patch", {{-3, -2}, {6, -2}, {6, 2}, {-3, 2}}, ground, {}});
    Rig rig(spec);
    rig.world.robots[0].spec.drive.max_linear_accel = 1000;  // belts at full speed in one step
    rig.run(0.5);
    double v_01 = 0, v_02 = 0;
    for (int i = 1; i <= 40; ++i) {
      rig.drive(1.0, 0, rig.dt());
      if (i == 20) v_01 = rig.robot().base.v_WB.x();
      if (i == 40) v_02 = rig.robot().base.v_WB.x();
    }
    const std::string what = ground.empty() ? "floor" : ground;
    EXPECT_NEAR(v_01, mu * 9.81 * 0.1, 0.06 * mu * 9.81 * 0.1) << what;
    EXPECT_NEAR(v_02, std::min(1.0, mu * 9.81 * 0.2), 0.06 * std::min(1.0, mu * 9.81 * 0.2)) << what;
  }
}

TEST(TrackedRobot, ItTurnsInPlace) {
  Rig rig(with_model(room_spec(), "tracked_robot"));
  rig.run(0.5);
  const Vec3 start = rig.robot().base.X_WB.p;
  double yaw = 0, last = rig.robot().base.X_WB.yaw();
  // 1 rad/s for 4 s (after a ramp of 1/6 s at 6 rad/s^2): 3.92 rad, with the yaw-rate feedback
  for (int i = 0; i < 800; ++i) {
    rig.drive(0, 1.0, rig.dt());
    const double now = rig.robot().base.X_WB.yaw();
    yaw += std::remainder(now - last, 2 * M_PI);
    last = now;
  }
  EXPECT_NEAR(yaw, 3.92, 0.1);
  // a skid-steer turn wanders: the tracks slide sideways over their whole length and the centre
  // of mass sits ahead of the middle; measured 0.43 m over these 3.9 rad, where a belt pushing
  // the wrong way, or one not pushing, would carry it off by metres or not turn it at all
  EXPECT_LT((rig.robot().base.X_WB.p - start).head<2>().norm(), 0.5);
}

TEST(TrackedRobot, ItsFlippersGoWhereTheyAreSent) {
  Rig rig(with_model(room_spec(), "tracked_robot"));
  rig.run(0.3);
  // stowed at the start, folded back over the tracks
  for (const auto& name : rig.spec().flipper_joints) {
    EXPECT_NEAR(rig.robot().q[static_cast<std::size_t>(joint(rig.spec(), name.c_str()))], -170 * M_PI / 180, 0.02) << name;
  }
  set_flippers(rig, -0.6);  // tips up ahead: 2.4 rad at 1.5 rad/s
  rig.run(3.0);
  for (const auto& name : rig.spec().flipper_joints) {
    EXPECT_NEAR(rig.robot().q[static_cast<std::size_t>(joint(rig.spec(), name.c_str()))], -0.6, 0.02) << name;
  }
  // tips down far enough lifts the front of the chassis: the flippers bear on the ground
  set_flippers(rig, 0.9);
  rig.run(2.0);
  EXPECT_GT(std::asin(std::clamp((rig.robot().base.X_WB.q * Vec3::UnitX()).z(), -1.0, 1.0)), 0.15) << "the nose should rise";
}

/// Pitch of the chassis (rad, nose up positive).
double nose_up(const Pose3& X) { return std::asin(std::clamp((X.q * Vec3::UnitX()).z(), -1.0, 1.0)); }

TEST(TrackedRobot, ClimbsFortyDegreeStairsWhereTheWheeledRobotCannot) {
  // the landing (0.8 m up) begins 3 treads (3 × 0.238 m) past the first riser at x = 1.0
  auto on_landing = [](const Pose3& X) { return X.p.x() > 2.2 && X.p.z() > 0.8; };
  {
    Rig rig(element_ahead(TerrainSpec::Kind::stairs, "tracked_robot"));
    rig.run(0.3);
    // as operators climb: flippers raised to meet the first step, then, once the nose is up
    // (17°), lowered onto the stairs, where they reach the next nose before the chassis pitches
    // past the stairs' slope and keep it from rearing over
    set_flippers(rig, -0.6);
    rig.run(2.0);  // out of their stowed position before it sets off
    const double t = drive_until(rig, 0.3, 0, 20.0, [&](const Pose3& X) {
      if (nose_up(X) > 0.3) set_flippers(rig, 0.2);
      return on_landing(X);
    });
    EXPECT_LT(t, 20.0) << "stuck at " << rig.robot().base.X_WB.p.transpose();
    EXPECT_NEAR(rig.robot().base.X_WB.p.z(), 0.8 + 0.09, 0.05);  // on its tracks on the landing
    EXPECT_NEAR(nose_up(rig.robot().base.X_WB), 0.0, 0.1);
  }
  {
    Rig rig(element_ahead(TerrainSpec::Kind::stairs, "rescue_robot"));
    rig.run(0.3);
    const double t = drive_until(rig, 0.3, 0, 20.0, on_landing);
    EXPECT_EQ(t, 20.0);
    EXPECT_LT(rig.robot().base.X_WB.p.z(), 0.4);
  }
}

TEST(TrackedRobot, CrossesAHalfCubicStepfieldWhereTheWheeledRobotCannot) {
  // the stepfield (5-20 cm posts) runs from x = 1.0 to 3.4 m; across means the base beyond it,
  // back on the floor
  auto across = [](const Pose3& X) { return X.p.x() > 3.8 && X.p.z() < 0.12; };
  {
    Rig rig(element_ahead(TerrainSpec::Kind::stepfield, "tracked_robot"));
    rig.run(0.3);
    set_flippers(rig, -0.3);  // tips up a little, to ride onto the posts
    rig.run(2.0);
    const double t = drive_until(rig, 0.3, 0, 40.0, across);
    EXPECT_LT(t, 40.0) << "stuck at " << rig.robot().base.X_WB.p.transpose();
  }
  {
    Rig rig(element_ahead(TerrainSpec::Kind::stepfield, "rescue_robot"));
    rig.run(0.3);
    const double t = drive_until(rig, 0.3, 0, 40.0, across);
    EXPECT_EQ(t, 40.0);
  }
}

TEST(TrackedRobot, ClimbsAFifteenCentimetreCurbThatStopsTheWheeledRobot) {
  // the curb's face at x = 1.6; the tracked robot climbs it with flippers level and comes down
  // its far side (x = 2.2) back onto the floor
  auto beyond = [](const Pose3& X) { return X.p.x() > 2.8 && X.p.z() < 0.12; };
  Rig tracked(element_ahead(TerrainSpec::Kind::curb, "tracked_robot"));
  tracked.run(0.3);
  EXPECT_LT(drive_until(tracked, 0.3, 0, 20.0, beyond), 20.0) << "stuck at " << tracked.robot().base.X_WB.p.transpose();
  Rig wheeled(element_ahead(TerrainSpec::Kind::curb, "rescue_robot"));
  wheeled.run(0.3);
  EXPECT_EQ(drive_until(wheeled, 0.3, 0, 20.0, beyond), 20.0);
}

}  // namespace
}  // namespace rescuesim
