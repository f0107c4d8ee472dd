#pragma once
/// Random mazes by a modified Prim's algorithm, with loops, rubble, raised areas and victims,
/// as in the jmeSim paper's batch world generation. A `Maze` is the grid; `maze_to_world`
/// turns it into a WorldSpec (walls, features, robot start) that the SVG writer can save.
/// Same options (including seed) → same maze on every machine: all randomness comes from
/// `Rng` streams derived from the seed.

#include <array>
#include <cstdint>
#include <vector>

#include "world/world_spec.h"

namespace rescuesim {

/// What to generate. Cells are indexed (col, row) from the south-west corner, col east, row north.
struct MazeOptions {
  int cols = 8;                      ///< cells east-west, >= 1
  int rows = 8;                      ///< cells north-south, >= 1
  double cell_size = 1.5;            ///< m, centre-to-centre of walls
  double wall_thickness = 0.05;      ///< m
  double wall_height = 1.0;          ///< m
  double loop_fraction = 0.0;        ///< fraction of the interior walls left after Prim's that are removed (0 = perfect maze)
  int rubble = 0;                    ///< loose boxes and cylinders to scatter
  double raised_fraction = 0.0;      ///< fraction of cells that get a raised platform with ramps on their open sides
  double raised_height = 0.10;       ///< m
  double ramp_length = 0.40;         ///< m
  int victims = 0;                   ///< victims to place, dead ends first
  /// Fraction of cells that get a test-method terrain element across their interior (never a
  /// start, raised or victim cell), of the kinds in `terrain` taken in turn: a half-cubic
  /// stepfield, a curb or a hurdle (docs/terrain.md). Rubble keeps out of them.
  double terrain_fraction = 0.0;
  std::vector<TerrainSpec::Kind> terrain{TerrainSpec::Kind::stepfield};
  std::array<int, 2> start_cell{0, 0};  ///< (col, row) where the robot starts
  /// Cells where further robots start ("robot2", "robot3", ... in this order), each kept free
  /// of platforms, victims and rubble like start_cell; distinct from it and each other.
  std::vector<std::array<int, 2>> more_start_cells;
  std::uint64_t seed = 1;            ///< everything random derives from this
};

/// Sides of a cell.
enum class Side : std::uint8_t { east = 0, north = 1, west = 2, south = 3 };

/// The generated grid and where features go.
struct Maze {
  MazeOptions options;
  /// Passage flags: open_east[i] is the opening between cell i and its east neighbour, open_north[i]
  /// between cell i and its north neighbour; i = row * cols + col. Outer boundary always closed.
  std::vector<std::uint8_t> open_east, open_north;
  std::vector<std::array<int, 2>> victim_cells;  ///< cell of each victim
  std::vector<Side> victim_sides;                ///< closed side each victim lies against
  std::vector<std::array<int, 2>> raised_cells;  ///< cells with a raised platform
  std::vector<std::array<int, 2>> terrain_cells; ///< cells with a terrain element (MazeOptions::terrain_fraction), in cell order

  int cell_count() const { return options.cols * options.rows; }
  int index(int col, int row) const { return row * options.cols + col; }
  /// True when there is a passage from (col, row) through `side` (false at the boundary).
  bool is_open(int col, int row, Side side) const;
  /// Number of passages between cells (a perfect maze has cell_count() - 1).
  int opening_count() const;
  /// Passages out of one cell (1 = dead end).
  int degree(int col, int row) const;
  /// Cells reachable from `from` through passages, as a flag per cell index.
  std::vector<std::uint8_t> reachable_from(std::array<int, 2> from) const;
};

/// Generates a maze; throws `Error` naming the option when the options are impossible
/// (non-positive size, start cell outside the grid, fractions outside [0, 1], ...).
Maze generate_maze(const MazeOptions& options);

/// The world of a maze: floor, outer and inner walls (collinear runs merged into single
/// walls), raised platforms with ramps on their open sides, rubble near walls, victims lying
/// against a closed side of their cell, and one robot `robot` at the start cell's centre
/// facing an open side. `world.seed` and `world.metadata` record the options.
WorldSpec maze_to_world(const Maze& maze);

}  // namespace rescuesim
