#pragma once
/// Fixed joints merged for physics, as Gazebo lumps them: every link hanging from its parent by
/// a fixed joint becomes part of that parent's rigid body (masses, centres of mass and inertias
/// combined, shapes carried over), so the physics engine sees one body per group and only the
/// moving joints. The RobotSpec itself keeps every link and fixed joint for TF and sensor mounts.

#include <vector>

#include "world/robot_spec.h"

namespace rescuesim {

/// A robot as physics sees it.
struct LumpedRobot {
  RobotSpec spec;                 ///< links = rigid bodies (named after their top link), joints = moving joints only
  std::vector<int> body_of_link;  ///< per original link: its body (index into spec.links)
  std::vector<Pose3> X_BL;        ///< per original link: its frame in its body's frame
  std::vector<int> joint_of;      ///< per lumped joint: index of the original joint
  std::vector<int> lumped_joint;  ///< per original joint: index of the lumped joint, -1 for fixed joints
};

/// Merges fixed joints. A robot without fixed joints comes back unchanged (bitwise: the same
/// numbers, so its physics is identical).
LumpedRobot lump_fixed_joints(const RobotSpec& robot);

}  // namespace rescuesim
