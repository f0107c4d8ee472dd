// slam_recorder: what a run of the SLAM demonstration leaves behind, written when sim time
// reaches ~duration (or at Ctrl-C): the last /map as map.pgm + map.yaml (map_server's format,
// as `rosrun map_server map_saver` writes it) and trajectory.csv, which pairs each
// /ground_truth/pose sample with the SLAM estimate of the same instant, map -> base_link =
// (map -> odom, the newest one published at or before it on /tf) * (odom -> base_link from
// /odom, interpolated), and with the odometry alone. slam_eval scores these files.
//
// Parameters: ~out (folder, created if needed), ~duration (sim s; 0: until shutdown),
// ~map_frame (map), ~odom_frame (odom).

#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>

#include "pose_buffer.h"

namespace {

using slam_demo::Pose2;

// writes through a temporary file renamed into place, so a half-written file never looks complete
bool write_atomically(const std::string& path, const std::string& bytes) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!f.flush()) {
      ROS_ERROR("slam_recorder: cannot write %s", tmp.c_str());
      return false;
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    ROS_ERROR("slam_recorder: cannot rename %s to %s", tmp.c_str(), path.c_str());
    return false;
  }
  return true;
}

// map_saver's rules: occupied (>= 65 %) black, free (<= 25 %) white, the rest and unknown grey;
// the image's first row is the map's northern edge
bool save_map(const nav_msgs::OccupancyGrid& map, const std::string& dir) {
  const unsigned w = map.info.width, h = map.info.height;
  std::string pgm = "P5\n# CREATOR: slam_recorder " + std::to_string(map.info.resolution) + " m/pix\n" +
                    std::to_string(w) + " " + std::to_string(h) + "\n255\n";
  for (unsigned row = 0; row < h; ++row)
    for (unsigned x = 0; x < w; ++x) {
      const int v = map.data[static_cast<std::size_t>(h - 1 - row) * w + x];
      pgm += static_cast<char>(v >= 65 ? 0 : (v >= 0 && v <= 25) ? 254 : 205);
    }
  const auto& o = map.info.origin.position;
  char yaml[512];
  std::snprintf(yaml, sizeof yaml,
                "image: map.pgm\nresolution: %.6f\norigin: [%.6f, %.6f, %.6f]\nnegate: 0\noccupied_thresh: 0.65\n"
                "free_thresh: 0.196\n",
                map.info.resolution, o.x, o.y, slam_demo::yaw_of(map.info.origin.orientation));
  return write_atomically(dir + "/map.pgm", pgm) && write_atomically(dir + "/map.yaml", yaml);
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "slam_recorder");
  ros::NodeHandle nh, pnh("~");
  std::string out, map_frame, odom_frame;
  double duration;
  pnh.param<std::string>("out", out, "");
  pnh.param("duration", duration, 0.0);
  pnh.param<std::string>("map_frame", map_frame, "map");
  pnh.param<std::string>("odom_frame", odom_frame, "odom");
  if (out.empty() || !(duration >= 0)) {
    ROS_FATAL("slam_recorder: set ~out to a folder and ~duration to sim seconds >= 0 (0: until shutdown)");
    return 2;
  }
  ::mkdir(out.c_str(), 0777);

  // everything is kept for the whole run (50 Hz x a few minutes is small)
  slam_demo::PoseBuffer odom(1e12), map_to_odom(1e12);
  std::vector<std::pair<double, Pose2>> truth;
  nav_msgs::OccupancyGrid::ConstPtr map;
  auto s1 = nh.subscribe<nav_msgs::Odometry>("odom", 1000, [&](const nav_msgs::Odometry::ConstPtr& m) {
    const auto& p = m->pose.pose;
    odom.add(m->header.stamp.toSec(), {p.position.x, p.position.y, slam_demo::yaw_of(p.orientation)});
  });
  auto s2 = nh.subscribe<geometry_msgs::PoseStamped>("ground_truth/pose", 1000,
                                                     [&](const geometry_msgs::PoseStamped::ConstPtr& m) {
    const auto& p = m->pose;
    truth.emplace_back(m->header.stamp.toSec(), Pose2{p.position.x, p.position.y, slam_demo::yaw_of(p.orientation)});
  });
  auto s3 = nh.subscribe<tf2_msgs::TFMessage>("tf", 1000, [&](const tf2_msgs::TFMessage::ConstPtr& m) {
    for (const auto& t : m->transforms)
      if (t.header.frame_id == map_frame && t.child_frame_id == odom_frame)
        map_to_odom.add(t.header.stamp.toSec(), {t.transform.translation.x, t.transform.translation.y,
                                                 slam_demo::yaw_of(t.transform.rotation)});
  });
  auto s4 = nh.subscribe<nav_msgs::OccupancyGrid>("map", 2, [&](const nav_msgs::OccupancyGrid::ConstPtr& m) { map = m; });

  ROS_INFO("slam_recorder: recording into %s until sim time %.1f s", out.c_str(), duration);
  ros::WallRate rate(50.0);
  double last_report = 0;
  while (ros::ok()) {
    ros::spinOnce();
    const double now = ros::Time::now().toSec();
    if (duration > 0 && now >= duration) break;
    if (now >= last_report + 10) {
      last_report = now;
      const double lag = map_to_odom.empty() ? -1 : now - map_to_odom.newest();
      ROS_INFO("slam_recorder: t = %.0f s, %zu truth samples, map %s, SLAM pose %s (%.2f s behind)", now, truth.size(),
               map ? "received" : "not yet", map_to_odom.empty() ? "not yet" : "tracking", lag);
    }
    rate.sleep();
  }
  ros::spinOnce();

  // the trajectory: truth, odometry and SLAM at each truth sample
  std::string csv = "t,gt_x,gt_y,gt_yaw,odom_x,odom_y,odom_yaw,slam_x,slam_y,slam_yaw\n";
  int rows = 0;
  for (const auto& [t, gt] : truth) {
    const auto X_OB = odom.at(t);
    if (!X_OB) continue;
    const auto X_MO = map_to_odom.latest_at(t);
    char line[256];
    if (X_MO) {
      const Pose2 X_MB = slam_demo::compose(*X_MO, *X_OB);
      std::snprintf(line, sizeof line, "%.3f,%.4f,%.4f,%.5f,%.4f,%.4f,%.5f,%.4f,%.4f,%.5f\n", t, gt.x, gt.y, gt.yaw,
                    X_OB->x, X_OB->y, X_OB->yaw, X_MB.x, X_MB.y, X_MB.yaw);
    } else {
      std::snprintf(line, sizeof line, "%.3f,%.4f,%.4f,%.5f,%.4f,%.4f,%.5f,,,\n", t, gt.x, gt.y, gt.yaw, X_OB->x,
                    X_OB->y, X_OB->yaw);
    }
    csv += line;
    ++rows;
  }
  bool ok = write_atomically(out + "/trajectory.csv", csv);
  if (!map) {
    ROS_ERROR("slam_recorder: no /map was received: is slam_node running?");
    return 1;
  }
  ok = save_map(*map, out) && ok;
  ROS_INFO("slam_recorder: wrote %s/{map.pgm, map.yaml, trajectory.csv} (%d poses, map %ux%u at %.3f m)", out.c_str(),
           rows, map->info.width, map->info.height, map->info.resolution);
  return ok ? 0 : 1;
}
