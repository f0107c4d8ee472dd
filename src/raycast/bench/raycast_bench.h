#pragma once
/// Ray throughput of RayScene beside bare Embree on the same triangles, measured in one run
/// (for `rescuesim bench`, which reports each figure beside its baseline).

#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// Rays per second on one thread.
struct RayBenchResult {
  double bare_rays_per_s = 0;   ///< bare Embree rtcIntersect16 on the world's triangles, flattened
  double scene_rays_per_s = 0;  ///< RayScene::cast on the same rays
};

/// Casts `rays` horizontal rays fanned evenly over 360° from `origin` (world frame, m), over and
/// over for about `seconds` in all, alternating between bare Embree and RayScene; both on one
/// thread. Rubble is included at its initial pose; robots are left out of both. With `state`
/// (a run's start, say), RayScene is updated with its rubble first, so rubble asleep there is
/// traced as a run traces it (in the flat geometry, see RayScene).
RayBenchResult measure_ray_throughput(const World& world, const Vec3& origin, int rays, double seconds, const State* state = nullptr);

}  // namespace rescuesim
