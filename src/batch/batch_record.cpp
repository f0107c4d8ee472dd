#include "batch/batch_record.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.h"

namespace rescuesim {

namespace {

using json = nlohmann::ordered_json;

/// A time that may be missing: null in JSON.
json optional_time(double t) { return t >= 0 ? json(t) : json(); }

/// A finite number for JSON (NaN and infinities become 0 rather than null).
double finite_or_zero(double v) { return std::isfinite(v) ? v : 0.0; }

const json& key(const json& j, const char* name) {
  const auto it = j.find(name);
  if (it == j.end()) throw Error(std::string("key \"") + name + "\" is missing");
  return *it;
}

double number(const json& j, const char* name) {
  const json& v = key(j, name);
  if (!v.is_number()) throw Error(std::string("key \"") + name + "\" should be a number");
  return v.get<double>();
}

double time_or_none(const json& j, const char* name) {
  const json& v = key(j, name);
  if (v.is_null()) return -1;
  if (!v.is_number() || v.get<double>() < 0) throw Error(std::string("key \"") + name + "\" should be a time >= 0 or null");
  return v.get<double>();
}

std::int64_t integer(const json& j, const char* name, std::int64_t lo) {
  const json& v = key(j, name);
  if (!v.is_number_integer() || v.get<std::int64_t>() < lo) {
    throw Error(std::string("key \"") + name + "\" should be an integer >= " + std::to_string(lo));
  }
  return v.get<std::int64_t>();
}

std::string text(const json& j, const char* name, bool nullable = false) {
  const json& v = key(j, name);
  if (nullable && v.is_null()) return {};
  if (!v.is_string()) throw Error(std::string("key \"") + name + "\" should be a string");
  return v.get<std::string>();
}

bool flag(const json& j, const char* name) {
  const json& v = key(j, name);
  if (!v.is_boolean()) throw Error(std::string("key \"") + name + "\" should be true or false");
  return v.get<bool>();
}

}  // namespace

std::string to_json_line(const TrialRecord& r) {
  json j;
  j["trial"] = r.trial;
  j["seed"] = r.seed;
  j["batch"] = r.batch;
  j["scenario"] = r.scenario;
  j["status"] = r.status;
  j["error"] = r.error.empty() ? json() : json(r.error);
  j["success"] = r.success;
  j["success_time_s"] = optional_time(r.success_time);
  j["stop_reason"] = r.stop_reason;
  j["victims_total"] = r.victims_total;
  j["victims_found"] = r.victims_found;
  auto& victims = j["victims"] = json::array();
  for (const auto& v : r.victims) victims.push_back({{"name", v.name}, {"found", v.found}, {"time_s", optional_time(v.time)}});
  j["coverage"] = finite_or_zero(r.coverage);
  j["distance_m"] = finite_or_zero(r.distance);
  j["collisions"] = r.collisions;
  j["sim_time_s"] = finite_or_zero(r.sim_time);
  j["wall_time_s"] = finite_or_zero(r.wall_time);
  j["real_time_factor"] = finite_or_zero(r.real_time_factor);
  j["state_hash"] = r.state_hash;
  j["host"] = r.host;
  if (r.mission) {
    j["mission"] = {{"score", finite_or_zero(r.mission->score)}, {"victims_reported", r.mission->victims_reported},
                    {"false_reports", r.mission->false_reports}, {"contact_fraction", finite_or_zero(r.mission->contact_fraction)}};
  } else {
    j["mission"] = json();
  }
  // a terrain trial's counts; left out of other trials' lines, so that those read as before
  if (r.terrain) {
    const TrialTerrain& t = *r.terrain;
    j["terrain"] = {{"lane", t.lane},           {"kind", t.kind},   {"robot", t.robot},   {"pattern", t.pattern},
                    {"laps", t.laps},           {"repetitions", t.repetitions},           {"falls", t.falls},
                    {"stuck", t.stuck},         {"timeouts", t.timeouts},                 {"mean_time_s", finite_or_zero(t.mean_time)}};
  }
  // one line: dump() without indentation never emits a newline (strings are escaped)
  return j.dump(-1, ' ', false, json::error_handler_t::replace) + "\n";
}

TrialRecord parse_trial_line(std::string_view line) {
  json j;
  try {
    j = json::parse(line.begin(), line.end());
  } catch (const json::exception& e) {  // parse_error, and out_of_range for numbers like 7E888
    throw Error(std::string("not valid JSON (") + e.what() + ")");
  }
  if (!j.is_object()) throw Error("not a JSON object");
  TrialRecord r;
  r.trial = static_cast<int>(integer(j, "trial", 0));
  const json& seed = key(j, "seed");
  if (!seed.is_number_unsigned() && !(seed.is_number_integer() && seed.get<std::int64_t>() >= 0)) {
    throw Error("key \"seed\" should be an integer >= 0");
  }
  r.seed = seed.get<std::uint64_t>();
  r.batch = text(j, "batch");
  r.scenario = text(j, "scenario");
  r.status = text(j, "status");
  if (r.status != "ok" && r.status != "failed") throw Error("key \"status\" should be \"ok\" or \"failed\", not \"" + r.status + "\"");
  r.error = text(j, "error", true);
  r.success = flag(j, "success");
  r.success_time = time_or_none(j, "success_time_s");
  r.stop_reason = text(j, "stop_reason");
  r.victims_total = static_cast<int>(integer(j, "victims_total", 0));
  r.victims_found = static_cast<int>(integer(j, "victims_found", 0));
  const json& victims = key(j, "victims");
  if (!victims.is_array()) throw Error("key \"victims\" should be an array");
  for (const json& v : victims) {
    if (!v.is_object()) throw Error("key \"victims\" should hold objects");
    r.victims.push_back({text(v, "name"), flag(v, "found"), time_or_none(v, "time_s")});
  }
  r.coverage = number(j, "coverage");
  r.distance = number(j, "distance_m");
  r.collisions = static_cast<int>(integer(j, "collisions", 0));
  r.sim_time = number(j, "sim_time_s");
  r.wall_time = number(j, "wall_time_s");
  r.real_time_factor = number(j, "real_time_factor");
  r.state_hash = text(j, "state_hash");
  r.host = text(j, "host");
  // "mission" came later: files without the key are read as trials without a mission
  if (j.contains("mission") && !j["mission"].is_null()) {
    const json& m = j["mission"];
    if (!m.is_object()) throw Error("key \"mission\" should be an object or null");
    TrialMission tm;
    tm.score = number(m, "score");
    tm.victims_reported = static_cast<int>(integer(m, "victims_reported", 0));
    tm.false_reports = static_cast<int>(integer(m, "false_reports", 0));
    tm.contact_fraction = number(m, "contact_fraction");
    if (tm.contact_fraction < 0 || tm.contact_fraction > 1) throw Error("mission.contact_fraction should lie in [0, 1]");
    r.mission = tm;
  }
  if (j.contains("terrain") && !j["terrain"].is_null()) {
    const json& t = j["terrain"];
    if (!t.is_object()) throw Error("key \"terrain\" should be an object or null");
    TrialTerrain tt;
    tt.lane = text(t, "lane");
    tt.kind = text(t, "kind");
    tt.robot = text(t, "robot");
    tt.pattern = text(t, "pattern");
    tt.laps = static_cast<int>(integer(t, "laps", 0));
    tt.repetitions = static_cast<int>(integer(t, "repetitions", 0));
    tt.falls = static_cast<int>(integer(t, "falls", 0));
    tt.stuck = static_cast<int>(integer(t, "stuck", 0));
    tt.timeouts = static_cast<int>(integer(t, "timeouts", 0));
    tt.mean_time = number(t, "mean_time_s");
    if (tt.repetitions > tt.laps) throw Error("terrain.repetitions exceeds terrain.laps");
    r.terrain = tt;
  }
  if (r.victims_found > r.victims_total) throw Error("victims_found exceeds victims_total");
  if (r.coverage < 0 || r.coverage > 1) throw Error("coverage should lie in [0, 1]");
  return r;
}

bool same_outcome(const TrialRecord& a, const TrialRecord& b) {
  return a.trial == b.trial && a.seed == b.seed && a.batch == b.batch && a.scenario == b.scenario && a.status == b.status &&
         a.error == b.error && a.success == b.success && a.success_time == b.success_time && a.stop_reason == b.stop_reason &&
         a.victims_total == b.victims_total && a.victims_found == b.victims_found && a.victims == b.victims &&
         a.coverage == b.coverage && a.distance == b.distance && a.collisions == b.collisions && a.sim_time == b.sim_time &&
         a.state_hash == b.state_hash && a.mission == b.mission && a.terrain == b.terrain;
}

}  // namespace rescuesim
