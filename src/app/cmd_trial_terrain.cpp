// rescuesim trial-terrain: a robot driven across one lane of a test-method arena, lap after lap,
// with repetitions, falls and stuck events counted (docs/terrain.md, "Trials").

#include <cstdio>
#include <filesystem>

#include "app/commands.h"
#include "core/atomic_file.h"
#include "import/svg/svg_world.h"
#include "robots/rescue_robot.h"
#include "session/terrain_trial.h"

namespace rescuesim::app {

namespace {

struct TrialCommand {
  std::string world;
  std::string out = "trial";
  std::string pattern = "laps";
  TerrainTrialOptions trial;
};

int run_trial(TrialCommand c) {
  namespace fs = std::filesystem;
  c.trial.pattern = parse_terrain_pattern(c.pattern);
  const SvgLoadResult loaded = load_svg_world(c.world);
  validate(loaded.world).throw_if_errors();
  const auto models = builtin_models();
  std::printf("trial: %s, lane '%s', %s, %d %s at %.2f m/s\n", c.world.c_str(), c.trial.lane.c_str(), c.trial.robot.c_str(), c.trial.laps,
              terrain_pattern_reps(c.trial.pattern), c.trial.speed);
  const TerrainTrialResult r = run_terrain_trial(loaded.world, models, c.trial, [&c](const TerrainLap& l) {
    std::printf("  lap %2d  %-7s %-9s %6.1f s  %5.2f m along  pitch up to %3.0f deg  roll up to %3.0f deg\n", l.lap,
                l.reverse                                         ? "back"
                : c.trial.pattern == TerrainPattern::figure_eight ? "eight"
                                                                  : "forward",
                l.outcome.c_str(), l.time, l.progress, l.max_pitch, l.max_roll);
    std::fflush(stdout);
  });
  const fs::path dir = c.out;
  fs::create_directories(dir);
  write_file_atomic(dir / "trial.json", terrain_trial_json(r));
  terrain_trial_figure(loaded.world, r).write_png(dir / "trial.png");
  std::printf("%d/%zu repetitions (%s), %d falls, %d stuck, %d out of time; mean %.1f s per repetition\n", r.repetitions, r.laps.size(),
              TerrainSpec::kind_name(r.element.kind), r.falls, r.stuck, r.timeouts, r.mean_time);
  std::printf("wrote %s and %s\n", (dir / "trial.json").string().c_str(), (dir / "trial.png").string().c_str());
  return kExitOk;
}

}  // namespace

void add_trial_terrain_command(CLI::App& app, Action& action) {
  auto c = std::make_shared<TrialCommand>();
  CLI::App* cmd = app.add_subcommand("trial-terrain", "Drive a robot across one lane of a test-method arena, lap after lap, and count");
  cmd->footer(
      "--pattern laps (the default): each lap starts on the lane's start line (--approach before\n"
      "the element), a few centimetres\n"
      "and degrees off its centre line (seeded), and drives along it at --speed until the end line\n"
      "(--approach beyond the element): a repetition. A lap ends early when the robot falls over\n"
      "(pitch beyond 75 or roll beyond 60 degrees), is stuck (no 5 cm of progress in --stuck-time s)\n"
      "or runs out of --time-limit. The scripted driver keeps to the centre line and works the\n"
      "flippers of a robot that has them: raised when level, laid on the obstacle once the nose is\n"
      "17 degrees up, lowered ahead when the nose tips down (docs/terrain.md, \"Trials\").\n\n"
      "--pattern back-and-forth: end-to-end repetitions without a reset, as the ASTM test methods\n"
      "count them: from the start line forward to the end line, then backwards (reversing, facing\n"
      "the same way) to the start line, and so on; each crossing is one repetition and one entry of\n"
      "--laps. The first crossing that fails (fell, stuck, out of time) ends the trial.\n\n"
      "--pattern figure-eight (stepfields and crossing ramps, the test methods' figure-8 terrains):\n"
      "figure-eights without a reset around two pylons on the element's centre line, a quarter of\n"
      "its length in from each end, in loops of half its width less 0.7 m (at least 0.3 m). The\n"
      "robot drives in from the start line to the element's centre, then each figure-eight, back to\n"
      "the centre, is one repetition and one entry of --laps; the first that fails ends the trial.\n"
      "The driver follows the path by pure pursuit (0.35 m ahead, at most 0.8 rad/s: it slows in\n"
      "the loops) and backs up 1.5 s when it has made no progress for 3 s.\n\n"
      "Writes DIR/trial.json (repetitions, falls, stuck, mean time, each lap) and DIR/trial.png\n"
      "(the lane from above with every lap's path: green completed, red fell, orange stuck).\n\n"
      "Examples:\n"
      "  rescuesim arena --lanes stepfield,stairs,curb --out arena.svg\n"
      "  rescuesim trial-terrain arena.svg --lane stairs --robot tracked_robot --laps 10 --out stairs\n"
      "  rescuesim trial-terrain worlds/terrain_lanes.svg --lane curb --robot rescue_robot --laps 3\n"
      "  rescuesim trial-terrain worlds/terrain_lanes.svg --lane curb --pattern back-and-forth --laps 4\n"
      "  rescuesim trial-terrain worlds/terrain_lanes.svg --lane stepfield --pattern figure-eight --laps 3\n\n"
      "Many trials with their own seeds, resumable and summarised: rescuesim batch --trial-terrain\n"
      "(docs/batch.md).");
  cmd->add_option("world", c->world, "the arena (an SVG world with terrain elements, e.g. from rescuesim arena)")->required();
  cmd->add_option("--lane", c->trial.lane, "the element's name (its SVG id), or a kind: the first element of that kind")->required();
  cmd->add_option("--robot", c->trial.robot, "built-in model: tracked_robot or rescue_robot")->capture_default_str();
  cmd->add_option("--laps", c->trial.laps, "attempts (laps), or crossings (back-and-forth) or figure-eights wanted")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--pattern", c->pattern,
                  "laps: each from the start line; back-and-forth: end to end and back without a reset; figure-eight: around two pylons "
                  "without a reset")
      ->capture_default_str()
      ->check(CLI::IsMember({"laps", "back-and-forth", "figure-eight"}));
  cmd->add_option("--seed", c->trial.seed, "seed of the laps' start offsets")->capture_default_str();
  cmd->add_option("--speed", c->trial.speed, "m/s")->capture_default_str()->check(CLI::Range(0.05, 2.0));
  cmd->add_option("--approach", c->trial.approach, "m of floor between the element and the start and end lines")
      ->capture_default_str()
      ->check(CLI::Range(0.3, 10.0));
  cmd->add_option("--time-limit", c->trial.time_limit, "s per lap (per crossing)")->capture_default_str()->check(CLI::Range(1.0, 3600.0));
  cmd->add_option("--stuck-time", c->trial.stuck_time, "s without progress that count as stuck")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 3600.0));
  cmd->add_option("--out,-o", c->out, "directory for trial.json and trial.png")->capture_default_str();
  cmd->final_callback([c, &action] { action = [c] { return run_trial(*c); }; });
}

}  // namespace rescuesim::app
