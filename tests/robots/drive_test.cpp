// The rescue robot on the physics engine: speeds, turns, ramps and walls, each against a
// number computed by hand.

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>

#include "support/rig.h"

namespace rescuesim {
namespace {

using testing::Rig;
using testing::room_spec;

TEST(RescueRobot, WeighsAboutTwentyFiveKilograms) {
  const RobotSpec r = rescue_robot();
  EXPECT_NEAR(r.total_mass(), 25.0, 1.5);
  EXPECT_EQ(r.head_joints.size(), 4u);
}

TEST(RescueRobot, SettlesOnItsWheels) {
  Rig rig(room_spec());
  rig.run(1.0);
  const Pose3 X = rig.robot().base.X_WB;
  // base_link is 0.15 m up when the 0.11 m wheels (0.04 m below it) stand on the floor
  EXPECT_NEAR(X.p.z(), 0.15, 0.01);
  EXPECT_NEAR(X.p.x(), 0.0, 0.01);
  EXPECT_NEAR(X.p.y(), 0.0, 0.01);
  std::printf("settled z %.4f, yaw %.4f, head q = %.3f %.3f %.3f %.3f\n", X.p.z(), X.yaw(), rig.robot().q[4], rig.robot().q[5],
              rig.robot().q[6], rig.robot().q[7]);
}

TEST(RescueRobot, DrivesTwoMetresInFourSecondsAtHalfAMetrePerSecond) {
  Rig rig(room_spec());
  rig.run(0.5);
  const Vec3 p0 = rig.robot().base.X_WB.p;
  rig.drive(0.5, 0.0, 4.0);
  const double d = (rig.robot().base.X_WB.p - p0).head<2>().norm();
  std::printf("distance %.4f m, lateral %.4f m\n", d, rig.robot().base.X_WB.p.y() - p0.y());
  // 0.5 m/s for 4 s, less the acceleration ramp (0.5^2 / (2 * 2.5) = 0.05 m): 1.95 m
  EXPECT_NEAR(d, 2.0, 0.10);
  EXPECT_NEAR(rig.robot().base.X_WB.p.y() - p0.y(), 0.0, 0.05);
}

TEST(RescueRobot, TurnsAtTheCommandedRate) {
  Rig rig(room_spec());
  rig.run(0.5);
  rig.drive(0.0, 0.5, 1.0);  // reach the rate
  const double yaw0 = rig.robot().base.X_WB.yaw();
  double turned = 0, prev = yaw0;
  for (int k = 0; k < 20; ++k) {
    rig.drive(0.0, 0.5, 0.1);
    const double y = rig.robot().base.X_WB.yaw();
    turned += wrap_angle(y - prev);
    prev = y;
  }
  std::printf("turned %.4f rad in 2 s (rate %.4f)\n", turned, turned / 2.0);
  EXPECT_NEAR(turned / 2.0, 0.5, 0.05);
}

}  // namespace
}  // namespace rescuesim

