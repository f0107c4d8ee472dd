#pragma once
/// Laser range finders: planar scans (LaserScan) and multi-layer point clouds (PointCloud2),
/// cast through the RayScene from the sensor's mount on a robot link. Ranges follow REP-117.

#include "core/rng.h"
#include "core/sim_time.h"
#include "msgs/messages.h"
#include "raycast/ray_scene.h"
#include "world/sensor_spec.h"
#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// The pose of a sensor in the world: X_WS = State::robots[robot].X_WL[mount link] * spec.X_LS.
/// Throws Error naming the sensor when its link is not one of the robot's.
Pose3 sensor_pose_in_world(const World& world, const State& state, RobotIndex robot, const SensorSpec& spec);

/// One range reading per REP-117 from a true distance (m; +inf = no return, NaN = invalid ray):
/// below min_range → -inf; no return → +inf; NaN stays NaN; otherwise distance + bias +
/// N(0, stddev²) clamped into [min_range, max_range] (a noisy value never leaves the range).
/// Draws from `rng` only for in-range returns with stddev > 0.
float range_reading(float distance, double min_range, double max_range, const NoiseSpec& noise, Rng& rng);

/// A planar scan in the sensor's x–y plane: beam i at angle min_angle + i·increment,
/// counter-clockwise about the sensor z, increment = (max_angle − min_angle)/(samples − 1).
/// Every beam is taken at `stamp` (time_increment 0). The robot never sees its own links.
/// For a multi-layer lidar this is the ring at elevation 0; the layers are sample_lidar_cloud's.
msg::LaserScan sample_lidar(const World& world, const State& state, const RayScene& scene, RobotIndex robot, const SensorSpec& spec,
                            SimTime stamp, Rng& rng);

/// A multi-layer scan as a point cloud: spec.lidar.layers rings spread evenly over
/// vertical_fov (centred on elevation 0; one ring at 0 when layers == 1), each with the
/// planar beams of sample_lidar. Points are x, y, z float32 in the sensor frame
/// (header.frame_id), ring by ring, for returns within [min_range, max_range] only; height 1,
/// is_dense true.
msg::PointCloud2 sample_lidar_cloud(const World& world, const State& state, const RayScene& scene, RobotIndex robot, const SensorSpec& spec,
                                    SimTime stamp, Rng& rng);

}  // namespace rescuesim
