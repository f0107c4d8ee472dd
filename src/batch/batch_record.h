#pragma once
/// One trial of a batch as it is recorded: a line of JSON in `results.jsonl`. The same line
/// format is written by `rescuesim batch`, by the Python API and by the Dask runner, so that
/// resume and `rescuesim batch merge` treat them alike (docs/batch.md lists every key).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rescuesim {

/// A victim as one trial saw it.
struct TrialVictim {
  std::string name;
  bool found = false;
  double time = -1;  ///< s of sim time when first seen; -1 when never
  bool operator==(const TrialVictim&) const = default;
};

/// A trial's mission score (scenarios with a `mission:` block).
struct TrialMission {
  double score = 0;
  int victims_reported = 0;     ///< accepted by the referee
  int false_reports = 0;
  double contact_fraction = 0;  ///< mean over the robots: share of link updates in contact with a base

  bool operator==(const TrialMission&) const = default;
};

/// A terrain trial's counts (batches of `--trial-terrain`; docs/terrain.md, "Trials").
struct TrialTerrain {
  std::string lane, kind, robot, pattern;
  int laps = 0;                 ///< laps (or crossings) driven
  int repetitions = 0;          ///< of them completed
  int falls = 0, stuck = 0, timeouts = 0;
  double mean_time = 0;         ///< s per completed repetition (0: none)

  bool operator==(const TrialTerrain&) const = default;
};

/// What one trial did.
struct TrialRecord {
  int trial = -1;               ///< index in the batch (0-based)
  std::uint64_t seed = 0;       ///< run seed of the trial: maze and every noise stream
  std::string batch;            ///< fingerprint of the batch it belongs to (batch_fingerprint)
  std::string scenario;         ///< scenario name
  std::string status = "ok";    ///< "ok", or "failed": the trial could not run to its end (bad world, crash, numerical trouble)
  std::string error;            ///< why it failed ("" when ok)
  bool success = false;         ///< status ok and every victim found
  double success_time = -1;     ///< s of sim time when the last victim was found; -1 unless success
  std::string stop_reason;      ///< "duration", "all victims found", or the trouble message
  int victims_total = 0;
  int victims_found = 0;
  std::vector<TrialVictim> victims;
  double coverage = 0;          ///< fraction of free floor passed within 1 m of
  double distance = 0;          ///< m driven (ground truth, all robots)
  int collisions = 0;           ///< contacts begun with walls, obstacles, victims, robots
  double sim_time = 0;          ///< s simulated
  double wall_time = 0;         ///< s the trial took, building its world included
  double real_time_factor = 0;  ///< sim_time / wall_time
  std::string state_hash;       ///< 16 hex digits: hash of the final State ("" when none)
  std::string host;             ///< machine that ran it
  std::optional<TrialMission> mission;  ///< the referee's figures; none without a mission (key "mission": null)
  std::optional<TrialTerrain> terrain;  ///< a terrain trial's counts; none for a scenario run (key "terrain" left out)
};

/// The record as one line of JSON (keys in a fixed order, ending in '\n').
std::string to_json_line(const TrialRecord& record);

/// Parses one line of results.jsonl. Throws Error saying what is wrong (not JSON, a key
/// missing or of the wrong type, an impossible value) for a corrupt line.
TrialRecord parse_trial_line(std::string_view line);

/// True when two records tell the same outcome: every field equal except wall time, real-time
/// factor and host (those depend on the machine). Used by determinism tests and by merge.
bool same_outcome(const TrialRecord& a, const TrialRecord& b);

}  // namespace rescuesim
