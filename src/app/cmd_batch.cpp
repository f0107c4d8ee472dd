// rescuesim batch: many seeded trials of a scenario, J at a time, each recorded in
// results.jsonl as it ends; resumable, shardable, and mergeable (docs/batch.md).

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <thread>

#include "app/commands.h"
#include "app/data_dir.h"
#include "robots/rescue_robot.h"
#include "batch/batch_results.h"
#include "batch/batch_runner.h"
#include "batch/batch_summary.h"
#include "batch/batch_trial.h"

namespace rescuesim::app {

namespace {

namespace fs = std::filesystem;

std::atomic<bool> g_stop{false};
extern "C" void on_stop_signal(int) { g_stop.store(true); }

struct BatchCommand {
  std::string scenario;
  std::optional<int> trials;
  int jobs = 0;
  std::optional<std::uint64_t> seed;
  std::string out;
  std::string shard;
  std::optional<double> duration;
  std::string controller;
  bool cameras = false;
  bool full_duration = false;
  bool retry_failed = false;
  bool threads = false;
  bool quiet = false;
  // terrain trials (--trial-terrain ARENA.svg)
  std::string terrain_world;
  std::string pattern = "laps";
  TerrainTrialOptions terrain;
};

struct MergeCommand {
  std::vector<std::string> dirs;
  std::string out;
};

std::string clock_text(double s) {
  if (s < 0) return "--:--";
  const long t = static_cast<long>(s + 0.5);
  char buf[32];
  if (t >= 3600) {
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%ld:%02ld", t / 60, t % 60);
  }
  return buf;
}

/// The progress bar (on a terminal) or a line per trial (in a log).
void print_progress(const BatchProgress& p, bool tty) {
  if (!tty) {
    if (!p.last) return;
    const TrialRecord& r = *p.last;
    if (r.status == "ok" && r.terrain) {
      std::fprintf(stderr, "[%d/%d] trial %d (seed %llu): %d/%d repetitions, %d falls, %d stuck, %.1f s in %.1f s\n", p.done, p.planned,
                   r.trial, static_cast<unsigned long long>(r.seed), r.terrain->repetitions, r.terrain->laps, r.terrain->falls,
                   r.terrain->stuck, r.sim_time, r.wall_time);
    } else if (r.status == "ok") {
      std::fprintf(stderr, "[%d/%d] trial %d (seed %llu): %d/%d victims, %.0f%% coverage, %d collisions, %.1f s in %.1f s\n", p.done,
                   p.planned, r.trial, static_cast<unsigned long long>(r.seed), r.victims_found, r.victims_total, 100 * r.coverage,
                   r.collisions, r.sim_time, r.wall_time);
    } else {
      std::fprintf(stderr, "[%d/%d] trial %d (seed %llu) FAILED: %s\n", p.done, p.planned, r.trial, static_cast<unsigned long long>(r.seed),
                   r.error.c_str());
    }
    std::fflush(stderr);
    return;
  }
  if (p.last && p.last->status != "ok") {
    std::fprintf(stderr, "\r\033[Ktrial %d (seed %llu) FAILED: %s\n", p.last->trial, static_cast<unsigned long long>(p.last->seed),
                 p.last->error.c_str());
  }
  const double f = p.planned > 0 ? static_cast<double>(p.done) / p.planned : 1.0;
  char bar[31];
  const int filled = static_cast<int>(f * 30);
  for (int i = 0; i < 30; ++i) bar[i] = i < filled ? '#' : '-';
  bar[30] = 0;
  std::fprintf(stderr, "\r[%s] %d/%d trials  %d failed  %d running  elapsed %s  ETA %s  ", bar, p.done, p.planned, p.failed, p.running,
               clock_text(p.elapsed).c_str(), clock_text(p.eta).c_str());
  std::fflush(stderr);
}

void print_summary_line(const std::map<int, TrialRecord>& records) {
  int failed = 0, successes = 0, found = 0, total = 0;
  double coverage = 0;
  int terrain = 0, laps = 0, reps = 0, falls = 0, stuck = 0;
  for (const auto& [t, r] : records) {
    if (r.terrain) {
      ++terrain;
      laps += r.terrain->laps;
      reps += r.terrain->repetitions;
      falls += r.terrain->falls;
      stuck += r.terrain->stuck;
    }
    failed += r.status != "ok";
    successes += r.success;
    found += r.victims_found;
    total += r.victims_total;
    coverage += r.coverage;
  }
  const double n = std::max<double>(1, static_cast<double>(records.size()));
  if (terrain > 0) {
    std::printf("%zu trials recorded: %d completed every repetition (%.0f%%), %d failed; repetitions %d/%d, %d falls, %d stuck\n",
                records.size(), successes, 100.0 * successes / n, failed, reps, laps, falls, stuck);
    return;
  }
  std::printf("%zu trials recorded: %d found every victim (%.0f%%), %d failed; victims found %d/%d, mean coverage %.0f%%\n",
              records.size(), successes, 100.0 * successes / n, failed, found, total, 100.0 * coverage / n);
}

int run_batch(const BatchCommand& c) {
  if (!c.trials) throw Error("batch: --trials N is required (how many trials the batch has)");
  const ModelMap models = builtin_models();
  const bool terrain = !c.terrain_world.empty();
  if (terrain && !c.scenario.empty()) throw Error("batch: give a scenario or --trial-terrain ARENA.svg, not both");
  if (!terrain && !c.terrain.lane.empty()) throw Error("batch: --lane belongs to --trial-terrain ARENA.svg");
  if (terrain && c.terrain.lane.empty()) throw Error("batch: --trial-terrain needs --lane (an element's name or a kind, e.g. stairs)");
  // a terrain batch's scenario is its arena: the SVG by its absolute path, so child processes and
  // reruns from another folder find it; its text is part of the fingerprint like a scenario's
  const BatchScenario bs =
      terrain ? parse_batch_scenario("name: " + fs::path(c.terrain_world).stem().string() + "\nseed: 1\nworld:\n  svg: \"" +
                                         fs::absolute(c.terrain_world).lexically_normal().string() + "\"\n",
                                     "<built-in>", models)
              : load_batch_scenario(c.scenario, models);
  TrialOptions to;
  to.duration = c.duration;
  to.controller = c.controller;
  to.cameras = c.cameras;
  to.stop_when_all_found = !c.full_duration;
  if (terrain) {
    to.terrain = c.terrain;
    to.terrain->pattern = parse_terrain_pattern(c.pattern);
    // fails now (exit 2) rather than in every trial: a world that does not load, a lane it lacks
    const WorldSpec world = build_world(bs.scenario);
    validate(world).throw_if_errors();
    const TerrainSpec* lane = find_terrain_lane(world, c.terrain.lane);
    if (!lane)
      throw Error({c.terrain_world, 0, "--lane"},
                  "no lane '" + c.terrain.lane + "' in " + c.terrain_world + " (expected a terrain element's name or kind)");
    check_terrain_pattern(*lane, to.terrain->pattern);
    if (!models.count(c.terrain.robot))
      throw Error("batch: unknown robot '" + c.terrain.robot + "' (expected tracked_robot or rescue_robot)");
  }
  const std::string fingerprint = batch_fingerprint(bs.text, to);
  const std::uint64_t base_seed = c.seed ? *c.seed : bs.scenario.seed;
  const Shard shard = c.shard.empty() ? Shard{} : parse_shard(c.shard);
  // a bad time limit is an error of the command, not of every trial
  const double duration = to.duration ? *to.duration : bs.scenario.duration;
  if (!terrain && (!std::isfinite(duration) || duration <= 0))
    throw Error({bs.file, 0, "duration"}, "a batch needs a finite time limit per trial: give --duration");
  const fs::path out = c.out.empty() ? fs::path("batches") / bs.scenario.name : fs::path(c.out);
  const int jobs = c.jobs > 0 ? c.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));

