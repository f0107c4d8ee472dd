#pragma once
/// Traversal costs for a disc-shaped robot over a window of an occupancy grid: cells nearer
/// an obstacle than the robot's radius are lethal, cells nearer than a comfort distance cost
/// more, so that planned paths keep to the middle of corridors.

#include <limits>
#include <vector>

#include "autonomy/occupancy_grid.h"

namespace rescuesim::autonomy {

/// How occupancy turns into cost.
struct CostMapConfig {
  double robot_radius = 0.35;      ///< m; cells whose centre is nearer an occupied cell's edge are lethal
  double comfort_distance = 0.75;  ///< m; nearer than this to an obstacle costs extra
  double clearance_weight = 3.0;   ///< extra cost factor at robot_radius, falling linearly to 0 at comfort_distance
  bool unknown_traversable = true; ///< may paths cross cells never observed?
  double unknown_cost = 2.0;       ///< cost factor of an unknown cell when traversable (>= 1)
  /// Discs (centres in the grid's frame, m) kept clear like occupied ground: other robots,
  /// which the map does not hold (a laser above their bodies sees only their masts).
  std::vector<Vec2> keep_out;
  double keep_out_radius = 0.3;    ///< m, the discs' radius
};

/// Cost factors (per metre travelled, >= 1, or lethal) of the cells in a rectangular window
/// of an OccupancyMapper, from an exact Euclidean distance transform of its occupied cells.
class CostMap {
 public:
  /// A lethal cell: never entered.
  static constexpr float kLethal = std::numeric_limits<float>::infinity();

  /// Costs of the cells in the box [lo, hi] (inclusive, clamped to the grid). Occupied cells
  /// outside the box are not seen, so callers pad the box by the comfort distance.
  CostMap(const OccupancyMapper& grid, const CostMapConfig& config, Cell lo, Cell hi);

  /// True for cells inside the window.
  bool in_window(Cell c) const { return c.x >= lo_.x && c.y >= lo_.y && c.x <= hi_.x && c.y <= hi_.y; }
  /// Cost factor of a cell in the window: >= 1 per metre, or kLethal.
  float factor(Cell c) const { return factor_[local(c)]; }
  /// Distance (m) from the cell's centre to the nearest occupied cell centre in the window,
  /// +inf when there is none.
  double clearance(Cell c) const { return clearance_[local(c)]; }
  Cell lo() const { return lo_; }  ///< window's lower-left cell
  Cell hi() const { return hi_; }  ///< window's upper-right cell (inclusive)
  /// Row-major index of a window cell within the window.
  int local(Cell c) const { return (c.y - lo_.y) * width_ + (c.x - lo_.x); }
  /// The window cell at a local index.
  Cell cell_at(int i) const { return {lo_.x + i % width_, lo_.y + i / width_}; }
  int size() const { return static_cast<int>(factor_.size()); }  ///< cells in the window

 private:
  Cell lo_, hi_;
  int width_ = 0;
  std::vector<float> factor_;
  std::vector<float> clearance_;
};

}  // namespace rescuesim::autonomy
