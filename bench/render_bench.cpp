// Camera rendering speed: colour, depth and thermal images of a 10 × 10 maze (low quality) at
// 640 × 480 and 320 × 240, each read back to memory, beside a bare GL loop drawing the same
// number of triangles over the whole view with a flat shader and an RGB8 read-back (target:
// renderer ≥ 0.8× bare). Also colour at medium and high quality for reference.
// Run: build/bin/render_bench. Items per second are frames per second.

#include <benchmark/benchmark.h>

#include <memory>

#include "import/maze/maze.h"
#include "render/bench/render_bench.h"
#include "render/renderer.h"

namespace rescuesim {
namespace {

/// The 10 × 10 maze (seed 42) with rubble, victims and raised areas, and no robot.
const RenderScene& maze_scene() {
  static const RenderScene scene = [] {
    MazeOptions o;
    o.cols = 10;
    o.rows = 10;
    o.seed = 42;
    o.loop_fraction = 0.1;
    o.rubble = 12;
    o.victims = 3;
    o.raised_fraction = 0.1;
    WorldSpec spec = maze_to_world(generate_maze(o));
    spec.robots.clear();
    return build_render_scene(compile_world(spec, {}));
  }();
  return scene;
}

/// From the start cell, 0.5 m up, looking along the maze's diagonal and a little down.
CameraView bench_view(int w, int h) {
  CameraView v;
  v.X_WC = Pose3::from_rpy(Vec3(0.75, 0.75, 0.5), 0, 0.15, 0.6);
  v.k = Intrinsics::from_hfov(w, h, 1.2);
  v.near_clip = 0.05;
  v.far_clip = 30.0;
  return v;
}

/// One renderer per quality for the whole run (a context and its shaders are made once).
Renderer& renderer(Quality q) {
  static std::unique_ptr<Renderer> r[3];
  auto& slot = r[static_cast<int>(q)];
  if (!slot) {
    slot = Renderer::create_headless(q);
    slot->load(maze_scene());
  }
  return *slot;
}

void BM_Renderer(benchmark::State& state, Quality q, BenchImage image) {
  const auto w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
  Renderer& r = renderer(q);
  const CameraView view = bench_view(w, h);
  ColorImage color;
  DepthImage depth;
  ThermalImage thermal;
  for (int i = 0; i < 3; ++i) r.color(view, color);
  for (auto _ : state) {
    switch (image) {
      case BenchImage::color: r.color(view, color); break;
      case BenchImage::depth: r.depth(view, depth); break;
      case BenchImage::thermal: r.thermal(view, 1.5, thermal); break;
    }
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["triangles"] = static_cast<double>(maze_scene().triangle_count());
}

void BM_BareGl(benchmark::State& state) {
  const auto w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
  const auto triangles = static_cast<int>(maze_scene().triangle_count());
  double fps = 0;
  for (auto _ : state) fps = bare_gl_frames_per_second(w, h, triangles, 1.0);
  state.counters["fps"] = fps;
  state.counters["triangles"] = triangles;
}

#define SIZES Args({640, 480})->Args({320, 240})->Unit(benchmark::kMillisecond)->UseRealTime()
BENCHMARK(BM_BareGl)->SIZES->Iterations(1);
BENCHMARK_CAPTURE(BM_Renderer, color_low, Quality::low, BenchImage::color)->SIZES;
BENCHMARK_CAPTURE(BM_Renderer, depth, Quality::low, BenchImage::depth)->SIZES;
BENCHMARK_CAPTURE(BM_Renderer, thermal_blur1_5, Quality::low, BenchImage::thermal)->SIZES;
BENCHMARK_CAPTURE(BM_Renderer, color_medium, Quality::medium, BenchImage::color)->SIZES;
BENCHMARK_CAPTURE(BM_Renderer, color_high, Quality::high, BenchImage::color)->SIZES;

}  // namespace
}  // namespace rescuesim

BENCHMARK_MAIN();
