#pragma once
/// A place on the floor where a robot fits, found by looking down at the world: every ray cast
/// straight down over a square around the spot, from 3 m, must reach the floor (z = 0) without
/// touching anything else (walls, rubble, victims, raised areas, robots). Where tests and the
/// bench spawn robots into a world they did not draw.

#include <optional>
#include <vector>

#include "raycast/ray_scene.h"
#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// The first free spot on a `step` grid over the floor (row by row from its south-west corner)
/// whose square of half-side `half` is clear, also at least `half` plus 0.3 m from each point
/// of `avoid`; nullopt when there is none.
inline std::optional<Vec2> free_spot(const World& world, const State& state, double half, const std::vector<Vec2>& avoid = {},
                                     double step = 0.25) {
  RayScene scene(world);
  scene.update(state);
  std::vector<Ray> rays;
  std::vector<RayHit> hits;
  for (double y = world.floor.min.y() + half; y <= world.floor.max.y() - half; y += step) {
    for (double x = world.floor.min.x() + half; x <= world.floor.max.x() - half; x += step) {
      const Vec2 c(x, y);
      bool near = false;
      for (const Vec2& a : avoid) near = near || (a - c).norm() < half + 0.3;
      if (near) continue;
      rays.clear();
      for (double dy = -half; dy <= half + 1e-9; dy += 0.1) {
        for (double dx = -half; dx <= half + 1e-9; dx += 0.1) rays.push_back({Vec3(x + dx, y + dy, 3.0), -Vec3::UnitZ(), 3.0f});
      }
      hits.assign(rays.size(), RayHit{});
      scene.cast(rays, hits);
      bool clear = true;
      for (const RayHit& h : hits) clear = clear && h.distance > 3.0f - 0.01f;  // the floor's top, or nothing
      if (clear) return c;
    }
  }
  return std::nullopt;
}

}  // namespace rescuesim
