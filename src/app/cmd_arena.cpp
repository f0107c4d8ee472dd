// rescuesim arena: a test-method arena (lanes of standard terrain side by side) as an SVG world,
// with a PNG preview, like rescuesim maze.

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "app/commands.h"
#include "core/atomic_file.h"
#include "import/svg/svg_world.h"
#include "viz/world_plot.h"
#include "world/terrain.h"

namespace rescuesim::app {

namespace {

struct ArenaCommand {
  std::string lanes;
  std::string out = "arena.svg";
  ArenaOptions arena;
  bool lane_width_given = false;
  bool png = true;
};

int run_arena(const ArenaCommand& c) {
  namespace fs = std::filesystem;
  ArenaOptions o = c.arena;
  if (o.figure_eight && !c.lane_width_given) o.lane_width = kFigureEightLaneWidth;
  std::stringstream list(c.lanes);
  std::string name;
  while (std::getline(list, name, ',')) {
    if (!name.empty()) o.lanes.push_back(terrain_kind_from_name(name));  // Error: exit 2, naming the known kinds
  }
  const WorldSpec world = test_method_arena(o);
  const Diagnostics problems = validate(world);
  problems.throw_if_errors();
  const fs::path svg = c.out;
  write_file_atomic(svg, world_to_svg(world));
  std::printf("%s: %zu %s of %.2f m, %.2f x %.2f m\n", svg.string().c_str(), world.terrain.size(),
              o.figure_eight ? "figure-8 lanes" : "lanes", o.lane_width, world.floor_max.x() - world.floor_min.x(),
              world.floor_max.y() - world.floor_min.y());
  for (std::size_t i = 0; i < world.terrain.size(); ++i) {
    const TerrainSpec& t = world.terrain[i];
    std::printf("  lane %zu  %-15s %.2f m long, from y = %s to %s m\n", i, TerrainSpec::kind_name(t.kind), t.length,
                world.metadata.at("lane." + std::to_string(i) + ".start_line_y").c_str(),
                world.metadata.at("lane." + std::to_string(i) + ".end_line_y").c_str());
  }
  if (o.figure_eight) {
    std::printf("drive it: rescuesim trial-terrain %s --lane %s --pattern figure-eight --laps 3\n", svg.string().c_str(),
                TerrainSpec::kind_name(world.terrain[0].kind));
  }
  if (c.png) {
    fs::path png = svg;
    png.replace_extension(".png");
    WorldPlotOptions po;
    po.px_per_m = 60;
    po.title = "test-method arena: " + c.lanes;
    plot_world(world, po).write_png(png);
    std::printf("wrote %s and %s\n", svg.string().c_str(), png.string().c_str());
  } else {
    std::printf("wrote %s\n", svg.string().c_str());
  }
  return kExitOk;
}

}  // namespace

void add_arena_command(CLI::App& app, Action& action) {
  auto c = std::make_shared<ArenaCommand>();
  CLI::App* cmd = app.add_subcommand("arena", "Generate a test-method arena: lanes of standard terrain side by side, as an SVG world");
  cmd->footer(
      "Each lane holds one element of the response-robot test methods at its standard size\n"
      "(docs/terrain.md), across the lane's middle, with open floor before and after it. Lanes run\n"
      "south to north, west to east in the order given; the robot starts at the south end of\n"
      "--start-lane. The SVG follows the world convention (docs/worlds.md): 'rescuesim check' and\n"
      "scenarios read it like any drawn world, and a stepfield's seed is the arena's seed plus its lane.\n\n"
      "Kinds: stepfield, stairs, crossing-ramps, curb, hurdle, gap.\n\n"
      "--figure-eight builds the figure-8 apparatus instead: each element 2.4 x 4.8 m (stepfields and\n"
      "crossing ramps only) in lanes 2.5 m wide, for 'rescuesim trial-terrain --pattern figure-eight'.\n\n"
      "Examples:\n"
      "  rescuesim arena --lanes stepfield,crossing-ramps,stairs --out arena.svg\n"
      "  rescuesim arena --lanes curb,hurdle,gap --lane-width 1.1 --start-lane 2 --seed 7 --out lanes.svg\n"
      "  rescuesim arena --lanes stepfield,crossing-ramps --figure-eight --out eights.svg");
  cmd->add_option("--lanes", c->lanes, "comma-separated terrain kinds, one lane each, west to east")->required();
  cmd->add_option("--out,-o", c->out, "the SVG to write (a PNG preview goes beside it)")->capture_default_str();
  cmd->add_option("--lane-width", c->arena.lane_width, "m (2.5 with --figure-eight)")->capture_default_str();
  cmd->add_flag("--figure-eight", c->arena.figure_eight, "figure-8 elements (2.4 x 4.8 m) instead of lane elements");
  cmd->add_option("--approach", c->arena.approach, "m of open floor before and after each element")->capture_default_str();
  cmd->add_option("--start-lane", c->arena.start_lane, "the lane the robot starts in (0 = westmost)")->capture_default_str();
  cmd->add_option("--seed", c->arena.seed, "seed of the stepfields' heights")->capture_default_str();
  cmd->add_flag("!--no-png", c->png, "skip the PNG preview");
  cmd->final_callback([c, cmd, &action] {
    c->lane_width_given = cmd->count("--lane-width") > 0;
    action = [c] { return run_arena(*c); };
  });
}

}  // namespace rescuesim::app
