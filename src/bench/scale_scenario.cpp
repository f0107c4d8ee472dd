#include "bench/scale_scenario.h"

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "core/error.h"

namespace rescuesim::bench {

namespace {
constexpr int kCells = 12;             // the 12 x 12 maze ...
constexpr double kSide = 20.0;         // ... over 20 m
constexpr int kMaxRobots = 10000;
}  // namespace

int scale_maze_cells(int robots) {
  return robots <= kCells * kCells ? kCells : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(robots))));
}

Scenario scale_scenario(int robots, double duration, const ModelMap& models, std::uint64_t seed) {
  if (robots < 1 || robots > kMaxRobots) {
    throw Error("scale scenario: " + std::to_string(robots) + " robots; expected 1 to " + std::to_string(kMaxRobots));
  }
  const int c = scale_maze_cells(robots);
  // written as a scenario file would be, so the scenario reader checks it like any other
  std::string cells, list;
  for (int k = 0; k < robots; ++k) {
    const long i = static_cast<long>(k) * c * c / robots;
    cells += fmt::format("{}[{}, {}]", k ? ", " : "", i % c, i / c);
    list += fmt::format(
        "  - {{name: r{}, controller: wall_follower, sensors: {{laser: {{samples: 1081, fov: 270, max_range: 30, rate: 10}}}}}}\n", k + 1);
  }
  const std::string yaml = fmt::format(
      "name: scale-{}\nseed: {}\nduration: {}\nmode: lockstep\n"
      "world:\n  maze:\n    cols: {}\n    rows: {}\n    cell_size: {}\n    loop_fraction: 0.15\n"
      "    rubble: 0\n    raised_fraction: 0\n    victims: 0\n    start_cells: [{}]\n"
      "robots:\n{}",
      robots, seed, duration, c, c, kSide / kCells, cells, list);
  return parse_scenario(yaml, "scale scenario", models);
}

}  // namespace rescuesim::bench
