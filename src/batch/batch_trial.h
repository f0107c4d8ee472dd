#pragma once
/// A batch's plan and its trials: trial i of a batch with base seed S runs the scenario with
/// run seed S + i (the maze and every noise stream), headless, in lockstep, with the built-in
/// controllers, until every victim is found or the time limit. A trial never throws: whatever
/// goes wrong is recorded in its TrialRecord.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "batch/batch_record.h"
#include "import/scenario/scenario.h"
#include "session/terrain_trial.h"

namespace rescuesim {

/// How every trial of a batch runs, beyond its scenario.
struct TrialOptions {
  std::optional<double> duration;   ///< s of sim time (time limit); default: the scenario's
  std::string controller;           ///< explorer or wall_follower for every robot; "" keeps the scenario's
  bool cameras = false;             ///< render the camera sensors (victims then count when seen in thermal images)
  bool stop_when_all_found = true;  ///< end a trial once every victim is found (else run to the time limit)
  /// A terrain trial (docs/terrain.md, "Trials") on the scenario's world instead of its run:
  /// trial i drives the lane with seed S + i; success is every repetition completed.
  std::optional<TerrainTrialOptions> terrain;
};

/// A batch's scenario with the text it came from (the text is part of the batch's fingerprint).
struct BatchScenario {
  Scenario scenario;
  std::string text;  ///< the YAML as read
  std::string file;  ///< the path as given, or "<built-in>"
};

/// Reads a scenario file, or the built-in default when `file` is empty. Throws Error for bad input.
BatchScenario load_batch_scenario(const std::string& file, const ModelMap& models);
/// A scenario from YAML text; `file` names it in messages and resolves relative paths.
BatchScenario parse_batch_scenario(const std::string& text, const std::string& file, const ModelMap& models);

/// Identifies a batch: "rs1-" and 16 hex digits hashed from the scenario text and the trial
/// options. Trials of different batches are never mixed in one results file.
std::string batch_fingerprint(const std::string& scenario_text, const TrialOptions& options);

/// Which trials a process runs: every `count`-th trial starting at `index` (0 <= index < count).
struct Shard {
  int index = 0;
  int count = 1;
};

/// Parses "K/M"; throws Error explaining the form for anything else.
Shard parse_shard(const std::string& text);

/// The trials of a shard among `trials`, in order.
std::vector<int> shard_trials(int trials, Shard shard);

/// The run seed of trial `trial` in a batch with base seed `base_seed`.
inline std::uint64_t trial_seed(std::uint64_t base_seed, int trial) { return base_seed + static_cast<std::uint64_t>(trial); }

/// The scenario one trial runs: `base` reseeded with `seed` (also the maze's seed), with the
/// options' duration, controller and stop rule applied, in lockstep.
Scenario trial_scenario(const Scenario& base, std::uint64_t seed, const TrialOptions& options, const ModelMap& models);

/// Runs one trial in this process and records it; never throws (a trial that cannot run is
/// recorded as failed with its error). `batch` is the fingerprint written into the record.
TrialRecord run_trial(const Scenario& base, const ModelMap& models, int trial, std::uint64_t seed, const TrialOptions& options,
                      const std::string& batch);

/// A failed record for a trial that produced none (its process crashed, say).
TrialRecord failed_trial(const Scenario& base, int trial, std::uint64_t seed, const std::string& batch, const std::string& error);

/// This machine's host name ("" when unknown).
std::string host_name();

}  // namespace rescuesim