  ResultsFile results(out);
  LoadedResults loaded = results.load();
  for (const auto& n : loaded.notices) std::fprintf(stderr, "%s/%s\n", out.string().c_str(), n.c_str());
  check_same_batch(loaded, results.path(), fingerprint, base_seed);
  if (c.retry_failed) {
    int dropped = 0;
    for (auto it = loaded.records.begin(); it != loaded.records.end();) {
      if (it->second.status != "ok") {
        it = loaded.records.erase(it);
        ++dropped;
      } else {
        ++it;
      }
    }
    if (dropped > 0) {
      results.rewrite(loaded.records);
      std::fprintf(stderr, "retrying %d failed trials\n", dropped);
    }
  }
  std::vector<int> todo;
  const std::vector<int> mine = shard_trials(*c.trials, shard);
  for (int t : mine) {
    if (!loaded.records.count(t)) todo.push_back(t);
  }
  std::printf("batch %s (%s): trials 0..%d with seeds %llu..%llu%s\n", bs.scenario.name.c_str(), fingerprint.c_str(), *c.trials - 1,
              static_cast<unsigned long long>(base_seed), static_cast<unsigned long long>(trial_seed(base_seed, *c.trials - 1)),
              c.shard.empty() ? "" : (", shard " + c.shard + " (" + std::to_string(mine.size()) + " trials)").c_str());
  if (terrain) {
    std::printf("  terrain trials: lane '%s', %s, %d %s at %.2f m/s\n", c.terrain.lane.c_str(), c.terrain.robot.c_str(), c.terrain.laps,
                terrain_pattern_reps(to.terrain->pattern), c.terrain.speed);
  }
  std::printf("  %zu already recorded in %s, %zu to run, %d at a time in %s%s\n", mine.size() - todo.size(),
              results.path().string().c_str(), todo.size(), jobs, c.threads ? "threads" : "child processes",
              c.cameras ? ", cameras on" : ", no cameras");
  std::fflush(stdout);

