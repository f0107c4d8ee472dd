// Authoring-side speed: generating mazes, writing them as SVG, and loading SVG worlds.
// Run: build/bin/world_bench (or `make bench`).

#include <benchmark/benchmark.h>

#include "import/maze/maze.h"
#include "import/svg/svg_world.h"

namespace rescuesim {
namespace {

MazeOptions options(int n) {
  MazeOptions o;
  o.cols = n;
  o.rows = n;
  o.seed = 42;
  o.loop_fraction = 0.1;
  o.victims = n / 2;
  o.rubble = n * 2;
  o.raised_fraction = 0.05;
  return o;
}

void BM_MazeGenerate(benchmark::State& state) {
  const MazeOptions o = options(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(generate_maze(o));
  state.SetItemsProcessed(state.iterations() * o.cols * o.rows);
}
BENCHMARK(BM_MazeGenerate)->Arg(10)->Arg(50)->Unit(benchmark::kMicrosecond);

void BM_MazeToWorld(benchmark::State& state) {
  const Maze m = generate_maze(options(static_cast<int>(state.range(0))));
  for (auto _ : state) benchmark::DoNotOptimize(maze_to_world(m));
}
BENCHMARK(BM_MazeToWorld)->Arg(10)->Arg(50)->Unit(benchmark::kMicrosecond);

void BM_WorldToSvg(benchmark::State& state) {
  const WorldSpec w = maze_to_world(generate_maze(options(static_cast<int>(state.range(0)))));
  for (auto _ : state) benchmark::DoNotOptimize(world_to_svg(w));
}
BENCHMARK(BM_WorldToSvg)->Arg(50)->Unit(benchmark::kMicrosecond);

void BM_SvgLoad(benchmark::State& state) {
  const std::string text = world_to_svg(maze_to_world(generate_maze(options(static_cast<int>(state.range(0))))));
  for (auto _ : state) benchmark::DoNotOptimize(load_svg_world_from_string(text, "maze.svg"));
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(text.size()));
}
BENCHMARK(BM_SvgLoad)->Arg(10)->Arg(50)->Unit(benchmark::kMicrosecond);

void BM_Validate(benchmark::State& state) {
  const WorldSpec w = maze_to_world(generate_maze(options(static_cast<int>(state.range(0)))));
  for (auto _ : state) benchmark::DoNotOptimize(validate(w));
}
BENCHMARK(BM_Validate)->Arg(50)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace rescuesim

BENCHMARK_MAIN();
