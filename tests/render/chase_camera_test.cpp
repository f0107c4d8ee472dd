// The chase camera's geometry (render/camera_model.h): look_at frames, where the chase eye sits
// behind a robot, and how clear_eye lifts or pulls the eye in past a wall.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "render/camera_model.h"

namespace rescuesim {
namespace {

TEST(LookAt, AlongXIsTheWorldFrameAndAlongYIsAQuarterTurn) {
  const Pose3 ahead = look_at(Vec3(1, 2, 3), Vec3(5, 2, 3));
  EXPECT_TRUE(ahead.p.isApprox(Vec3(1, 2, 3)));
  EXPECT_TRUE(ahead.q.toRotationMatrix().isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  const Pose3 left = look_at(Vec3::Zero(), Vec3(0, 2, 0));
  EXPECT_NEAR(left.yaw(), std::numbers::pi / 2, 1e-12);
  // looking down 45° towards (1, 0, -1): x axis (1, 0, -1)/√2, y stays level
  const Eigen::Matrix3d R = look_at(Vec3::Zero(), Vec3(1, 0, -1)).q.toRotationMatrix();
  EXPECT_TRUE(R.col(0).isApprox(Vec3(1, 0, -1) / std::sqrt(2.0), 1e-12));
  EXPECT_TRUE(R.col(1).isApprox(Vec3(0, 1, 0), 1e-12));
}

TEST(ChasePoints, BehindAboveAndAheadOfTheHeading) {
  // a robot at (1, 1, 0) facing +y: behind is −y
  const Pose3 X_WB{Vec3(1, 1, 0), Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()))};
  const ChasePoints c = chase_points(X_WB);
  EXPECT_TRUE(c.eye.isApprox(Vec3(1, 1 - kChaseBack, kChaseUp), 1e-12));
  EXPECT_TRUE(c.target.isApprox(Vec3(1, 1 + kChaseAhead, kChaseAim), 1e-12));
}

TEST(ClearEye, UnchangedLiftedOrPulledIn) {
  const Vec3 eye(-2.5, 0, 1.8), target(1.2, 0, 0.1), robot(0, 0, 0);
  // nothing in the way
  EXPECT_TRUE(clear_eye([](const Vec3&, const Vec3&) { return false; }, eye, target, robot).isApprox(eye));
  // a wall that hides everything from eyes below 2.3 m: two sixths of kMaxEyeLift (0.5 m) up
  const auto wall = [](const Vec3& from, const Vec3&) { return from.z() < 2.3 - 1e-9; };
  EXPECT_TRUE(clear_eye(wall, eye, target, robot).isApprox(Vec3(-2.5, 0, 2.3)));
  // a wall that only eyes within 1 m (in x) of the target see past: from the lifted eye
  // (-2.5, 0, 3.3) towards the target in tenths, the first with x ≥ 0.2 is 0.2 of the way
  const auto near_only = [&](const Vec3& from, const Vec3&) { return from.x() < 0.2 - 1e-9; };
  const Vec3 lifted = eye + Vec3(0, 0, kMaxEyeLift);
  EXPECT_TRUE(clear_eye(near_only, eye, target, robot).isApprox(target + (lifted - target) * 0.2));
  // always hidden: 0.1 of the way
  EXPECT_TRUE(clear_eye([](const Vec3&, const Vec3&) { return true; }, eye, target, robot).isApprox(target + (lifted - target) * 0.1));
}

}  // namespace
}  // namespace rescuesim
