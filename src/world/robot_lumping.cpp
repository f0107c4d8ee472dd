#include "world/robot_lumping.h"

namespace rescuesim {

LumpedRobot lump_fixed_joints(const RobotSpec& robot) {
  LumpedRobot out;
  const std::size_t n_links = robot.links.size();
  out.body_of_link.assign(n_links, -1);
  out.X_BL.assign(n_links, Pose3{});
  out.lumped_joint.assign(robot.joints.size(), -1);
  RobotSpec& s = out.spec;
  s = robot;
  s.links.clear();
  s.joints.clear();

  // the root and every child of a moving joint start a body; joints are in tree order, so a
  // parent's body is known before its children are placed
  if (n_links == 0) return out;
  out.body_of_link[0] = 0;
  s.links.push_back(robot.links[0]);
  std::vector<std::vector<int>> members(1, std::vector<int>{0});
  for (std::size_t j = 0; j < robot.joints.size(); ++j) {
    const JointSpec& js = robot.joints[j];
    const int p = robot.link_index(js.parent), c = robot.link_index(js.child);
    if (p < 0 || c < 0) continue;
    const auto pu = static_cast<std::size_t>(p), cu = static_cast<std::size_t>(c);
    const int body = out.body_of_link[pu];
    if (js.type == JointSpec::Type::fixed) {
      out.body_of_link[cu] = body;
      out.X_BL[cu] = out.X_BL[pu] * js.X_PJ;
      members[static_cast<std::size_t>(body)].push_back(c);
      continue;
    }
    out.body_of_link[cu] = static_cast<int>(s.links.size());
    s.links.push_back(robot.links[cu]);
    members.push_back({c});
    JointSpec lj = js;
    lj.parent = s.links[static_cast<std::size_t>(body)].name;
    lj.X_PJ = out.X_BL[pu] * js.X_PJ;
    out.lumped_joint[j] = static_cast<int>(s.joints.size());
    out.joint_of.push_back(static_cast<int>(j));
    s.joints.push_back(lj);
  }

  // bodies of several links: combined mass, centre of mass and inertia; shapes in the body frame
  for (std::size_t b = 0; b < members.size(); ++b) {
    if (members[b].size() == 1) continue;
    LinkSpec& body = s.links[b];
    double mass = 0;
    Vec3 weighted = Vec3::Zero();
    for (int l : members[b]) {
      const LinkSpec& ls = robot.links[static_cast<std::size_t>(l)];
      mass += ls.mass;
      weighted += ls.mass * (out.X_BL[static_cast<std::size_t>(l)] * ls.com);
    }
    const Vec3 com = mass > 0 ? Vec3(weighted / mass) : Vec3::Zero();
    Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
    body.shapes.clear();
    body.friction_scale = robot.links[static_cast<std::size_t>(members[b][0])].friction_scale;
    for (int l : members[b]) {
      const LinkSpec& ls = robot.links[static_cast<std::size_t>(l)];
      const Pose3& X = out.X_BL[static_cast<std::size_t>(l)];
      const Eigen::Matrix3d R = X.q.toRotationMatrix();
      // the link's inertia turned into the body frame, moved to the common centre of mass
      const Vec3 d = X * ls.com - com;
      I += R * inertia_tensor(ls) * R.transpose() + ls.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
      for (LinkShape sh : ls.shapes) {
        sh.X_LG = X * sh.X_LG;
        body.shapes.push_back(std::move(sh));
      }
    }
    body.mass = mass;
    body.com = com;
    set_inertia_tensor(body, I);
  }
  return out;
}

}  // namespace rescuesim
