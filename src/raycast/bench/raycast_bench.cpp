#include "raycast/bench/raycast_bench.h"

#include <chrono>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "raycast/embree_support.h"
#include "raycast/ray_scene.h"

namespace rescuesim {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Bare embree: the world's static and rubble triangles in one flat scene, traced with
/// rtcIntersect16 straight from float arrays.
class BareScene {
 public:
  explicit BareScene(const World& world) {
    raycast_detail::FloatMesh mesh = raycast_detail::static_triangles(world, nullptr);
    for (const DynamicObject& d : world.dynamics) mesh.append(mesh_of(d.geometry, raycast_detail::kRoundSegments), d.X_WO);
    scene_ = raycast_detail::new_mesh_scene(mesh, RTC_BUILD_QUALITY_HIGH);
  }
  ~BareScene() { rtcReleaseScene(scene_); }
  BareScene(const BareScene&) = delete;
  BareScene& operator=(const BareScene&) = delete;

  /// Traces every ray once; returns the number of hits (so the work cannot be skipped).
  int trace(const std::vector<Ray>& rays) const {
    int hit_count = 0;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // as RayScene traces
    alignas(64) int valid[16];
    alignas(64) RTCRayHit16 rh;
    for (std::size_t begin = 0; begin < rays.size(); begin += 16) {
      for (std::size_t i = 0; i < 16; ++i) {
        const std::size_t k = begin + i < rays.size() ? begin + i : begin;
        valid[i] = begin + i < rays.size() ? -1 : 0;
        rh.ray.org_x[i] = static_cast<float>(rays[k].origin.x());
        rh.ray.org_y[i] = static_cast<float>(rays[k].origin.y());
        rh.ray.org_z[i] = static_cast<float>(rays[k].origin.z());
        rh.ray.dir_x[i] = static_cast<float>(rays[k].direction.x());
        rh.ray.dir_y[i] = static_cast<float>(rays[k].direction.y());
        rh.ray.dir_z[i] = static_cast<float>(rays[k].direction.z());
        rh.ray.tnear[i] = 0.0f;
        rh.ray.tfar[i] = rays[k].max_distance;
        rh.ray.time[i] = 0.0f;
        rh.ray.mask[i] = 0xFFFFFFFFu;
        rh.ray.id[i] = static_cast<unsigned>(i);
        rh.ray.flags[i] = 0;
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect16(valid, scene_, &ctx, &rh);
      for (int i = 0; i < 16; ++i) hit_count += valid[i] && rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
    }
    return hit_count;
  }

 private:
  RTCScene scene_ = nullptr;
};

}  // namespace

RayBenchResult measure_ray_throughput(const World& world, const Vec3& origin, int rays, double seconds, const State* state) {
  RS_DEMAND(rays > 0, "measure_ray_throughput: rays must be positive");
  // the same world without robots for both, so both see exactly the same triangles
  World bare_world = world;
  bare_world.robots.clear();
  const BareScene bare(bare_world);
  RayScene scene(bare_world);
  if (state) {
    State s = *state;
    s.robots.clear();
    scene.update(s);
  }

  // a horizontal fan around the origin
  std::vector<Ray> fan(static_cast<std::size_t>(rays));
  for (int i = 0; i < rays; ++i) {
    const double a = 2 * M_PI * i / rays;
    fan[static_cast<std::size_t>(i)] = Ray{origin, Vec3(std::cos(a), std::sin(a), 0), INFINITY};
  }
  std::vector<RayHit> hits(fan.size());

  // alternate the two in short rounds so machine noise falls on both alike
  const int previous_threads = worker_threads();
  set_worker_threads(1);
  const int rounds = 4;
  double bare_time = 0, scene_time = 0;
  long bare_rays = 0, scene_rays = 0;
  long checksum = 0;
  for (int round = 0; round < rounds; ++round) {
    auto t0 = Clock::now();
    do {
      checksum += bare.trace(fan);
      bare_rays += rays;
    } while (seconds_since(t0) < seconds / (2 * rounds));
    bare_time += seconds_since(t0);
    t0 = Clock::now();
    do {
      scene.cast(fan, hits);
      checksum += hits[0].hit();
      scene_rays += rays;
    } while (seconds_since(t0) < seconds / (2 * rounds));
    scene_time += seconds_since(t0);
  }
  set_worker_threads(previous_threads);
  RS_DEMAND(checksum >= 0, "measure_ray_throughput: impossible hit count");
  return {static_cast<double>(bare_rays) / bare_time, static_cast<double>(scene_rays) / scene_time};
}

}  // namespace rescuesim
