// measure_ray_throughput as a function (speed itself is for bench/, not tests): it measures
// both sides, and leaves the thread limit as it found it.

#include "raycast/bench/raycast_bench.h"

#include <gtest/gtest.h>

#include "core/parallel.h"

namespace rescuesim {
namespace {

TEST(RayThroughput, MeasuresBothAndRestoresTheThreadLimit) {
  WorldSpec spec;
  spec.name = "bench_test";
  spec.materials = default_materials();
  spec.walls.push_back(WallSpec{{5, 0}, {5, 10}, 0.1, 1.0, "wall", {}});
  spec.walls.push_back(WallSpec{{0, 5}, {10, 5}, 0.1, 1.0, "wall", {}});
  const World world = compile_world(spec, {});
  set_worker_threads(0);
  const RayBenchResult r = measure_ray_throughput(world, Vec3(2, 2, 0.3), 100, 0.02);
  EXPECT_GT(r.bare_rays_per_s, 0);
  EXPECT_GT(r.scene_rays_per_s, 0);
  EXPECT_EQ(worker_threads(), 0);
}

}  // namespace
}  // namespace rescuesim
