#include "sensors/ground_truth.h"

namespace rescuesim {

namespace {

msg::TransformStamped transform(SimTime stamp, const std::string& parent, const std::string& child, const Pose3& X) {
  msg::TransformStamped t;
  t.header = {stamp, parent};
  t.child_frame_id = child;
  t.transform = X;
  return t;
}

}  // namespace

msg::PoseStamped sample_ground_truth(const State& state, RobotIndex robot, SimTime stamp) {
  msg::PoseStamped p;
  p.header = {stamp, "map"};
  p.pose = state.robot(robot).base.X_WB;
  return p;
}

msg::TFMessage ground_truth_tf(const State& state, RobotIndex robot, SimTime stamp, const GroundTruthTf& tf) {
  const RobotState& rs = state.robot(robot);
  msg::TFMessage out;
  if (tf.odom_to_base) out.transforms.push_back(transform(stamp, tf.odom_frame, tf.base_frame, rs.base.X_WB));
  if (tf.map_to_odom) {
    // odom sits where the odometry pose (true or dead-reckoned) must put it for the chain to be true
    const Pose3 X_OB = tf.odom_to_base ? rs.base.X_WB : Pose3::from_pose2(rs.odom);
    out.transforms.push_back(transform(stamp, "map", tf.odom_frame, rs.base.X_WB * X_OB.inverse()));
  }
  return out;
}

}  // namespace rescuesim
