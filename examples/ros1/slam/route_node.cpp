// route_node: scripted tele-operation. Drives the robot through a list of waypoints by
// publishing /cmd_vel at 20 Hz, as the seed paper's operator drove the real robot round the
// office while SLAM ran. Like a human operator it sees where the robot really is: it steers on
// ~pose_topic (default /ground_truth/pose, geometry_msgs/PoseStamped); the SLAM node never
// sees that topic. When the last waypoint is reached it stops the robot and exits.
//
// Parameters: ~route (file of "x y" lines, # comments), ~pose_topic, ~speed (m/s, 0.8),
// ~turn_speed (rad/s, 1.2), ~tolerance (m, 0.15), ~stuck_time (s, 20: skip a waypoint not
// reached by then).

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>

#include "pose2.h"

namespace {

struct Waypoint {
  double x, y;
  int line;
};

// reads "x y [# comment]" lines; an unreadable file or line is fatal, naming the file and line
bool read_route(const std::string& path, std::vector<Waypoint>& out) {
  std::ifstream in(path);
  if (!in) {
    ROS_FATAL("route_node: cannot read ~route file '%s'", path.c_str());
    return false;
  }
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    line = line.substr(0, line.find('#'));
    std::istringstream s(line);
    Waypoint w{0, 0, n};
    std::string rest;
    if (!(s >> w.x)) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;  // blank or comment
    } else if ((s >> w.y) && !(s >> rest) && std::isfinite(w.x) && std::isfinite(w.y)) {
      out.push_back(w);
      continue;
    }
    ROS_FATAL("route_node: %s:%d: expected two numbers \"x y\", got '%s'", path.c_str(), n, line.c_str());
    return false;
  }
  if (out.empty()) {
    ROS_FATAL("route_node: %s: no waypoints", path.c_str());
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "route_node");
  ros::NodeHandle nh, pnh("~");
  std::string route_file, pose_topic;
  double speed, turn_speed, tolerance, stuck_time;
  pnh.param<std::string>("route", route_file, "");
  pnh.param<std::string>("pose_topic", pose_topic, "/ground_truth/pose");
  pnh.param("speed", speed, 0.8);
  pnh.param("turn_speed", turn_speed, 1.2);
  pnh.param("tolerance", tolerance, 0.15);
  pnh.param("stuck_time", stuck_time, 20.0);
  if (route_file.empty()) {
    ROS_FATAL("route_node: set ~route to a waypoint file (e.g. _route:=examples/ros1/slam/office_route.txt)");
    return 2;
  }
  if (!(speed > 0) || !(turn_speed > 0) || !(tolerance > 0) || !(stuck_time > 0)) {
    ROS_FATAL("route_node: ~speed, ~turn_speed, ~tolerance and ~stuck_time must be > 0");
    return 2;
  }
  std::vector<Waypoint> route;
  if (!read_route(route_file, route)) return 2;

  slam_demo::Pose2 pose;
  bool have_pose = false;
  auto sub = nh.subscribe<geometry_msgs::PoseStamped>(pose_topic, 10, [&](const geometry_msgs::PoseStamped::ConstPtr& m) {
    pose = {m->pose.position.x, m->pose.position.y, slam_demo::yaw_of(m->pose.orientation)};
    have_pose = true;
  });
  auto pub = nh.advertise<geometry_msgs::Twist>("cmd_vel", 10);

  ROS_INFO("route_node: %zu waypoints from %s, steering on %s", route.size(), route_file.c_str(), pose_topic.c_str());
  std::size_t next = 0;
  ros::Time since;
  ros::Rate rate(20.0);
  while (ros::ok() && next < route.size()) {
    ros::spinOnce();
    rate.sleep();
    if (!have_pose) continue;
    if (since.isZero()) since = ros::Time::now();
    const Waypoint& w = route[next];
    const double dx = w.x - pose.x, dy = w.y - pose.y, dist = std::hypot(dx, dy);
    const bool stuck = (ros::Time::now() - since).toSec() > stuck_time;
    if (dist < tolerance || stuck) {
      if (stuck) ROS_WARN("route_node: waypoint %zu (line %d) not reached in %.0f s; skipped", next + 1, w.line, stuck_time);
      else ROS_INFO("route_node: waypoint %zu/%zu (%.1f, %.1f) reached at t = %.1f s", next + 1, route.size(), w.x, w.y,
                    ros::Time::now().toSec());
      ++next;
      since = ros::Time::now();
      continue;
    }
    // turn towards the waypoint; drive forward only when roughly facing it
    const double err = slam_demo::wrap_angle(std::atan2(dy, dx) - pose.yaw);
    geometry_msgs::Twist cmd;
    cmd.angular.z = std::clamp(2.0 * err, -turn_speed, turn_speed);
    const double facing = std::max(0.0, 1.0 - std::fabs(err) / 0.5);
    cmd.linear.x = speed * facing * std::min(1.0, dist / 0.5 + 0.3);
    pub.publish(cmd);
  }
  // stop: zero commands for a moment (the drive would also stop by itself 0.5 s later)
  for (int i = 0; i < 10 && ros::ok(); ++i) {
    pub.publish(geometry_msgs::Twist());
    rate.sleep();
  }
  if (next == route.size()) ROS_INFO("route_node: route done at t = %.1f s", ros::Time::now().toSec());
  return 0;
}