namespace rescuesim {
namespace {

using testing::Rig;
using testing::room_spec;

TEST(RescueRobot, TurnsAtTheCommandedRateWhileDriving) {
  for (double w : {0.25, 1.0, -1.5}) {
    Rig rig(room_spec());
    rig.run(0.3);
    rig.drive(0.3, w, 1.0);
    double prev = rig.robot().base.X_WB.yaw(), turned = 0;
    for (int k = 0; k < 20; ++k) {
      rig.drive(0.3, w, 0.1);
      const double y = rig.robot().base.X_WB.yaw();
      turned += wrap_angle(y - prev);
      prev = y;
    }
    EXPECT_NEAR(turned / 2.0, w, 0.05 * std::abs(w)) << "commanded " << w;
  }
}

TEST(RescueRobot, StopsWhenCommandsStop) {
  Rig rig(room_spec());
  rig.drive(0.5, 0, 2.0);
  // no new command: after the 0.5 s timeout the controller ramps to zero at 2.5 m/s^2
  rig.run(1.5);
  EXPECT_NEAR(rig.robot().base.v_WB.norm(), 0.0, 0.02);
}

TEST(RescueRobot, ClimbsTheDefaultRamp) {
  // the maze's raised cell: a 10 cm platform with a 40 cm ramp (14 degrees) on its west side
  WorldSpec w = room_spec(20.0, {0, 0, 0});
  RaisedAreaSpec r;
  r.outline = {{2.4, -1.0}, {4.4, -1.0}, {4.4, 1.0}, {2.4, 1.0}};
  r.height = 0.10;
  r.ramp_length = 0.40;
  r.ramp_edges = {3};  // edge from (2.4, 1) to (2.4, -1): the west side
  w.raised_areas.push_back(r);
  Rig rig(w);
  rig.run(0.3);
  rig.drive(0.4, 0, 9.0);
  const Vec3 p = rig.robot().base.X_WB.p;
  // on top: base_link 0.15 m above the 0.10 m platform
  EXPECT_GT(p.x(), 3.0);
  EXPECT_NEAR(p.z(), 0.25, 0.02);
  EXPECT_EQ(rig.state.trouble.nan_poses + rig.state.trouble.escaped, 0);
}

TEST(RescueRobot, IsStoppedByAWallAtFullSpeed) {
  WorldSpec w = room_spec(20.0, {0, 0, 0});
  w.walls.push_back({{2.0, -2.0}, {2.0, 2.0}, 0.05, 1.0, "wall", {}});  // 5 cm thick, face at x = 1.975
  Rig rig(w);
  rig.run(0.3);
  rig.drive(1.0, 0, 5.0);  // the drive's top speed, for far longer than it takes to arrive
  const Pose3 X = rig.robot().base.X_WB;
  // the chassis' front (x + 0.30) rests against the wall face, never through it
  EXPECT_LT(X.p.x() + 0.30, 1.975 + 0.01);
  EXPECT_GT(X.p.x() + 0.30, 1.80);
  EXPECT_GE(rig.robot().collisions, 1);
  EXPECT_NE(std::find(rig.robot().touching.begin(), rig.robot().touching.end(), "wall_4"), rig.robot().touching.end());
}

TEST(RescueRobot, HeadHoldsItsPoseAndFollowsCommands) {
  Rig rig(room_spec());
  rig.run(1.0);
  const RobotSpec& spec = rig.spec();
  // at rest every head joint sits at its initial position despite gravity
  for (std::size_t i = 0; i < spec.head_joints.size(); ++i) {
    const int j = spec.joint_index(spec.head_joints[i]);
    EXPECT_NEAR(rig.robot().q[static_cast<std::size_t>(j)], spec.joints[static_cast<std::size_t>(j)].initial, 0.02) << spec.head_joints[i];
  }
  // a command beyond the mast's 170 degree limit is clamped to it
  rig.robot().head_target = {4.0, 0.3, 1.2, -0.9};
  rig.run(4.0);
  const int mast = spec.joint_index("mast_yaw");
  EXPECT_NEAR(rig.robot().q[static_cast<std::size_t>(mast)], 170 * M_PI / 180, 0.02);
  EXPECT_NEAR(rig.robot().q[static_cast<std::size_t>(spec.joint_index("shoulder_pitch"))], 0.3, 0.02);
  EXPECT_NEAR(rig.robot().q[static_cast<std::size_t>(spec.joint_index("head_tilt"))], -0.9, 0.02);
}

// The drive controller alone (no physics): a robot wedged so that its chassis never turns, told
// to turn at 1 rad/s for 5 s, then to back up straight at 0.5 m/s. The yaw-rate integral may add
// at most three times the set turn rate while turning and 0.2 rad/s while going straight, so once
// the set points have ramped (0.2 s at 2.5 m/s^2 and 6 rad/s^2) the wheels turn at
// (-0.5 -+ 0.2 h) / r, h = half the effective track: both sides backwards. With the integral
// unbounded by the set rate (0.5 rad before, 10 rad/s of turn) the sides counter-rotated and the
// robot could not back off whatever it was told.
TEST(DriveController, AWedgedRobotToldToBackUpDrivesBothSidesBackwards) {
  const RobotSpec spec = rescue_robot();
  const DriveSpec& d = spec.drive;
  RobotState s;
  s.q.assign(spec.joints.size(), 0.0);
  s.qd.assign(spec.joints.size(), 0.0);
  const double dt = 0.005;
  SimTime now{0};
  const auto run = [&](double v, double w, double seconds) {
    for (int i = 0; i < static_cast<int>(std::lround(seconds / dt)); ++i) {
      s.cmd_linear = Vec3(v, 0, 0);
      s.cmd_angular = Vec3(0, 0, w);
      s.cmd_time = now;
      update_drive(spec, s, now, dt);  // the chassis' angular velocity stays zero: wedged
      now += SimTime::from_seconds(dt);
    }
  };
  run(0.0, 1.0, 5.0);
  EXPECT_NEAR(s.yaw_rate_integral, 3.0 * 1.0 / d.yaw_rate_ki, 1e-12);
  run(-0.5, 0.0, 1.0);
  EXPECT_NEAR(s.drive_v, -0.5, 1e-12);
  EXPECT_NEAR(s.drive_w, 0.0, 1e-12);
  EXPECT_NEAR(s.yaw_rate_integral, 0.2 / d.yaw_rate_ki, 1e-12);
  const double h = 0.5 * d.track_width * d.track_multiplier;
  for (std::size_t i = 0; i < d.left_wheels.size(); ++i) {
    const double target = s.joint_target[static_cast<std::size_t>(spec.joint_index(d.left_wheels[i]))] * wheel_sign(d.left_signs, i);
    EXPECT_NEAR(target, (-0.5 - 0.2 * h) / d.wheel_radius, 1e-9);
    EXPECT_LT(target, 0.0);
  }
  for (std::size_t i = 0; i < d.right_wheels.size(); ++i) {
    const double target = s.joint_target[static_cast<std::size_t>(spec.joint_index(d.right_wheels[i]))] * wheel_sign(d.right_signs, i);
    EXPECT_NEAR(target, (-0.5 + 0.2 * h) / d.wheel_radius, 1e-9);
    EXPECT_LT(target, 0.0);
  }
}

}  // namespace
}  // namespace rescuesim
