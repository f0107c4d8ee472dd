// Ray-sensor speed: bare Embree rtcIntersect16 on a 10 × 10 maze's triangles beside RayScene
// on the same 1080 rays (target: RayScene ≥ 0.7× bare), and a 1080-beam lidar end to end.
// Run: build/bin/raycast_bench. Items per second are rays per second.

#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include <map>
#include <vector>

#include "core/parallel.h"
#include "core/rng.h"
#include "import/maze/maze.h"
#include "raycast/ray_scene.h"
#include "sensors/lidar.h"
#include "world/world.h"

namespace rescuesim {
namespace {

constexpr int kBeams = 1080;

/// A one-link robot carrying a 1080-beam, 270° lidar 0.15 m above its base link.
RobotSpec lidar_robot() {
  RobotSpec r;
  r.model = "bench_bot";
  LinkSpec base;
  base.name = "base_link";
  base.shapes.push_back({Geometry::box({0.5, 0.4, 0.2}), Pose3{}, "robot_body", true});
  r.links.push_back(base);
  SensorSpec s;
  s.name = "scan";
  s.type = SensorSpec::Type::lidar;
  s.X_LS = Pose3{Vec3(0, 0, 0.15), Quat::Identity()};
  s.frame_id = "laser";
  s.lidar.samples = kBeams;
  s.lidar.min_angle = -0.75 * M_PI;
  s.lidar.max_angle = 0.75 * M_PI;
  s.lidar.max_range = 30.0;
  r.sensors.push_back(s);
  return r;
}

/// The 10 × 10 maze world, with the bench robot at the start cell (or without robots).
World maze_world(bool with_robot) {
  MazeOptions o;
  o.cols = 10;
  o.rows = 10;
  o.seed = 42;
  o.loop_fraction = 0.1;
  WorldSpec spec = maze_to_world(generate_maze(o));
  if (!with_robot) spec.robots.clear();
  for (auto& r : spec.robots) r.model = "bench_bot";
  return compile_world(spec, {{"bench_bot", lidar_robot()}});
}

/// The lidar's 1080 beams as world rays from the start cell centre, 0.3 m up.
std::vector<Ray> scan_rays() {
  MazeOptions o;
  const double c = 0.5 * o.cell_size;
  std::vector<Ray> rays;
  for (int i = 0; i < kBeams; ++i) {
    const double a = -0.75 * M_PI + i * 1.5 * M_PI / (kBeams - 1);
    rays.push_back({Vec3(c, c, 0.3), Vec3(std::cos(a), std::sin(a), 0), 30.0f});
  }
  return rays;
}

/// Bare embree: the world's static triangles in one flat scene, robust and high quality as in
/// RayScene, on its own device.
struct BareEmbree {
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(device);
  explicit BareEmbree(const World& w) {
    std::vector<float> v;
    std::vector<unsigned> idx;
    for (const StaticObject& o : w.statics) {
      const TriangleMesh m = mesh_of(o.geometry, 24);
      const auto base = static_cast<unsigned>(v.size() / 3);
      for (const Vec3& p : m.vertices) {
        const Vec3 q = o.X_WO * p;
        v.insert(v.end(), {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z())});
      }
      for (const auto& t : m.triangles) {
        for (int k : t) idx.push_back(base + static_cast<unsigned>(k));
      }
    }
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, v.size() / 3));
    std::copy(v.begin(), v.end(), vb);
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, idx.size() / 3));
    std::copy(idx.begin(), idx.end(), ib);
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    rtcCommitScene(scene);
  }
  ~BareEmbree() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
};

void BM_BareEmbreeIntersect16(benchmark::State& state) {
  const World world = maze_world(false);
  const BareEmbree bare(world);
  const std::vector<Ray> rays = scan_rays();
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // as RayScene traces
  alignas(64) int valid[16];
  alignas(64) RTCRayHit16 rh;
  for (auto _ : state) {
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
      rtcIntersect16(valid, bare.scene, &ctx, &rh);
      benchmark::DoNotOptimize(rh.ray.tfar[0]);
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(rays.size()));
}
BENCHMARK(BM_BareEmbreeIntersect16)->Unit(benchmark::kMicrosecond);

void BM_RaySceneCast(benchmark::State& state) {
  const World world = maze_world(false);
  const RayScene scene(world);
  const std::vector<Ray> rays = scan_rays();
  std::vector<RayHit> hits(rays.size());
  set_worker_threads(1);
  for (auto _ : state) {
    scene.cast(rays, hits);
    benchmark::DoNotOptimize(hits.data());
  }
  set_worker_threads(0);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(rays.size()));
  state.counters["triangles"] = static_cast<double>(scene.triangle_count());
}
BENCHMARK(BM_RaySceneCast)->Unit(benchmark::kMicrosecond);

/// Moving every rubble body and the robot and recommitting the scene, as the simulation does
/// before each sensor sample: an n × n maze with 20 pieces of rubble. The static walls are not
/// rebuilt, so the time hardly grows with n.
void BM_RaySceneUpdate(benchmark::State& state) {
  MazeOptions o;
  o.cols = static_cast<int>(state.range(0));
  o.rows = o.cols;
  o.seed = 42;
  o.rubble = 20;
  WorldSpec spec = maze_to_world(generate_maze(o));
  for (auto& r : spec.robots) r.model = "bench_bot";
  const World world = compile_world(spec, {{"bench_bot", lidar_robot()}});
  RayScene scene(world);
  State s;
  for (const auto& d : world.dynamics) s.dynamics.push_back({d.X_WO});
  for (const auto& r : world.robots) {
    RobotState rs;
    rs.X_WL = {r.X_W_start};
    s.robots.push_back(rs);
  }
  double shift = 0;
  for (auto _ : state) {
    shift = shift > 0.01 ? 0 : shift + 0.001;
    for (std::size_t i = 0; i < s.dynamics.size(); ++i) s.dynamics[i].X_WB.p.x() = world.dynamics[i].X_WO.p.x() + shift;
    s.robots[0].X_WL[0].p.x() = world.robots[0].X_W_start.p.x() + shift;
    scene.update(s);
  }
  state.counters["triangles"] = static_cast<double>(scene.triangle_count());
}
BENCHMARK(BM_RaySceneUpdate)->Arg(10)->Arg(50)->Unit(benchmark::kMicrosecond);

/// A whole 1080-beam scan with 1 cm noise; the argument is the thread limit (0 = all cores).
void BM_Lidar1080(benchmark::State& state) {
  const World world = maze_world(true);
  RayScene scene(world);
  State s;
  for (const auto& r : world.robots) {
    RobotState rs;
    for (const Pose3& X_BL : link_poses(r.spec, initial_positions(r.spec))) rs.X_WL.push_back(r.X_W_start * X_BL);
    s.robots.push_back(rs);
  }
  scene.update(s);
  const SensorSpec& spec = world.robots[0].spec.sensors[0];
  Rng rng(1, "scan");
  set_worker_threads(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(sample_lidar(world, s, scene, RobotIndex(0), spec, SimTime{}, rng));
  set_worker_threads(0);
  state.SetItemsProcessed(state.iterations() * kBeams);
  state.counters["scans/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Lidar1080)->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace rescuesim

BENCHMARK_MAIN();
