#include "world/robot_spec.h"

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

std::vector<Pose3> link_poses(const RobotSpec& robot, const std::vector<double>& q) {
  std::vector<Pose3> X(robot.links.size());
  for (std::size_t j = 0; j < robot.joints.size(); ++j) {
    const JointSpec& js = robot.joints[j];
    const int p = robot.link_index(js.parent), c = robot.link_index(js.child);
    if (p < 0 || c < 0) continue;
    const double angle = js.type == JointSpec::Type::fixed || j >= q.size() ? 0.0 : q[j];
    const Pose3 rot{Vec3::Zero(), Quat(Eigen::AngleAxisd(angle, js.axis.normalized()))};
    X[static_cast<std::size_t>(c)] = X[static_cast<std::size_t>(p)] * js.X_PJ * rot;
  }
  return X;
}

std::vector<double> initial_positions(const RobotSpec& robot) {
  std::vector<double> q;
  for (const auto& j : robot.joints) q.push_back(j.initial);
  return q;
}

const char* sensor_type_name(SensorSpec::Type t) {
  switch (t) {
    case SensorSpec::Type::lidar: return "lidar";
    case SensorSpec::Type::sonar: return "sonar";
    case SensorSpec::Type::imu: return "imu";
    case SensorSpec::Type::odometry: return "odometry";
    case SensorSpec::Type::ground_truth: return "ground_truth";
    case SensorSpec::Type::joint_states: return "joint_states";
    case SensorSpec::Type::contact: return "contact";
    case SensorSpec::Type::color_camera: return "color_camera";
    case SensorSpec::Type::depth_camera: return "depth_camera";
    case SensorSpec::Type::thermal_camera: return "thermal_camera";
  }
  return "unknown";
}

}  // namespace rescuesim
