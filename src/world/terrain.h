#pragma once
/// The solids of a generated terrain element (TerrainSpec): stepfield posts, stairs, crossing
/// ramps, curbs, hurdles and gaps, at the standard dimensions by default (docs/terrain.md).

#include <string>
#include <vector>

#include "world/world_spec.h"

namespace rescuesim {

/// One solid of a terrain element, in the world.
struct TerrainSolid {
  std::string name;   ///< "<element>_post_12", "<element>_step_2", ...
  Geometry geometry;  ///< a box, or a convex wedge (ramps)
  Pose3 X_WS;
  bool ramp = false;  ///< an inclined surface (a wedge), else a flat-topped solid
};

/// The solids of `t`. Throws Error (naming the element) when it cannot be built: a stepfield
/// smaller than one post, stairs too steep or too long for the footprint, a gap wider than its
/// footprint allows, non-positive or non-finite sizes.
std::vector<TerrainSolid> terrain_solids(const TerrainSpec& t);

/// The post heights of a stepfield, row by row across travel (nx along x, ny across): seeded,
/// each a whole number (1-4) of units, the unit a post (full-cubic) or half a post (half-cubic).
/// The generator is SplitMix64 on `seed`, the same on every platform.
std::vector<double> stepfield_heights(const TerrainSpec& t, int nx, int ny);

/// A test-method arena: lanes side by side, west to east, each with one element across its
/// middle (the kind's defaults, `lane_width - 0.1` wide), walls between the lanes, an open
/// approach of `approach` metres at each end, and the robot's start in `start_lane`'s south end,
/// facing north. Every lane runs south to north.
struct ArenaOptions {
  std::vector<TerrainSpec::Kind> lanes;
  double lane_width = 1.2;     ///< m; RoboCup's lanes are 1.1-1.2 m
  double approach = 1.5;       ///< m of flat floor before and after each element
  double wall_height = 1.0;    ///< m
  int start_lane = 0;
  std::uint64_t seed = 1;      ///< the stepfields' seeds are seed, seed + 1, ... in lane order
  /// Figure-8 apparatus instead of lanes: each element at the test methods' figure-8 size,
  /// kFigureEightWidth x kFigureEightLength, for figure-eights around two pylons (stepfields and
  /// crossing ramps only; lanes at least kFigureEightLaneWidth wide).
  bool figure_eight = false;
};

/// The test methods' figure-8 terrain: 2.4 m wide (two 1.2 m panels), 4.8 m long.
inline constexpr double kFigureEightWidth = 2.4;
inline constexpr double kFigureEightLength = 4.8;
/// The narrowest lane a figure-8 element fits in (the lanes' 0.1 m margin), and the figure-8
/// arena's default lane width.
inline constexpr double kFigureEightLaneWidth = kFigureEightWidth + 0.1;

/// Whether the test methods drive figure-eights on this kind (stepfields and crossing ramps).
inline bool is_figure_eight_kind(TerrainSpec::Kind k) {
  return k == TerrainSpec::Kind::stepfield || k == TerrainSpec::Kind::crossing_ramps;
}

/// The arena as a WorldSpec (in the SVG convention, ready for world_to_svg). Its metadata records
/// each lane's kind and its start and end lines (the element's near and far edges). Throws Error
/// for no lanes, a start lane that does not exist, a lane too narrow for its element, or a
/// figure-8 arena with a kind that is not driven in figure-eights.
WorldSpec test_method_arena(const ArenaOptions& options);

/// The terrain kind called `name` ("stepfield", "crossing-ramps", ...); throws Error naming the
/// known kinds otherwise.
TerrainSpec::Kind terrain_kind_from_name(const std::string& name);

}  // namespace rescuesim