  g_stop = false;
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  const bool tty = ::isatty(STDERR_FILENO);
  BatchRunOptions ro;
  ro.jobs = jobs;
  ro.isolation = c.threads ? Isolation::thread : Isolation::process;
  ro.stop = &g_stop;
  if (!c.quiet) ro.progress = [tty](const BatchProgress& p) { print_progress(p, tty); };
  const BatchRunStats stats =
      todo.empty() ? BatchRunStats{} : run_batch_trials(bs.scenario, models, todo, base_seed, to, fingerprint, results, ro);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (!c.quiet && tty && !todo.empty()) std::fprintf(stderr, "\n");

  const LoadedResults all = results.load();
  BatchRunInfo info;
  info.jobs = jobs;
  info.trials_run = stats.recorded;
  info.wall_time = stats.elapsed;
  write_batch_summary(out, all.records, info);
  print_summary_line(all.records);
  if (stats.recorded > 0) {
    std::printf("this run: %d trials in %.1f s (%.0f trials/hour), %d failed\n", stats.recorded, stats.elapsed,
                stats.recorded / stats.elapsed * 3600, stats.failed);
  }
  std::printf("wrote %s/{results.jsonl, summary.json, summary.csv, summary.png}\n", out.string().c_str());
  if (stats.interrupted) {
    std::fprintf(stderr, "batch interrupted: %zu trials not recorded; run the same command again to finish\n",
                 todo.size() - stats.recorded);
    return kExitFailure;
  }
  int failed = 0;
  for (int t : mine) failed += all.records.count(t) && all.records.at(t).status != "ok";
  return failed > 0 ? kExitFailure : kExitOk;
}

int run_merge(const MergeCommand& m) {
  std::vector<fs::path> dirs(m.dirs.begin(), m.dirs.end());
  std::map<int, TrialRecord> merged;
  for (const auto& n : merge_results(dirs, m.out, &merged)) std::fprintf(stderr, "%s\n", n.c_str());
  write_batch_summary(m.out, merged);
  print_summary_line(merged);
  std::printf("wrote %s/{results.jsonl, summary.json, summary.csv, summary.png}\n", m.out.c_str());
  return kExitOk;
}

}  // namespace

