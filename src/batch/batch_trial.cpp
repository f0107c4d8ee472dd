#include "batch/batch_trial.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/rng.h"
#include "session/scenario_load.h"
#include "session/session.h"

namespace rescuesim {

BatchScenario load_batch_scenario(const std::string& file, const ModelMap& models) {
  if (file.empty()) return parse_batch_scenario(default_scenario_text(), "<built-in>", models);
  return parse_batch_scenario(read_file(file, std::size_t(16) << 20), file, models);
}

BatchScenario parse_batch_scenario(const std::string& text, const std::string& file, const ModelMap& models) {
  BatchScenario b;
  b.scenario = parse_scenario(text, file, models);
  b.text = text;
  b.file = file;
  return b;
}

std::string batch_fingerprint(const std::string& scenario_text, const TrialOptions& options) {
  char duration[40] = "scenario";
  if (options.duration) std::snprintf(duration, sizeof duration, "%.17g", *options.duration);
  const std::string key = scenario_text + "\n--\nduration=" + duration + "\ncontroller=" + options.controller +
                          "\ncameras=" + (options.cameras ? "1" : "0") +
                          "\nstop_when_all_found=" + (options.stop_when_all_found ? "1" : "0");
  std::string terrain;
  if (const auto& t = options.terrain) {
    // only terrain batches carry these, so other batches keep their fingerprints
    char numbers[200];
    std::snprintf(numbers, sizeof numbers, "%d %.17g %.17g %.17g %.17g", t->laps, t->speed, t->approach, t->time_limit, t->stuck_time);
    terrain = "\nterrain=" + t->lane + " " + t->robot + " " + terrain_pattern_name(t->pattern) + " " + numbers;
  }
  char out[24];
  std::snprintf(out, sizeof out, "rs1-%016llx", static_cast<unsigned long long>(fnv1a64(key + terrain)));
  return out;
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  Shard s;
  bool ok = slash != std::string::npos && slash > 0 && slash + 1 < text.size();
  if (ok) {
    try {
      std::size_t used = 0;
      s.index = std::stoi(text.substr(0, slash), &used);
      ok = used == slash;
      s.count = std::stoi(text.substr(slash + 1), &used);
      ok = ok && used == text.size() - slash - 1;
    } catch (const std::exception&) {
      ok = false;
    }
  }
  if (!ok || s.count < 1 || s.index < 0 || s.index >= s.count) {
    throw Error("--shard '" + text + "': expected K/M with 0 <= K < M, e.g. 0/4 for the first of four shards");
  }
  return s;
}

std::vector<int> shard_trials(int trials, Shard shard) {
  std::vector<int> out;
  for (int i = shard.index; i < trials; i += shard.count) out.push_back(i);
  return out;
}

Scenario trial_scenario(const Scenario& base, std::uint64_t seed, const TrialOptions& options, const ModelMap& models) {
  Scenario s = base;
  reseed_scenario(s, seed);
  if (options.duration) s.duration = *options.duration;
  if (!std::isfinite(s.duration) || s.duration <= 0) {
    throw Error({base.source_file, 0, "duration"}, "a batch trial needs a finite, positive duration (give --duration)");
  }
  s.realtime = false;
  s.stop_when_all_found = options.stop_when_all_found;
  if (!options.controller.empty()) {
    // the controller applies to every robot, including the world's default ones
    if (s.robots.empty()) s.robots = robot_configs(s, build_world(s), models);
    for (auto& r : s.robots) r.controller = options.controller;
  }
  return s;
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return {};
  return name;
}

TrialRecord failed_trial(const Scenario& base, int trial, std::uint64_t seed, const std::string& batch, const std::string& error) {
  TrialRecord r;
  r.trial = trial;
  r.seed = seed;
  r.batch = batch;
  r.scenario = base.name;
  r.status = "failed";
  r.error = error;
  r.stop_reason = "failed";
  r.host = host_name();
  return r;
}

namespace {

/// A terrain trial (TrialOptions::terrain) on the scenario's world, seeded with the trial's seed.
TrialRecord run_terrain(const Scenario& base, const ModelMap& models, int trial, std::uint64_t seed, const TerrainTrialOptions& options,
                        const std::string& batch) {
  TerrainTrialOptions o = options;
  o.seed = seed;
  const WorldSpec world = build_world(base);
  validate(world).throw_if_errors();
  const TerrainTrialResult r = run_terrain_trial(world, models, o);
  TrialRecord rec;
  rec.trial = trial;
  rec.seed = seed;
  rec.batch = batch;
  rec.scenario = base.name;
  rec.success = r.repetitions == o.laps;
  rec.success_time = rec.success ? r.sim_time : -1;
  // why the trial fell short: the first lap that did not complete (fell, stuck, timeout)
  rec.stop_reason = "all repetitions completed";
  for (const TerrainLap& l : r.laps) {
    if (l.outcome != "completed") {
      rec.stop_reason = l.outcome;
      break;
    }
  }
  rec.sim_time = r.sim_time;
  // the distance along each lap's path (sampled every 0.1 s)
  for (const TerrainLap& l : r.laps) {
    for (std::size_t i = 1; i < l.path.size(); ++i) rec.distance += (l.path[i] - l.path[i - 1]).norm();
  }
  rec.host = host_name();
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(r.state_hash));
  rec.state_hash = hash;
  rec.terrain = TrialTerrain{r.element.name, TerrainSpec::kind_name(r.element.kind), r.robot, terrain_pattern_name(o.pattern),
                             static_cast<int>(r.laps.size()), r.repetitions, r.falls, r.stuck, r.timeouts, r.mean_time};
  return rec;
}

}  // namespace

