// slam_node: ICP scan-matching SLAM as a ROS 1 node (MRPT's CMetricMapBuilderICP; icp_slam.h).
// Consumes /scan, /odom and the laser mount from /tf_static; publishes the occupancy grid on
// /map (latched, every ~map_period s) and map -> odom on /tf for each processed scan, like
// gmapping or slam_toolbox would. Run with /use_sim_time true when the simulator drives time.

#include <deque>
#include <map>
#include <string>

#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

#include "icp_slam.h"
#include "pose_buffer.h"

namespace slam_demo {
namespace {

struct Mount {
  std::string parent;
  Pose2 X_PC;
  double z = 0;
};

class SlamNode {
 public:
  SlamNode(ros::NodeHandle& nh, ros::NodeHandle& pnh, const IcpSlamOptions& options)
      : slam_(options), odom_(30.0) {
    pnh.param<std::string>("map_frame", map_frame_, "map");
    pnh.param<std::string>("odom_frame", odom_frame_, "odom");
    pnh.param<std::string>("base_frame", base_frame_, "base_link");
    pnh.param("map_period", map_period_, 1.0);
    map_pub_ = nh.advertise<nav_msgs::OccupancyGrid>("map", 1, /*latch=*/true);
    tf_pub_ = nh.advertise<tf2_msgs::TFMessage>("tf", 10);
    // deep queues: scans wait for the odometry of their stamp, and none is dropped when the
    // simulation runs faster than the matching for a while
    scan_sub_ = nh.subscribe("scan", 200, &SlamNode::on_scan, this);
    odom_sub_ = nh.subscribe("odom", 1000, &SlamNode::on_odom, this);
    tf_static_sub_ = nh.subscribe("tf_static", 10, &SlamNode::on_tf_static, this);
    map_timer_ = nh.createTimer(ros::Duration(map_period_), [this](const ros::TimerEvent&) { publish_map(); });
  }

  void finish() const {
    ROS_INFO("slam_node: %d scans matched", slam_.scans());
  }

 private:
  void on_tf_static(const tf2_msgs::TFMessage& msg) {
    for (const auto& t : msg.transforms) {
      const auto& p = t.transform.translation;
      mounts_[t.child_frame_id] = {t.header.frame_id, {p.x, p.y, yaw_of(t.transform.rotation)}, p.z};
    }
  }

  void on_odom(const nav_msgs::Odometry& msg) {
    const auto& p = msg.pose.pose;
    odom_.add(msg.header.stamp.toSec(), {p.position.x, p.position.y, yaw_of(p.orientation)});
    process_pending();
  }

  void on_scan(const sensor_msgs::LaserScan::ConstPtr& msg) {
    pending_.push_back(msg);
    process_pending();
  }

  // a scan is matched once odometry has caught up with its stamp (messages of different
  // topics may arrive in either order)
  void process_pending() {
    while (!pending_.empty() && !odom_.empty() && pending_.front()->header.stamp.toSec() <= odom_.newest()) {
      const auto msg = pending_.front();
      pending_.pop_front();
      const auto X_OB = odom_.at(msg->header.stamp.toSec());
      const auto mount = mounts_.find(msg->header.frame_id);
      if (!X_OB) {
        ROS_WARN_THROTTLE(2.0, "slam_node: no odometry at the scan's stamp %.3f s; scan skipped", msg->header.stamp.toSec());
        continue;
      }
      if (mount == mounts_.end() || mount->second.parent != base_frame_) {
        ROS_WARN_THROTTLE(2.0, "slam_node: no %s -> %s on /tf_static yet; scan skipped", base_frame_.c_str(),
                          msg->header.frame_id.c_str());
        continue;
      }
      Scan scan;
      scan.stamp = msg->header.stamp.toSec();
      scan.angle_min = msg->angle_min;
      scan.angle_max = msg->angle_min + msg->angle_increment * (static_cast<double>(msg->ranges.size()) - 1);
      scan.range_min = msg->range_min;
      scan.range_max = msg->range_max;
      scan.ranges = msg->ranges;
      scan.X_BL = mount->second.X_PC;
      scan.mount_z = mount->second.z;
      const Pose2 X_MB = slam_.add_scan(scan, *X_OB);
      publish_map_to_odom(msg->header.stamp, compose(X_MB, inverse(*X_OB)));
    }
  }

  void publish_map_to_odom(const ros::Time& stamp, const Pose2& X_MO) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id = map_frame_;
    t.child_frame_id = odom_frame_;
    t.transform.translation.x = X_MO.x;
    t.transform.translation.y = X_MO.y;
    t.transform.rotation = quaternion_of(X_MO.yaw);
    tf2_msgs::TFMessage msg;
    msg.transforms.push_back(t);
    tf_pub_.publish(msg);
  }

  void publish_map() {
    if (slam_.scans() == 0) return;
    const Grid g = slam_.grid();
    nav_msgs::OccupancyGrid msg;
    msg.header.stamp = ros::Time::now();
    msg.header.frame_id = map_frame_;
    msg.info.map_load_time = msg.header.stamp;
    msg.info.resolution = static_cast<float>(g.resolution);
    msg.info.width = static_cast<std::uint32_t>(g.width);
    msg.info.height = static_cast<std::uint32_t>(g.height);
    msg.info.origin.position.x = g.origin_x;
    msg.info.origin.position.y = g.origin_y;
    msg.info.origin.orientation.w = 1;
    msg.data = g.cells;
    map_pub_.publish(msg);
  }

  IcpSlam slam_;
  PoseBuffer odom_;
  std::deque<sensor_msgs::LaserScan::ConstPtr> pending_;
  std::map<std::string, Mount> mounts_;
  std::string map_frame_, odom_frame_, base_frame_;
  double map_period_ = 1.0;
  ros::Publisher map_pub_, tf_pub_;
  ros::Subscriber scan_sub_, odom_sub_, tf_static_sub_;
  ros::Timer map_timer_;
};

}  // namespace
}  // namespace slam_demo

int main(int argc, char** argv) {
  ros::init(argc, argv, "slam_node");
  ros::NodeHandle nh, pnh("~");
  slam_demo::IcpSlamOptions o;
  pnh.param("resolution", o.resolution, o.resolution);
  pnh.param("insert_distance", o.insert_distance, o.insert_distance);
  pnh.param("insert_angle", o.insert_angle, o.insert_angle);
  pnh.param("max_insert_range", o.max_insert_range, o.max_insert_range);
  pnh.param("min_goodness", o.min_goodness, o.min_goodness);
  pnh.param("icp_iterations", o.icp_iterations, o.icp_iterations);
  if (!(o.resolution > 0) || !(o.insert_distance >= 0) || !(o.insert_angle >= 0) || !(o.max_insert_range > 0) ||
      o.icp_iterations < 1) {
    ROS_FATAL("slam_node: bad parameter: ~resolution and ~max_insert_range must be > 0, ~insert_distance and "
              "~insert_angle >= 0, ~icp_iterations >= 1");
    return 2;
  }
  slam_demo::SlamNode node(nh, pnh, o);
  ros::spin();
  node.finish();
  return 0;
}
