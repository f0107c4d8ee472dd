#include "batch/batch_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"

namespace rescuesim {

namespace {

using json = nlohmann::ordered_json;

json stat_json(const Stat& s) {
  return {{"n", s.n}, {"mean", s.mean}, {"stddev", s.stddev}, {"min", s.min}, {"median", s.median}, {"max", s.max}};
}

/// A CSV field: quoted when it holds a comma, quote or line break.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string num(double v, const char* format = "%.6g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

}  // namespace

Stat stat_of(std::vector<double> v) {
  Stat s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / s.n;
  double sq = 0;
  for (double x : v) sq += (x - s.mean) * (x - s.mean);
  s.stddev = s.n > 1 ? std::sqrt(sq / (s.n - 1)) : 0.0;
  s.min = v.front();
  s.max = v.back();
  s.median = s.n % 2 ? v[static_cast<std::size_t>(s.n / 2)]
                     : 0.5 * (v[static_cast<std::size_t>(s.n / 2 - 1)] + v[static_cast<std::size_t>(s.n / 2)]);
  return s;
}

std::string batch_summary_json(const std::map<int, TrialRecord>& records, const BatchRunInfo& run) {
  json j;
  const TrialRecord* first = records.empty() ? nullptr : &records.begin()->second;
  j["scenario"] = first ? first->scenario : "";
  j["batch"] = first ? first->batch : "";
  j["base_seed"] = first ? first->seed - static_cast<std::uint64_t>(first->trial) : 0;
  int ok = 0, failed = 0, successes = 0, victims = 0, found = 0;
  std::vector<double> success_times, victims_found, coverage, distance, collisions, sim_time, wall_time, rtf;
  std::vector<double> score, reported, false_reports, contact;  // trials with a mission
  std::vector<double> repetitions, rep_time;                   // terrain trials
  int laps = 0, reps = 0, falls = 0, stuck = 0, timeouts = 0;
  json failures = json::array();
  for (const auto& [trial, r] : records) {
    wall_time.push_back(r.wall_time);
    if (r.status != "ok") {
      ++failed;
      failures.push_back({{"trial", trial}, {"seed", r.seed}, {"error", r.error}});
      continue;
    }
    ++ok;
    successes += r.success;
    if (r.success) success_times.push_back(r.success_time);
    victims += r.victims_total;
    found += r.victims_found;
    victims_found.push_back(r.victims_found);
    coverage.push_back(r.coverage);
    distance.push_back(r.distance);
    collisions.push_back(r.collisions);
    sim_time.push_back(r.sim_time);
    rtf.push_back(r.real_time_factor);
    if (r.mission) {
      score.push_back(r.mission->score);
      reported.push_back(r.mission->victims_reported);
      false_reports.push_back(r.mission->false_reports);
      contact.push_back(r.mission->contact_fraction);
    }
    if (r.terrain) {
      repetitions.push_back(r.terrain->repetitions);
      if (r.terrain->repetitions > 0) rep_time.push_back(r.terrain->mean_time);
      laps += r.terrain->laps;
      reps += r.terrain->repetitions;
      falls += r.terrain->falls;
      stuck += r.terrain->stuck;
      timeouts += r.terrain->timeouts;
    }
  }
  const int n = static_cast<int>(records.size());
  j["trials"] = n;
  j["trials_ok"] = ok;
  j["trials_failed"] = failed;
  j["successes"] = successes;
  j["success_rate"] = n > 0 ? static_cast<double>(successes) / n : 0.0;
  j["victims_total"] = victims;
  j["victims_found"] = found;
  j["victim_find_rate"] = victims > 0 ? static_cast<double>(found) / victims : 0.0;
  j["note"] = "statistics are over the trials that ran (status ok); wall time is over all trials";
  j["success_time_s"] = stat_json(stat_of(success_times));
  j["victims_found_per_trial"] = stat_json(stat_of(victims_found));
  j["coverage"] = stat_json(stat_of(coverage));
  j["distance_m"] = stat_json(stat_of(distance));
  j["collisions"] = stat_json(stat_of(collisions));
  j["sim_time_s"] = stat_json(stat_of(sim_time));
  j["wall_time_s"] = stat_json(stat_of(wall_time));
  j["real_time_factor"] = stat_json(stat_of(rtf));
  if (!score.empty()) {
    j["mission"] = {{"trials", score.size()},
                    {"score", stat_json(stat_of(score))},
                    {"victims_reported", stat_json(stat_of(reported))},
                    {"false_reports", stat_json(stat_of(false_reports))},
                    {"contact_fraction", stat_json(stat_of(contact))},
                    {"per_seed", json::array()}};
    for (const auto& [trial, r] : records) {
      if (r.status == "ok" && r.mission) {
        j["mission"]["per_seed"].push_back({{"trial", trial}, {"seed", r.seed}, {"score", r.mission->score}});
      }
    }
  }
  if (!repetitions.empty()) {
    // terrain trials (rescuesim batch --trial-terrain): a success is a trial with every repetition completed
    j["terrain"] = {{"trials", repetitions.size()},
                    {"laps", laps},
                    {"repetitions", reps},
                    {"repetition_rate", laps > 0 ? static_cast<double>(reps) / laps : 0.0},
                    {"falls", falls},
                    {"stuck", stuck},
                    {"timeouts", timeouts},
                    {"repetitions_per_trial", stat_json(stat_of(repetitions))},
                    {"mean_time_per_repetition_s", stat_json(stat_of(rep_time))}};
  }
  if (run.trials_run > 0 && run.wall_time > 0) {
    j["run"] = {{"jobs", run.jobs}, {"trials", run.trials_run}, {"wall_time_s", run.wall_time},
                {"trials_per_hour", run.trials_run / run.wall_time * 3600.0}};
  }
  j["failures"] = failures;
  return j.dump(2) + "\n";
}

std::string batch_summary_csv(const std::map<int, TrialRecord>& records) {
  std::string out =
      "trial,seed,status,success,success_time_s,victims_found,victims_total,coverage,distance_m,collisions,sim_time_s,wall_time_s,"
      "real_time_factor,stop_reason,state_hash,host,error,mission_score,victims_reported,false_reports\n";
  for (const auto& [trial, r] : records) {
    out += std::to_string(trial) + "," + std::to_string(r.seed) + "," + r.status + "," + (r.success ? "true" : "false") + "," +
           (r.success_time >= 0 ? num(r.success_time, "%.3f") : std::string()) + "," + std::to_string(r.victims_found) + "," +
           std::to_string(r.victims_total) + "," + num(r.coverage, "%.4f") + "," + num(r.distance, "%.3f") + "," +
           std::to_string(r.collisions) + "," + num(r.sim_time, "%.3f") + "," + num(r.wall_time, "%.3f") + "," +
           num(r.real_time_factor, "%.2f") + "," + csv_field(r.stop_reason) + "," + r.state_hash + "," + csv_field(r.host) + "," +
           csv_field(r.error) + "," + (r.mission ? num(r.mission->score, "%g") + "," + std::to_string(r.mission->victims_reported) + "," +
                                                      std::to_string(r.mission->false_reports)
                                                : std::string(",,")) +
           "\n";
  }
  return out;
}

void write_batch_summary(const std::filesystem::path& dir, const std::map<int, TrialRecord>& records, const BatchRunInfo& run) {
  write_file_atomic(dir / "summary.json", batch_summary_json(records, run));
  write_file_atomic(dir / "summary.csv", batch_summary_csv(records));
  batch_figure(records).write_png(dir / "summary.png");
}

}  // namespace rescuesim
