#pragma once
/// Grid path planning on an occupancy map: A* to a goal and Dijkstra to the nearest
/// reachable frontier (the edge between known free space and the unknown). Both search
/// 8-connected cells with costs from a CostMap and break ties by (f, h, cell index), so the
/// same map and query always give the same path.

#include <functional>
#include <vector>

#include "autonomy/cost_map.h"
#include "autonomy/occupancy_grid.h"

namespace rescuesim::autonomy {

/// Settings of the planner.
struct PlannerConfig {
  /// Costs for goal planning; frontier search never crosses unknown cells whatever
  /// `unknown_traversable` says.
  CostMapConfig cost;
  int min_frontier_cells = 12;       ///< a frontier cluster (8-connected) needs this many cells
  double min_frontier_distance = 0.5;  ///< m; frontier cells nearer the start are skipped
  double excluded_radius = 1.0;      ///< m; frontier cells this near an excluded point are skipped
  double claimed_radius = 3.0;       ///< m; frontier cells this near a point teammates claimed are skipped
  /// m; when the start lies in lethal space (robot pressed against a wall), lethal but
  /// unoccupied cells this near the start may be crossed to get out.
  double escape_radius = 0.5;
};

/// A* / Dijkstra planner over an OccupancyMapper.
class AStarPlanner {
 public:
  explicit AStarPlanner(PlannerConfig config = {});

  /// The cheapest path from `start_O` to `goal_O` (m, odom frame) as cell centres from the
  /// start's cell to the goal's, with collinear interior points removed; empty when either
  /// end is off the grid, the goal is lethal or no path exists. The search is limited to the
  /// observed part of the map (plus the goal) padded by the comfort distance.
  std::vector<Vec2> plan(const OccupancyMapper& grid, const Vec2& start_O, const Vec2& goal_O);

  /// The path (as `plan`) to the nearest frontier cell, by path cost through known free
  /// space, whose 8-connected frontier cluster has at least `min_frontier_cells` cells;
  /// frontier cells within `excluded_radius` of any point of `excluded_O` (m, odom frame),
  /// or within `claimed_radius` of any point of `claimed_O` (where teammates are and are
  /// going), are ignored. Empty when no such frontier is reachable.
  std::vector<Vec2> plan_to_nearest_frontier(const OccupancyMapper& grid, const Vec2& start_O,
                                             const std::vector<Vec2>& excluded_O = {}, const std::vector<Vec2>& claimed_O = {});

  /// The same search for any kind of target: the nearest cell for which `is_target` holds,
  /// whose 8-connected cluster of target cells has at least `min_cells(cell)` cells (asked of
  /// the first cell of each cluster reached). plan_to_nearest_frontier is this with is_frontier
  /// and min_frontier_cells; the explorer adds ground its camera has not looked at.
  std::vector<Vec2> plan_to_nearest_target(const OccupancyMapper& grid, const Vec2& start_O,
                                           const std::function<bool(Cell)>& is_target,
                                           const std::function<int(Cell)>& min_cells,
                                           const std::vector<Vec2>& excluded_O = {}, const std::vector<Vec2>& claimed_O = {});

  /// Cells expanded by the last search (a cost measure for tests and benches).
  int last_expansions() const { return expansions_; }
  const PlannerConfig& config() const { return config_; }  ///< its settings
  /// Discs every later search keeps clear as if occupied (CostMapConfig::keep_out): where
  /// other robots stand, in the grid's frame. Replaces the previous set.
  void set_keep_out(std::vector<Vec2> centres, double radius) {
    config_.cost.keep_out = std::move(centres);
    config_.cost.keep_out_radius = radius;
  }

 private:
  PlannerConfig config_;
  int expansions_ = 0;
};

/// True for a free cell with at least one unknown 8-neighbour inside the grid.
bool is_frontier(const OccupancyMapper& grid, Cell c);

/// Total length (m) of a polyline.
double path_length(const std::vector<Vec2>& path);

/// True when an occupied cell lies within `clearance` (m) of the polyline's part from
/// `from_O` onwards: the segment from `from_O` to `path[first]`, then the rest of the path.
bool path_blocked(const OccupancyMapper& grid, const std::vector<Vec2>& path, std::size_t first, const Vec2& from_O,
                  double clearance);

}  // namespace rescuesim::autonomy