void add_batch_command(CLI::App& app, Action& action) {
  auto c = std::make_shared<BatchCommand>();
  auto m = std::make_shared<MergeCommand>();
  CLI::App* cmd = app.add_subcommand("batch", "Run many seeded trials of a scenario and summarise them (resumable, shardable)");
  cmd->footer(
      "Trial i runs the scenario with seed S+i (maze and every noise stream), headless, in\n"
      "lockstep, with the scenario's controllers (the built-in explorer by default), until every\n"
      "victim is found or the time limit. Each trial runs in a child process of its own: a trial\n"
      "that crashes is recorded as failed and the batch goes on.\n\n"
      "Writes DIR/results.jsonl (one JSON line per trial, appended as each ends) and, at the end,\n"
      "summary.json, summary.csv and summary.png. Rerunning the same command skips the trials\n"
      "already recorded, so a killed batch loses only the trials that were running.\n\n"
      "Examples:\n"
      "  rescuesim batch --trials 100 --jobs 2                 the default scenario\n"
      "  rescuesim batch worlds/arena.yaml --trials 50 --seed 1000 --out batches/arena\n"
      "  rescuesim batch s.yaml --trials 1000 --shard 3/10 --out part3   (one of ten machines)\n"
      "  rescuesim batch merge part0 part1 part2 --out all\n"
      "  rescuesim batch --trial-terrain worlds/terrain_lanes.svg --lane stairs --robot tracked_robot \\\n"
      "      --laps 5 --trials 20 --out batches/stairs\n\n"
      "Terrain trials (--trial-terrain ARENA.svg --lane L): trial i is `rescuesim trial-terrain`\n"
      "on that lane with seed S+i (--seed, default 1); it succeeds when every one of its --laps\n"
      "repetitions is completed. Each results.jsonl line then has a \"terrain\" object (lane, kind,\n"
      "robot, pattern, laps, repetitions, falls, stuck, timeouts, mean_time_s), and summary.json a\n"
      "\"terrain\" section (repetition rate, falls, stuck) beside the success rate.\n\n"
      "Exit codes: 0 all trials recorded and none failed, 1 some failed or the batch was\n"
      "interrupted, 2 bad input. See docs/batch.md (Slurm arrays, Dask).");
  cmd->add_option("scenario", c->scenario,
                  "scenario YAML file (default: built-in); a relative path not found here is looked for in the installed worlds")
      ->transform(data_file());
  cmd->add_option("--trials,-n", c->trials, "number of trials in the batch (required)")->check(CLI::Range(1, 100000000));
  cmd->add_option("--jobs,-j", c->jobs, "trials at once (default: one per core)")->check(CLI::Range(1, 1024));
  cmd->add_option("--seed", c->seed, "base seed S: trial i uses S+i (default: the scenario's seed)");
  cmd->add_option("--out,-o", c->out, "batch folder (default batches/<scenario name>)");
  cmd->add_option("--shard", c->shard, "run only trials i with i % M == K, given as K/M");
  cmd->add_option("--duration", c->duration, "time limit per trial, s of sim time (default: the scenario's)")->check(CLI::PositiveNumber);
  cmd->add_option("--controller", c->controller, "controller of every robot (default: the scenario's)")
      ->check(CLI::IsMember({"explorer", "wall_follower"}));
  cmd->add_flag("--cameras", c->cameras, "render the cameras (victims then count when seen in thermal images; needs OpenGL, slower)");
  cmd->add_flag("--full-duration", c->full_duration, "run every trial to its time limit, even after all victims are found");
  cmd->add_flag("--retry-failed", c->retry_failed, "run the trials recorded as failed again");
  cmd->add_flag("--threads", c->threads, "run trials in threads of this process instead of child processes (a crash then ends the batch)");
  cmd->add_flag("--quiet,-q", c->quiet, "no progress output");
  CLI::Option* terrain = cmd->add_option("--trial-terrain", c->terrain_world,
                                         "run terrain trials on this arena (an SVG world with terrain elements) instead of a scenario")
                             ->check(CLI::ExistingFile);
  cmd->add_option("--lane", c->terrain.lane, "terrain trials: the element's name (its SVG id), or a kind: the first element of that kind")
      ->needs(terrain);
  cmd->add_option("--robot", c->terrain.robot, "terrain trials: built-in model, tracked_robot or rescue_robot")
      ->capture_default_str()
      ->needs(terrain);
  cmd->add_option("--laps", c->terrain.laps, "terrain trials: laps (crossings back and forth, figure-eights) per trial")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000))
      ->needs(terrain);
  cmd->add_option("--pattern", c->pattern,
                  "terrain trials: laps (each from the start line), back-and-forth (end to end without a reset) or figure-eight (around "
                  "two pylons, stepfields and crossing ramps)")
      ->capture_default_str()
      ->check(CLI::IsMember({"laps", "back-and-forth", "figure-eight"}))
      ->needs(terrain);
  cmd->add_option("--speed", c->terrain.speed, "terrain trials: m/s")->capture_default_str()->check(CLI::Range(0.05, 2.0))->needs(terrain);
  cmd->add_option("--time-limit", c->terrain.time_limit, "terrain trials: s per lap (per crossing)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 3600.0))
      ->needs(terrain);

  CLI::App* merge = cmd->add_subcommand("merge", "Combine the results of several batch folders (shards) into one");
  merge->footer(
      "Every folder must hold trials of the same batch (same scenario and options). The first\n"
      "record of each trial wins; OUT may be one of the folders or hold results already.\n"
      "Writes OUT/results.jsonl in trial order and the summaries.");
  merge->add_option("dirs", m->dirs, "batch folders")->required()->check(CLI::ExistingDirectory);
  merge->add_option("--out,-o", m->out, "folder to write the merged batch to")->required();
  merge->final_callback([m, &action] { action = [m] { return run_merge(*m); }; });
  cmd->final_callback([c, merge, &action] {
    if (!merge->parsed()) action = [c] { return run_batch(*c); };
  });
}

}  // namespace rescuesim::app
