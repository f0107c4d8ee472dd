// rescuesim maze: batches of random mazes as SVG drawings (the same convention as hand-drawn
// worlds) with a PNG preview of each.

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "app/commands.h"
#include "core/atomic_file.h"
#include "import/maze/maze.h"
#include "import/svg/svg_world.h"
#include "viz/world_plot.h"
#include "world/terrain.h"

namespace rescuesim::app {

namespace {

struct MazeCommand {
  MazeOptions maze;
  int count = 1;
  std::string out = "mazes";
  std::vector<int> start_cell{0, 0};
  std::string terrain_kinds = "stepfield";
  bool png = true;
  double png_resolution = 40;
};

int run_maze(const MazeCommand& c) {
  namespace fs = std::filesystem;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < c.count; ++k) {
    MazeOptions o = c.maze;
    o.seed = c.maze.seed + static_cast<std::uint64_t>(k);
    o.start_cell = {c.start_cell[0], c.start_cell[1]};
    o.terrain.clear();
    std::stringstream kinds(c.terrain_kinds);
    for (std::string name; std::getline(kinds, name, ',');) {
      if (!name.empty()) o.terrain.push_back(terrain_kind_from_name(name));  // Error: exit 2, naming the kinds
    }
    const Maze maze = generate_maze(o);
    const WorldSpec world = maze_to_world(maze);
    const std::string stem = "maze-" + std::to_string(o.seed);
    const fs::path svg = fs::path(c.out) / (stem + ".svg");
    write_file_atomic(svg, world_to_svg(world));
    if (c.png) {
      WorldPlotOptions po;
      po.px_per_m = c.png_resolution;
      po.title = stem + "  " + std::to_string(o.cols) + "x" + std::to_string(o.rows) + " cells, seed " + std::to_string(o.seed);
      plot_world(world, po).write_png(fs::path(c.out) / (stem + ".png"));
    }
    std::printf("[%d/%d] %s: %dx%d cells, %d openings, %zu walls, %zu victims, %zu raised areas, %zu terrain cells, %zu rubble\n", k + 1,
                c.count, svg.string().c_str(), o.cols, o.rows, maze.opening_count(), world.walls.size(), world.victims.size(),
                world.raised_areas.size(), world.terrain.size(), world.rubble.size());
    std::fflush(stdout);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("wrote %d maze(s) to %s/ in %.2f s\n", c.count, c.out.c_str(), s);
  return kExitOk;
}

}  // namespace

void add_maze_command(CLI::App& app, Action& action) {
  auto c = std::make_shared<MazeCommand>();
  CLI::App* cmd = app.add_subcommand("maze", "Generate random mazes (modified Prim's algorithm) as SVG worlds with PNG previews");
  cmd->footer(
      "Maze i of a batch uses seed SEED+i and is written as OUT/maze-<seed>.svg (+ .png). The SVGs\n"
      "follow the world colour convention (docs/worlds.md), so 'rescuesim check' and scenarios read\n"
      "them like hand-drawn worlds. The same seed gives the same maze, byte for byte, everywhere.\n\n"
      "Examples:\n"
      "  rescuesim maze --seed 1 --cols 10 --rows 10 --victims 5\n"
      "  rescuesim maze --seed 100 --count 20 --loops 0.2 --rubble 30 --raised 0.1 --out batch/");
  cmd->add_option("--seed", c->maze.seed, "seed of the first maze")->capture_default_str();
  cmd->add_option("--cols", c->maze.cols, "cells east-west")->capture_default_str()->check(CLI::Range(1, 500));
  cmd->add_option("--rows", c->maze.rows, "cells north-south")->capture_default_str()->check(CLI::Range(1, 500));
  cmd->add_option("--count,-n", c->count, "how many mazes")->capture_default_str()->check(CLI::Range(1, 100000));
  cmd->add_option("--out,-o", c->out, "output folder")->capture_default_str();
  cmd->add_option("--cell-size", c->maze.cell_size, "cell size in metres")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--wall-thickness", c->maze.wall_thickness, "m")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--wall-height", c->maze.wall_height, "m")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--loops", c->maze.loop_fraction, "fraction of remaining inner walls opened (0 = perfect maze)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--rubble", c->maze.rubble, "loose boxes and cylinders")->capture_default_str()->check(CLI::Range(0, 10000));
  cmd->add_option("--raised", c->maze.raised_fraction, "fraction of cells with a raised platform and ramps")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--terrain", c->maze.terrain_fraction, "fraction of cells with a test-method terrain element (docs/terrain.md)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--terrain-kinds", c->terrain_kinds, "the elements, taken in turn: stepfield, curb, hurdle (comma-separated)")
      ->capture_default_str();
  cmd->add_option("--victims", c->maze.victims, "victims, placed in dead ends first")->capture_default_str()->check(CLI::Range(0, 10000));
  cmd->add_option("--start-cell", c->start_cell, "robot start cell: COL ROW")->expected(2)->capture_default_str();
  cmd->add_flag("!--no-png", c->png, "skip the PNG previews");
  cmd->add_option("--png-resolution", c->png_resolution, "preview pixels per metre")->capture_default_str()->check(CLI::Range(1.0, 500.0));
  cmd->final_callback([c, &action] { action = [c] { return run_maze(*c); }; });
}

}  // namespace rescuesim::app
