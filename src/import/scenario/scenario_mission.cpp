#include "import/scenario/scenario_mission.h"

#include <cmath>
#include <limits>

#include "core/error.h"

namespace rescuesim {

namespace {

/// Every model's parameter names (set_radio_parameter refuses those of another model).
constexpr const char* kRadioParameters[] = {"p0_dbm",       "d0_m",         "n",         "wall_loss_db",   "max_walls",
                                            "cutoff_dbm",   "l0_db",        "sigma_db",  "tx_power_dbm",   "noise_floor_dbm",
                                            "capacity_bps", "max_range_m",  "max_datagram_bytes"};

MissionRadioSpec read_radio(const YamlNode& r) {
  MissionRadioSpec out;
  const std::string model = r.choice("model", "ideal", {"ideal", "wss", "subt"});
  out.model = radio_model(model);
  out.link_rate_hz = r.number("link_rate", out.link_rate_hz, 0.1, 1000);
  out.relays_per_robot = static_cast<int>(r.integer("relays_per_robot", out.relays_per_robot, 0, 10000));
  out.antenna_height_m = r.number("antenna_height", out.antenna_height_m, 0, 100);
  for (const char* key : kRadioParameters) {
    if (!r.has(key)) continue;
    const double value = r.number(key, 0, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
    if (const auto why = set_radio_parameter(out.model, key, value)) throw Error(r.where(key), *why);
  }
  r.finish();
  const auto problems = validate_radio_model(out.model);
  if (!problems.empty()) {
    std::string text = "impossible radio parameters:";
    for (const auto& p : problems) text += "\n  " + p;
    throw Error(r.where(), text);
  }
  return out;
}

BaseStationSpec read_base(const YamlNode& b, const std::string& fallback_name) {
  BaseStationSpec out;
  out.name = b.string("name", fallback_name);
  if (out.name.empty() || out.name.find_first_of("/ ") != std::string::npos) {
    throw Error(b.where("name"), "base name '" + out.name + "' must be a plain word (it names a radio)");
  }
  out.p_W = {b.required_number("x", -1e6, 1e6), b.required_number("y", -1e6, 1e6), b.number("z", 1.0, -1e4, 1e4)};
  b.finish();
  return out;
}

}  // namespace

MissionSpec read_mission(const YamlNode& m) {
  MissionSpec s;
  const std::string preset = m.choice("rules", "robocup", {"robocup", "subt"});
  s.rules = mission_rules(preset);
  MissionRules& r = s.rules;
  r.report_radius_m = m.number("report_radius", r.report_radius_m, 1e-3, 1e4);
  r.victim_points = m.number("victim_points", r.victim_points, 0, 1e6);
  r.false_report_penalty = m.number("false_report_penalty", r.false_report_penalty, 0, 1e6);
  r.report_limit = static_cast<int>(m.integer("report_limit", r.report_limit, 0, 1000000));
  r.time_limit_s = m.number("time_limit", r.time_limit_s, 0, 1e7);
  r.report_rate_hz = m.number("report_rate", r.report_rate_hz, 1e-3, 1e6);
  r.require_contact = m.boolean("require_contact", r.require_contact);
  s.radio = read_radio(m.map("radio"));
  if (m.has("base") && m.has("bases")) throw Error(m.where("bases"), "give mission.base or mission.bases, not both");
  if (m.has("base")) s.bases.push_back(read_base(m.map("base"), "base"));
  const auto bases = m.sequence("bases");
  for (std::size_t i = 0; i < bases.size(); ++i) {
    s.bases.push_back(read_base(bases[i], "base" + std::to_string(i + 1)));
    for (std::size_t k = 0; k < i; ++k) {
      if (s.bases[k].name == s.bases[i].name) throw Error(bases[i].where("name"), "two bases are named '" + s.bases[i].name + "'");
    }
  }
  m.finish();
  return s;
}

}  // namespace rescuesim
