#pragma once
/// Scoring a map against the simulator's ground truth: a SLAM run (slam_eval; docs/demos.md)
/// and a mission team's map on /rescue/map (Mission; docs/missions.md):
/// the true occupancy of a world rasterised from its WorldSpec, the occupied cells a laser could
/// have seen from the true trajectory, occupied-cell precision and recall of a SLAM map within a
/// tolerance, and the absolute trajectory error under a stated alignment. C++20, rescuesim's
/// own types; no ROS.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/pose.h"
#include "world/world_spec.h"

namespace rescuesim::map_eval {

/// A square-celled grid, axis-aligned in its frame. Cell (i, j) covers
/// [origin.x + i*res, origin.x + (i+1)*res) x [origin.y + j*res, ...); stored row-major from j = 0.
struct Grid {
  Vec2 origin = Vec2::Zero();  ///< south-west corner of cell (0, 0) (m)
  double resolution = 0.05;    ///< m
  int width = 0, height = 0;
  std::vector<std::uint8_t> cells;  ///< meaning depends on use: see the functions below

  bool inside(int i, int j) const { return i >= 0 && j >= 0 && i < width && j < height; }
  std::uint8_t at(int i, int j) const { return cells[static_cast<std::size_t>(j) * width + i]; }
  std::uint8_t& at(int i, int j) { return cells[static_cast<std::size_t>(j) * width + i]; }
  /// The cell containing p (may be outside the grid).
  void cell_of(const Vec2& p, int& i, int& j) const;
  /// Centre of cell (i, j) (m).
  Vec2 centre(int i, int j) const { return origin + Vec2((i + 0.5) * resolution, (j + 0.5) * resolution); }
};

/// Values of a SLAM map cell (map_server's three classes).
enum MapCell : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

/// A map read from map_server files: cells hold MapCell values, in the map's own frame.
struct SlamMap {
  Grid grid;
  std::filesystem::path yaml;  ///< where it came from
};

/// Reads map_server's map.yaml and the PGM it names (P5, 8 bit): occupied where the pixel's
/// occupancy (1 - v/255, or v/255 with negate) exceeds occupied_thresh, free below free_thresh.
/// Throws rescuesim::Error naming the file and what is wrong.
SlamMap read_map(const std::filesystem::path& yaml);

/// The world's true occupancy on a grid of the given resolution in the world frame covering
/// its floor: 1 where a wall, or an obstacle taller than `laser_height`, touches the cell.
/// Victims, raised areas and rubble are left out (the floor plan is what SLAM should map).
Grid true_occupancy(const WorldSpec& world, double resolution, double laser_height);

/// 1 on cells within `margin` (m) of a victim, else 0: neither counted for nor against a map
/// (a seated person is seen by the laser but is not part of the floor plan).
Grid ignore_mask(const WorldSpec& world, const Grid& like, double margin);

/// A planar laser for ray casting: beams from `min_angle` to `max_angle` (rad, in base_link),
/// mounted at `X_BL`, reaching `max_range` (m).
struct LaserModel {
  Pose2 X_BL{0.26, 0, 0};
  double min_angle = -3 * M_PI / 4, max_angle = 3 * M_PI / 4;
  int beams = 541;
  double max_range = 20.0;
};

/// 1 on each occupied cell of `truth` that some beam from some pose of `poses` (base_link in the
/// world) hits first: the surface the robot could have mapped.
Grid visible_surface(const Grid& truth, const std::vector<Pose2>& poses, const LaserModel& laser);
/// Adds to `seen` (a grid like `truth`) the occupied cells of `truth` the laser hits first from
/// base pose X_WB: visible_surface one pose at a time.
void add_visible(Grid& seen, const Grid& truth, const Pose2& X_WB, const LaserModel& laser);

/// Occupied-cell agreement of a SLAM map with the truth. X_WM places the map in the world.
struct MapScore {
  double precision = 0;         ///< map occupied cells within tolerance of a true occupied cell / all counted
  double recall = 0;            ///< visible true cells within tolerance of a map occupied cell / all visible
  long map_occupied = 0;        ///< map occupied cells counted (outside the ignore mask)
  long map_matched = 0;
  long map_ignored = 0;         ///< map occupied cells in the ignore mask
  long visible = 0;             ///< visible true surface cells
  long visible_matched = 0;
};

/// Scores `map` against `truth` (occupied = 1) and `visible` (the cells recall is counted over)
/// with a tolerance of `tolerance_cells` cells (Chebyshev distance on the truth grid).
MapScore score_map(const SlamMap& map, const Pose2& X_WM, const Grid& truth, const Grid& visible, const Grid& ignore,
                   int tolerance_cells = 1);
/// The same for a map grid of MapCell values.
MapScore score_map(const Grid& map, const Pose2& X_WM, const Grid& truth, const Grid& visible, const Grid& ignore,
                   int tolerance_cells = 1);

/// A nav_msgs/OccupancyGrid's cells as MapCell values (-1 unknown; 0 to free_max free; from
/// occupied_min occupied; between: unknown), in the grid's own frame (origin at 0; the caller
/// places it with info.origin). Throws rescuesim::Error for a grid that is not one: a
/// resolution that is not a positive finite number, data of another size than width × height.
Grid grid_from_occupancy(int width, int height, double resolution, const std::vector<std::int8_t>& data,
                         int free_max = 25, int occupied_min = 65);

/// How an estimated trajectory is put into the world frame before comparing.
enum class Alignment {
  start,         ///< the first estimated pose is placed on the first true pose (no fitting)
  least_squares  ///< the rigid 2-D transform minimising the squared position errors (Umeyama, no scale)
};

/// Absolute trajectory error: RMS of the position differences (m) between true and estimated
/// poses paired by index, after aligning the estimate; also returns the alignment X_WM used.
struct TrajectoryError {
  double rmse = 0, max = 0;
  Pose2 X_WM;
  std::size_t pairs = 0;
};
TrajectoryError trajectory_error(const std::vector<Pose2>& truth, const std::vector<Pose2>& estimate, Alignment alignment);

}  // namespace rescuesim::map_eval