TrialRecord run_trial(const Scenario& base, const ModelMap& models, int trial, std::uint64_t seed, const TrialOptions& options,
                      const std::string& batch) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  TrialRecord rec;
  try {
    if (options.terrain) {
      rec = run_terrain(base, models, trial, seed, *options.terrain, batch);
      rec.wall_time = std::chrono::duration<double>(clock::now() - t0).count();
      rec.real_time_factor = rec.wall_time > 0 ? rec.sim_time / rec.wall_time : 0;
      return rec;
    }
    const Scenario s = trial_scenario(base, seed, options, models);
    SessionOptions so;
    so.cameras = options.cameras;
    Session session(s, models, so);
    const RunResult r = session.run();
    rec.trial = trial;
    rec.seed = seed;
    rec.batch = batch;
    rec.scenario = s.name;
    rec.stop_reason = r.stop_reason;
    if (r.trouble) {
      rec.status = "failed";
      rec.error = "numerical trouble: " + r.stop_reason;
    }
    rec.victims_total = static_cast<int>(r.victims.size());
    rec.victims_found = r.victims_found;
    double last = 0;
    for (const auto& v : r.victims) {
      rec.victims.push_back({v.name, v.found, v.time});
      if (v.found) last = std::max(last, v.time);
    }
    rec.success = rec.status == "ok" && rec.victims_total > 0 && rec.victims_found == rec.victims_total;
    rec.success_time = rec.success ? last : -1;
    rec.coverage = r.coverage;
    rec.distance = r.distance;
    rec.collisions = r.collisions;
    rec.sim_time = r.sim_time;
    char hash[24];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(r.state_hash));
    rec.state_hash = hash;
    rec.host = host_name();
    if (r.mission) {
      TrialMission m;
      m.score = r.mission->score;
      m.victims_reported = r.mission->victims_found;
      m.false_reports = static_cast<int>(r.mission->counts[ReportOutcome::false_report]);
      for (double c : r.mission->contact_fraction) m.contact_fraction += c / static_cast<double>(r.mission->contact_fraction.size());
      rec.mission = m;
    }
  } catch (const std::exception& e) {
    rec = failed_trial(base, trial, seed, batch, e.what());
  }
  rec.wall_time = std::chrono::duration<double>(clock::now() - t0).count();
  rec.real_time_factor = rec.wall_time > 0 ? rec.sim_time / rec.wall_time : 0;
  return rec;
}

}  // namespace rescuesim
