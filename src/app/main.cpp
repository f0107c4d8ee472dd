// rescuesim: the command-line entry point. Parses the subcommand, runs it, and turns bad
// input into a clear message with exit code 2.

#include <cstdio>
#include <cstdlib>
#include <exception>

#include "app/commands.h"
#include "app/data_dir.h"
#include "app/program.h"
#include "core/log.h"
#include "core/memory.h"
#include "core/parallel.h"

using namespace rescuesim;

int main(int argc, char** argv) {
  tune_allocator_for_long_runs();
  app::set_program_path(argc > 0 ? argv[0] : nullptr);
  CLI::App app{
      "rescuesim — a simulator for mobile rescue robots: Bullet physics, worlds drawn as SVG or\n"
      "generated as random mazes, a wheeled robot with a sensor head, ROS and Foxglove output.\n\n"
      "Quick start:\n"
      "  rescuesim run                      the default rescue scenario, outputs in runs/default/\n"
      "  rescuesim maze --seed 3 --count 5  five random mazes as SVG + PNG in mazes/\n"
      "  rescuesim check worlds/arena.svg   what a drawing contains, or what is wrong with it\n"
      "  rescuesim trial-terrain worlds/terrain_lanes.svg --lane stairs --laps 5\n"
      "                                     the tracked robot on the 40 degree stairs, counted\n"
      "  rescuesim run --record run.mcap    also record every topic (open it in Foxglove)\n"
      "  rescuesim replay run.mcap --ros2   publish a recording again (docs/recording.md)\n"
      "  rescuesim recover run.mcap.part    save what a killed recording holds\n\n"
      "Worlds are SVG drawings: black = walls, red = raised areas, blue = victims, green = robot\n"
      "start, orange = rubble (docs/worlds.md). Run 'rescuesim <command> --help' for details.",
      "rescuesim"};
  app.set_version_flag("--version", std::string("rescuesim ") + RESCUESIM_VERSION);
  app.require_subcommand(1);
  std::string log_level = "warn";
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")->capture_default_str();
  int threads = 0;
  app.add_option("--threads", threads,
                 "worker threads for physics groups, ray sensors and built-in controllers (0 = every core); results are "
                 "the same at any count, e.g. rescuesim --threads 1 run")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));

  app::Action action;
  app::add_run_command(app, action);
  app::add_maze_command(app, action);
  app::add_arena_command(app, action);
  app::add_trial_terrain_command(app, action);
  app::add_check_command(app, action);
  app::add_bench_command(app, action, std::vector<std::string>(argv + 1, argv + argc));
  app::add_snapshot_command(app, action);
  app::add_view_command(app, action);
  app::add_replay_command(app, action);
  app::add_batch_command(app, action);
  app::add_recover_command(app, action);

  return app::run_program(app, argc, argv, log_level, threads, action, "rescuesim");
}
