#pragma once
/// The scale scenario (issue 17, `rescuesim bench --scale`): N rescue robots at distinct cells
/// of a maze of 20/12 m cells (12 x 12 cells over 20 m for up to 144 robots; beyond, the
/// smallest square maze of the same cells that has one for each), each with a 1081-beam 270°
/// 30 m lidar at 10 Hz besides its odometry, IMU and sonars, following walls. No victims, no
/// rubble, no raised areas: what it measures is robots, sensors and physics.

#include "import/scenario/scenario.h"

namespace rescuesim::bench {

/// The scale scenario's side in cells for `robots` robots: 12, or ceil(sqrt(robots)) above 144.
int scale_maze_cells(int robots);

/// The scale scenario for `robots` (1 ..= 10,000) robots, `duration` s of sim time, seed
/// `seed`; robots r1, r2, ... at cells spread evenly over the maze (row-major, cell
/// floor(k C² / N) for robot k). Throws rescuesim::Error for a count out of range.
Scenario scale_scenario(int robots, double duration, const ModelMap& models, std::uint64_t seed = 1);

}  // namespace rescuesim::bench
