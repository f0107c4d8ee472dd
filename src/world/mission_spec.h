#pragma once
/// A rescue mission as authored (a scenario's `mission:` block): the referee's rules for victim
/// reports, the radio link model between robots, base stations and relays, and where the base
/// stations stand. Plain data; the referee (mission/referee.h) and the radio network
/// (radio/radio_network.h) act on it. See docs/missions.md for the rules beside RoboCup's and
/// SubT's.

#include <cstdint>
#include <string>
#include <vector>

#include "core/pose.h"
#include "world/radio_model.h"

namespace rescuesim {

/// How victim reports are judged and scored.
struct MissionRules {
  std::string preset = "robocup";   ///< the rule set the values started from: robocup or subt
  double report_radius_m = 1.5;     ///< a report finds a victim within this distance (RoboCup 1.5 m, SubT 5 m)
  double victim_points = 1.0;       ///< score for each victim found
  double false_report_penalty = 0.5;  ///< score taken for a report near no victim (RoboCup VRC 0.5, SubT 0)
  int report_limit = 0;             ///< reports judged at most (accepted, duplicate or false; SubT 40); 0: no limit
  double time_limit_s = 0;          ///< reports after this sim time are refused; 0: until the run ends
  double report_rate_hz = 2.0;      ///< per robot; reports closer together than 1/rate are refused and counted
  bool require_contact = true;      ///< a report counts only with a radio route to a base at that moment
};

/// The rules a preset name gives: "robocup" (1.5 m, 0.5 per false report, no limit) or "subt"
/// (5 m, no penalty, 40 reports). Throws Error naming the accepted names for any other.
MissionRules mission_rules(const std::string& preset);

/// An operator base station: a radio that never moves, where reports are received.
struct BaseStationSpec {
  std::string name = "base";
  Vec3 p_W = Vec3::Zero();          ///< antenna position, world frame (m)
};

/// The radios of a mission.
struct MissionRadioSpec {
  RadioModel model;                 ///< ideal unless the scenario names another
  double link_rate_hz = 10;         ///< how often links are recomputed (Hz)
  int relays_per_robot = 12;        ///< relays each robot may drop (SubT gave 12)
  double antenna_height_m = 0.5;    ///< robots' antennas above their base frame (m)
};

/// A scenario's mission.
struct MissionSpec {
  MissionRules rules;
  MissionRadioSpec radio;
  /// Base stations; empty means one, "base", 1 m above the first robot's start.
  std::vector<BaseStationSpec> bases;
};

}  // namespace rescuesim
