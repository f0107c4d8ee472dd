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

}  // namespace rescuesim
