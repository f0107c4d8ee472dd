// The rescue robot meets test-method terrain in the physics: its 0.11 m wheels climb a curb lower
// than their radius and are stopped by one higher than it, as a wheel that meets a step above its
// axle pushes into the step's face instead of rolling onto it.

#include <gtest/gtest.h>

#include "support/rig.h"
#include "world/terrain.h"

namespace rescuesim {
namespace {

using testing::Rig;
using testing::room_spec;

/// The robot at the origin facing +x and a curb whose face is 1.0 m ahead of the base's centre
/// (0.7 m ahead of the bumper), across the whole 1.2 m lane.
Rig curb_ahead(double height) {
  WorldSpec spec = room_spec();
  TerrainSpec curb = TerrainSpec::defaults(TerrainSpec::Kind::curb);
  curb.name = "curb";
  curb.height = height;
  curb.length = 6.0;  // the curb is the footprint's far half: x from 1.0 to 4.0 m
  curb.pose = {1.0, 0, 0};
  spec.terrain.push_back(curb);
  return Rig(spec);
}

TEST(TerrainDrive, TheRescueRobotClimbsAFiveCentimetreCurbButNotAFifteenCentimetreOne) {
  {
    Rig rig = curb_ahead(0.05);
    rig.run(0.3);
    rig.drive(0.5, 0, 6.0);  // 3 m of wheel travel: over the curb's face at 1.0 m and on along its top
    const Pose3 X = rig.robot().base.X_WB;
    EXPECT_GT(X.p.x(), 2.0);
    EXPECT_LT(X.p.x(), 3.2);
    EXPECT_NEAR(X.p.z(), 0.15 + 0.05, 0.02);  // base_link 0.15 m above the ground it stands on
  }
  {
    Rig rig = curb_ahead(0.15);
    rig.run(0.3);
    rig.drive(0.5, 0, 6.0);
    const Pose3 X = rig.robot().base.X_WB;
    // the front wheels (0.18 m ahead of the base, 0.11 m radius) stop against the face: the base
    // at 1.0 - 0.18 - 0.11 = 0.71 m, give or take the wheels' squash and a little climb
    EXPECT_LT(X.p.x(), 0.85);
    EXPECT_GT(X.p.x(), 0.6);
    EXPECT_LT(X.p.z(), 0.15 + 0.15);
  }
}

}  // namespace
}  // namespace rescuesim
