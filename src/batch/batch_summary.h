#pragma once
/// What a batch amounts to: `summary.json` (success rate, statistics of every figure, the
/// failures), `summary.csv` (one row per trial) and `summary.png` (success against time and
/// histograms), written from the records of results.jsonl.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "batch/batch_record.h"
#include "viz/canvas.h"

namespace rescuesim {

/// Statistics of one figure over trials.
struct Stat {
  int n = 0;
  double mean = 0, stddev = 0, min = 0, median = 0, max = 0;
};

/// Statistics of `values` (n = 0 and zeros when empty; stddev is the sample standard deviation).
Stat stat_of(std::vector<double> values);

/// How the batch run that writes a summary went (optional parts of summary.json).
struct BatchRunInfo {
  int jobs = 0;              ///< 0: not known (merge, Dask)
  int trials_run = 0;        ///< trials recorded by this run
  double wall_time = 0;      ///< s this run took
};

/// The summary as JSON text (pretty-printed).
std::string batch_summary_json(const std::map<int, TrialRecord>& records, const BatchRunInfo& run = {});

/// The per-trial table: a header row and one row per trial in trial order.
std::string batch_summary_csv(const std::map<int, TrialRecord>& records);

/// The figure: success rate against sim time (and the mean fraction of victims found), and
/// histograms of victims found, coverage, collisions and real-time factor.
Canvas batch_figure(const std::map<int, TrialRecord>& records);

/// Writes summary.json, summary.csv and summary.png into `dir` (each atomically).
void write_batch_summary(const std::filesystem::path& dir, const std::map<int, TrialRecord>& records, const BatchRunInfo& run = {});

}  // namespace rescuesim
