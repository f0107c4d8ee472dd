#include "icp_slam.h"

#include <cmath>

#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPose3DPDF.h>
#include <mrpt/slam/CMetricMapBuilderICP.h>

namespace slam_demo {

struct IcpSlam::Impl {
  mrpt::slam::CMetricMapBuilderICP builder;
  bool have_last = false;
  Pose2 last_X_OB;  ///< odometry at the previous scan
};

IcpSlam::IcpSlam(const IcpSlamOptions& o) : impl_(std::make_unique<Impl>()) {
  auto& b = impl_->builder;
  b.setMinLoggingLevel(mrpt::system::LVL_WARN);

  // when to insert a scan into the maps, and when to trust a match
  b.ICP_options.matchAgainstTheGrid = false;  // the points map: slower than the grid, more precise
  b.ICP_options.insertionLinDistance = o.insert_distance;
  b.ICP_options.insertionAngDistance = o.insert_angle;
  b.ICP_options.localizationLinDistance = 0.0;  // match every scan
  b.ICP_options.localizationAngDistance = 0.0;
  b.ICP_options.minICPgoodnessToAccept = o.min_goodness;

  // the ICP itself: coarse-to-fine correspondence thresholds
  b.ICP_params.maxIterations = static_cast<unsigned>(o.icp_iterations);
  b.ICP_params.thresholdDist = 0.6;
  b.ICP_params.thresholdAng = 0.15 * M_PI / 180;
  b.ICP_params.ALFA = 0.5;
  b.ICP_params.smallestThresholdDist = 0.05;
  b.ICP_params.skip_cov_calculation = true;

  // the maps: points (what scans are matched against) and an occupancy grid (what is published)
  mrpt::maps::CSimplePointsMap::TMapDefinition points;
  points.insertionOpts.minDistBetweenLaserPoints = 0.03f;
  points.insertionOpts.isPlanarMap = true;
  points.insertionOpts.fuseWithExisting = false;
  b.ICP_options.mapInitializers.push_back(points);

  mrpt::maps::COccupancyGridMap2D::TMapDefinition grid;
  grid.min_x = -10;
  grid.max_x = 10;
  grid.min_y = -10;
  grid.max_y = 10;
  grid.resolution = static_cast<float>(o.resolution);
  grid.insertionOpts.maxDistanceInsertion = static_cast<float>(o.max_insert_range);
  grid.insertionOpts.maxOccupancyUpdateCertainty = 0.65f;
  grid.insertionOpts.considerInvalidRangesAsFreeSpace = false;
  b.ICP_options.mapInitializers.push_back(grid);

  b.initialize();
}

IcpSlam::~IcpSlam() = default;

Pose2 IcpSlam::add_scan(const Scan& scan, const Pose2& X_OB) {
  auto& I = *impl_;

  // the scan as MRPT wants it: symmetric about the sensor's x axis, counter-clockwise; a ROS
  // scan that is not symmetric has its middle folded into the sensor's heading
  auto obs = mrpt::obs::CObservation2DRangeScan::Create();
  obs->timestamp = mrpt::Clock::fromDouble(scan.stamp);
  obs->sensorLabel = "laser";
  obs->aperture = static_cast<float>(scan.angle_max - scan.angle_min);
  obs->rightToLeft = true;
  obs->maxRange = static_cast<float>(scan.range_max);
  obs->stdError = 0.01f;
  const double mid = 0.5 * (scan.angle_min + scan.angle_max);
  obs->sensorPose = mrpt::poses::CPose3D(scan.X_BL.x, scan.X_BL.y, scan.mount_z, wrap_angle(scan.X_BL.yaw + mid), 0, 0);
  obs->resizeScan(scan.ranges.size());
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const float r = scan.ranges[i];
    const bool valid = std::isfinite(r) && r >= scan.range_min && r < scan.range_max;
    obs->setScanRange(i, valid ? r : static_cast<float>(scan.range_max));
    obs->setScanRangeValidity(i, valid);
  }

  // the odometry increment since the previous scan is ICP's starting guess
  const Pose2 d = I.have_last ? compose(inverse(I.last_X_OB), X_OB) : Pose2{};
  I.last_X_OB = X_OB;
  I.have_last = true;
  mrpt::obs::CActionRobotMovement2D move;
  mrpt::obs::CActionRobotMovement2D::TMotionModelOptions model;
  model.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
  move.computeFromOdometry(mrpt::poses::CPose2D(d.x, d.y, d.yaw), model);
  move.timestamp = obs->timestamp;
  mrpt::obs::CActionCollection actions;
  actions.insert(move);
  mrpt::obs::CSensoryFrame frame;
  frame.insert(obs);
  I.builder.processActionObservation(actions, frame);
  ++scans_;

  mrpt::poses::CPose3D X_MB;
  I.builder.getCurrentPoseEstimation()->getMean(X_MB);
  return {X_MB.x(), X_MB.y(), X_MB.yaw()};
}

Grid IcpSlam::grid() const {
  Grid g;
  const auto* maps = impl_->builder.getCurrentlyBuiltMetricMap();
  const auto occ = maps->mapByClass<mrpt::maps::COccupancyGridMap2D>();
  if (!occ) return g;
  g.width = static_cast<int>(occ->getSizeX());
  g.height = static_cast<int>(occ->getSizeY());
  g.resolution = occ->getResolution();
  g.origin_x = occ->getXMin();
  g.origin_y = occ->getYMin();
  g.cells.resize(static_cast<std::size_t>(g.width) * g.height);
  // MRPT stores the probability of "free"; ROS wants percent occupied, -1 where nothing was seen
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const float p_free = occ->getCell(x, y);
      std::int8_t v = -1;
      if (std::fabs(p_free - 0.5f) > 0.01f) v = static_cast<std::int8_t>(std::lround(100.0 * (1.0 - p_free)));
      g.cells[static_cast<std::size_t>(y) * g.width + x] = v;
    }
  return g;
}

}  // namespace slam_demo
