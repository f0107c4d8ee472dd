#include "sensors/joint_state.h"

namespace rescuesim {

msg::JointState sample_joint_states(const World& world, const State& state, RobotIndex robot, SimTime stamp) {
  const RobotSpec& spec = world.robot(robot).spec;
  const RobotState& rs = state.robot(robot);
  msg::JointState js;
  js.header = {stamp, ""};
  // fixed joints never move: they are on /tf_static, not here
  for (std::size_t j = 0; j < spec.joints.size(); ++j) {
    if (spec.joints[j].type == JointSpec::Type::fixed) continue;
    js.name.push_back(spec.joints[j].name);
    js.position.push_back(rs.q[j]);
    js.velocity.push_back(rs.qd[j]);
    js.effort.push_back(rs.effort[j]);
  }
  return js;
}

}  // namespace rescuesim
