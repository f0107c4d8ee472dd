#pragma once
/// ICP scan-matching SLAM on MRPT (mrpt::slam::CMetricMapBuilderICP): each laser scan is
/// matched against the points map built so far, starting from the odometry's guess, and
/// inserted into a points map and an occupancy grid when the robot has moved far enough.
/// MRPT types stay in icp_slam.cpp; this interface speaks plain types only.

#include <cstdint>
#include <memory>
#include <vector>

#include "pose2.h"

namespace slam_demo {

/// One planar laser scan as the node received it (REP-117 ranges).
struct Scan {
  double stamp = 0;                 ///< s (sim time)
  double angle_min = 0, angle_max = 0;  ///< rad, first and last beam, counter-clockwise
  double range_max = 0;             ///< m; returns beyond it (and +inf, NaN) are "no echo"
  double range_min = 0;             ///< m
  std::vector<float> ranges;        ///< m, one per beam, evenly spaced from angle_min to angle_max
  Pose2 X_BL;                       ///< laser in base_link (the planar part of the mount)
  double mount_z = 0;               ///< laser height above base_link (m)
};

/// Settings of the ICP SLAM (the node's ROS parameters of the same names).
struct IcpSlamOptions {
  double resolution = 0.05;         ///< occupancy grid cell (m)
  double insert_distance = 0.4;     ///< insert a scan into the maps after this much travel (m)
  double insert_angle = 0.35;       ///< ... or this much turning (rad)
  double max_insert_range = 18.0;   ///< grid insertion: ignore returns beyond this (m)
  double min_goodness = 0.4;        ///< ICP goodness below which the match is rejected (odometry kept)
  int icp_iterations = 60;          ///< ICP iteration cap per scan
};

/// An occupancy grid in ROS's convention (row-major from the south-west cell; -1 unknown,
/// 0..100 occupancy probability in percent).
struct Grid {
  int width = 0, height = 0;
  double resolution = 0.05;         ///< m per cell
  double origin_x = 0, origin_y = 0;  ///< south-west corner of cell (0, 0) in the map frame (m)
  std::vector<std::int8_t> cells;
};

class IcpSlam {
 public:
  explicit IcpSlam(const IcpSlamOptions& options);
  ~IcpSlam();
  IcpSlam(const IcpSlam&) = delete;
  IcpSlam& operator=(const IcpSlam&) = delete;

  /// Processes a scan taken when the odometry read `X_OB` (base_link in odom); returns the
  /// estimated base_link pose in the map frame (the map frame is base_link at the first scan).
  Pose2 add_scan(const Scan& scan, const Pose2& X_OB);

  /// The occupancy grid built so far.
  Grid grid() const;

  /// Scans processed so far.
  int scans() const { return scans_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int scans_ = 0;
};

}  // namespace slam_demo
