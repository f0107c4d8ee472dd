#include "world/robot_spec.h"

#include <Eigen/Eigenvalues>

namespace rescuesim {

int RobotSpec::link_index(const std::string& name) const {
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (links[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

int RobotSpec::joint_index(const std::string& name) const {
  for (std::size_t i = 0; i < joints.size(); ++i) {
    if (joints[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

const SensorSpec* RobotSpec::find_sensor(const std::string& name) const {
  for (const auto& s : sensors) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

SensorSpec* RobotSpec::find_sensor(const std::string& name) {
  for (auto& s : sensors) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

double RobotSpec::total_mass() const {
  double m = 0;
  for (const auto& l : links) m += l.mass;
  return m;
}

Pose3 joint_motion(const JointSpec& j, double q) {
  switch (j.type) {
    case JointSpec::Type::fixed: return Pose3{};
    case JointSpec::Type::prismatic: return Pose3{q * j.axis.normalized(), Quat::Identity()};
    case JointSpec::Type::revolute:
    case JointSpec::Type::continuous: break;
  }
  return Pose3{Vec3::Zero(), Quat(Eigen::AngleAxisd(q, j.axis.normalized()))};
}

std::vector<Pose3> link_poses(const RobotSpec& robot, const std::vector<double>& q) {
  std::vector<Pose3> X(robot.links.size());
  for (std::size_t j = 0; j < robot.joints.size(); ++j) {
    const JointSpec& js = robot.joints[j];
    const int p = robot.link_index(js.parent), c = robot.link_index(js.child);
    if (p < 0 || c < 0) continue;
    X[static_cast<std::size_t>(c)] = X[static_cast<std::size_t>(p)] * js.X_PJ * joint_motion(js, j < q.size() ? q[j] : 0.0);
  }
  return X;
}

Eigen::Matrix3d inertia_tensor(const LinkSpec& link) {
  const Eigen::Matrix3d R = link.inertia_axes.toRotationMatrix();
  return R * link.inertia.asDiagonal() * R.transpose();
}

void set_inertia_tensor(LinkSpec& link, const Eigen::Matrix3d& I_L) {
  const Eigen::Matrix3d I = 0.5 * (I_L + I_L.transpose());
  // already diagonal: keep the axes exactly as they are (no round-off from a decomposition)
  if (I(0, 1) == 0 && I(0, 2) == 0 && I(1, 2) == 0) {
    link.inertia = I.diagonal();
    link.inertia_axes = Quat::Identity();
    return;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
  Eigen::Matrix3d V = eig.eigenvectors();
  if (V.determinant() < 0) V.col(2) = -V.col(2);  // a rotation, not a reflection
  link.inertia = eig.eigenvalues();
  link.inertia_axes = Quat(V).normalized();
}

double wheel_sign(const std::vector<double>& signs, std::size_t i) { return i < signs.size() ? signs[i] : 1.0; }

std::vector<double> initial_positions(const RobotSpec& robot) {
  std::vector<double> q;
  for (const auto& j : robot.joints) q.push_back(j.initial);
  return q;
}

}  // namespace rescuesim
