// The rescue robot's head joints are self-locking (worm-geared): a joint standing at its target is
// held rigid, as a fixed joint with no motor, until its target moves away. Each number below
// follows from the model's constants: 4 wheel and 4 head degrees of freedom; the head's loop
// turns an error e into a speed of 8/s x e (at most 1.5 rad/s); a joint is held within
// kSelfLockTolerance (0.01 rad) of its target and below kSelfLockSpeed (0.01 rad/s).

#include <gtest/gtest.h>

#include <cmath>

#include "world/state.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using testing::Rig;
using testing::room_spec;

std::size_t joint(const Rig& rig, const char* name) { return static_cast<std::size_t>(rig.spec().joint_index(name)); }

TEST(SelfLockingHead, AStillHeadIsHeldRigidAndItsMotorsCarryNoLoad) {
  Rig rig(room_spec());
  EXPECT_EQ(rig.physics->stats().multibody_dofs, 8);  // before the first step nothing is held
  rig.run(1.0);
  EXPECT_EQ(rig.physics->stats().multibody_dofs, 4);  // the wheels alone
  const RobotSpec& spec = rig.spec();
  std::vector<double> held(spec.head_joints.size());
  for (std::size_t i = 0; i < spec.head_joints.size(); ++i) {
    const auto j = joint(rig, spec.head_joints[i].c_str());
    EXPECT_EQ(rig.robot().qd[j], 0.0) << spec.head_joints[i];
    EXPECT_EQ(rig.robot().effort[j], 0.0) << spec.head_joints[i];
    EXPECT_NEAR(rig.robot().q[j], spec.joints[j].initial, kSelfLockTolerance) << spec.head_joints[i];
    held[i] = rig.robot().q[j];
  }
  // full speed, then a stop at the drive's 2.5 m/s^2: a motor-held head would sway; a held one
  // does not move at all
  rig.drive(1.0, 0, 1.5);
  rig.drive(0, 0, 1.0);
  EXPECT_GT(rig.robot().base.X_WB.p.x(), 1.0);
  for (std::size_t i = 0; i < spec.head_joints.size(); ++i) EXPECT_EQ(rig.robot().q[joint(rig, spec.head_joints[i].c_str())], held[i]);
  EXPECT_EQ(rig.physics->stats().multibody_dofs, 4);
}

TEST(SelfLockingHead, ACommandLetsTheJointGoAndItIsHeldAgainAtItsTarget) {
  Rig rig(room_spec());
  rig.run(1.0);
  const auto mast = joint(rig, "mast_yaw");
  const double start = rig.robot().q[mast];
  rig.robot().head_target = {start + 0.5, rig.robot().q[joint(rig, "shoulder_pitch")], rig.robot().q[joint(rig, "elbow_pitch")],
                             rig.robot().q[joint(rig, "head_tilt")]};
  rig.step();  // let go at the start of this step; the others stay held (their targets are where they stand)
  EXPECT_EQ(rig.physics->stats().multibody_dofs, 5);
  EXPECT_GT(rig.robot().qd[mast], 0.5);
  EXPECT_GT(rig.robot().effort[mast], 0.0);
  // 0.31 rad at 1.5 rad/s, then the error falls as e^(-8t): below 1.25 mrad (8/s x 1.25 mrad =
  // the 0.01 rad/s at which it is held) after ln(0.1875 / 0.00125) / 8 = 0.63 s; 0.84 s in all
  rig.run(0.7);
  EXPECT_EQ(rig.physics->stats().multibody_dofs, 5);
  rig.run(0.5);
  EXPECT_EQ(rig.physics->stats().multibody_dofs, 4);
  EXPECT_EQ(rig.robot().qd[mast], 0.0);
  EXPECT_NEAR(rig.robot().q[mast], start + 0.5, 0.0015);
}

TEST(SelfLockingHead, ATargetWithinTheToleranceKeepsTheJointWhereItIsHeld) {
  Rig rig(room_spec());
  rig.run(1.0);
  const auto mast = joint(rig, "mast_yaw");
  const double held = rig.robot().q[mast];
  rig.robot().head_target = {held + 0.5 * kSelfLockTolerance, rig.robot().q[joint(rig, "shoulder_pitch")],
                             rig.robot().q[joint(rig, "elbow_pitch")], rig.robot().q[joint(rig, "head_tilt")]};
  rig.run(0.5);
  EXPECT_EQ(rig.robot().q[mast], held);  // the gear's dead band: the joint does not move
  EXPECT_EQ(rig.physics->stats().multibody_dofs, 4);
}

TEST(SelfLockingHead, ARestoreHoldsTheSameJointsAndReplaysBitwise) {
  // snapshots while the mast is let go and moving, and while everything is held
  for (const double at : {0.2, 1.5}) {
    Rig rig(room_spec());
    rig.run(1.0);
    rig.robot().head_target = {1.0, 0.2, 1.4, -1.0};
    rig.run(at);
    const State snap = rig.state;
    const int dofs = rig.physics->stats().multibody_dofs;
    rig.physics->restore(rig.state);  // a snapshot is a synchronisation point (Simulation::snapshot)
    rig.drive(0.5, 0.3, 1.0);
    const std::uint64_t first = state_hash(rig.state);
    rig.run(0.7);  // elsewhere meanwhile
    rig.state = snap;
    rig.physics->restore(rig.state);
    EXPECT_EQ(rig.physics->stats().multibody_dofs, dofs) << "at " << at;
    rig.drive(0.5, 0.3, 1.0);
    EXPECT_EQ(state_hash(rig.state), first) << "at " << at;
  }
}

}  // namespace
}  // namespace rescuesim
