#include "mission/referee.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.h"

namespace rescuesim {

namespace {

constexpr double kRepeatTolerance = 0.01;  // m: a report this close to an earlier one of the same robot repeats it

}  // namespace

std::string_view report_outcome_name(ReportOutcome outcome) {
  switch (outcome) {
    case ReportOutcome::accepted: return "accepted";
    case ReportOutcome::duplicate: return "duplicate";
    case ReportOutcome::false_report: return "false";
    case ReportOutcome::repeat: return "repeat";
    case ReportOutcome::out_of_contact: return "out_of_contact";
    case ReportOutcome::limit_reached: return "limit_reached";
    case ReportOutcome::rate_limited: return "rate_limited";
    case ReportOutcome::time_over: return "time_over";
    case ReportOutcome::invalid: return "invalid";
  }
  return "invalid";
}

Referee::Referee(MissionRules rules, std::vector<RefereeVictim> victims, int robots)
    : rules_(std::move(rules)), victims_(std::move(victims)), states_(victims_.size()), robots_(robots),
      last_report_ns_(static_cast<std::size_t>(std::max(robots, 0)), std::numeric_limits<std::int64_t>::min()) {
  std::string problems;
  const auto need = [&](bool ok, const std::string& what) {
    if (!ok) problems += (problems.empty() ? "" : "; ") + what;
  };
  need(std::isfinite(rules_.report_radius_m) && rules_.report_radius_m > 0,
       fmt::format("report_radius must be > 0 m, not {}", rules_.report_radius_m));
  need(std::isfinite(rules_.report_rate_hz) && rules_.report_rate_hz > 0,
       fmt::format("report_rate must be > 0 Hz, not {}", rules_.report_rate_hz));
  need(std::isfinite(rules_.victim_points) && rules_.victim_points >= 0,
       fmt::format("victim_points must be >= 0, not {}", rules_.victim_points));
  need(std::isfinite(rules_.false_report_penalty) && rules_.false_report_penalty >= 0,
       fmt::format("false_report_penalty must be >= 0, not {}", rules_.false_report_penalty));
  need(rules_.report_limit >= 0, fmt::format("report_limit must be >= 0, not {}", rules_.report_limit));
  need(std::isfinite(rules_.time_limit_s) && rules_.time_limit_s >= 0,
       fmt::format("time_limit must be >= 0 s, not {}", rules_.time_limit_s));
  need(robots >= 0, fmt::format("robot count must be >= 0, not {}", robots));
  for (const auto& v : victims_) need(v.p_W.allFinite(), "victim '" + v.name + "' has a position that is not finite");
  if (!problems.empty()) throw Error("mission rules: " + problems);
}

int Referee::reports_left() const {
  if (rules_.report_limit == 0) return -1;
  return std::max(0, rules_.report_limit - static_cast<int>(counts_.charged));
}

ReportReply Referee::judge(const VictimReport& report) {
  ReportReply r;
  r.id = next_id_++;
  const auto finish = [&](ReportOutcome outcome, std::string message) {
    r.outcome = outcome;
    r.message = std::move(message);
    r.score = score_;
    r.reports_left = reports_left();
    ++counts_.by_outcome[static_cast<int>(outcome)];
    return r;
  };
  if (!report.robot.valid() || report.robot.value() >= robots_) {
    return finish(ReportOutcome::invalid, fmt::format("no robot {} (there are {})", report.robot.value(), robots_));
  }
  if (!report.p_W.allFinite()) {
    return finish(ReportOutcome::invalid,
                  fmt::format("position ({}, {}, {}) is not finite", report.p_W.x(), report.p_W.y(), report.p_W.z()));
  }
  const double t = report.time.seconds();
  if (rules_.time_limit_s > 0 && t > rules_.time_limit_s) {
    return finish(ReportOutcome::time_over, fmt::format("the mission ended at {:.1f} s", rules_.time_limit_s));
  }
  std::int64_t& last = last_report_ns_[report.robot.slot()];
  const auto min_gap = static_cast<std::int64_t>(std::llround(1e9 / rules_.report_rate_hz));
  if (last != std::numeric_limits<std::int64_t>::min() && report.time.ns - last < min_gap) {
    return finish(ReportOutcome::rate_limited, fmt::format("at most {:g} reports per second per robot", rules_.report_rate_hz));
  }
  last = report.time.ns;
  if (rules_.require_contact && !report.in_contact) {
    return finish(ReportOutcome::out_of_contact, "no radio route to a base: report again when in contact");
  }
  for (const auto& c : charged_) {
    if (c.robot == report.robot && (c.p_W - report.p_W).norm() <= kRepeatTolerance) {
      return finish(ReportOutcome::repeat, "this robot reported this position before");
    }
  }
  if (rules_.report_limit > 0 && counts_.charged >= static_cast<std::uint64_t>(rules_.report_limit)) {
    return finish(ReportOutcome::limit_reached, fmt::format("all {} reports are used", rules_.report_limit));
  }

  // the nearest unfound victim within the radius; else the nearest found one (a duplicate)
  VictimIndex unfound, found;
  double d_unfound = std::numeric_limits<double>::infinity(), d_found = d_unfound;
  for (std::size_t i = 0; i < victims_.size(); ++i) {
    const double d = (victims_[i].p_W - report.p_W).norm();
    if (d > rules_.report_radius_m) continue;
    if (!states_[i].found && d < d_unfound) d_unfound = d, unfound = VictimIndex::at(i);
    if (states_[i].found && d < d_found) d_found = d, found = VictimIndex::at(i);
  }
  ++counts_.charged;
  charged_.push_back({report.robot, report.p_W});
  ScoreEvent e;
  e.t = t;
  e.robot = report.robot;
  if (unfound.valid()) {
    RefereeVictimState& v = states_[unfound.slot()];
    v.found = true;
    v.time = t;
    v.by = report.robot;
    v.error_m = d_unfound;
    ++found_;
    score_ += rules_.victim_points;
    r.victim = unfound;
    r.distance_m = d_unfound;
    r.score_change = rules_.victim_points;
    e.outcome = ReportOutcome::accepted;
    e.victim = unfound;
    e.score = score_;
    timeline_.push_back(e);
    return finish(ReportOutcome::accepted, fmt::format("found victim '{}' {:.2f} m away", victims_[unfound.slot()].name, d_unfound));
  }
  if (found.valid()) {
    r.victim = found;
    r.distance_m = d_found;
    e.outcome = ReportOutcome::duplicate;
    e.victim = found;
    e.score = score_;
    timeline_.push_back(e);
    return finish(ReportOutcome::duplicate,
                  fmt::format("victim '{}' ({:.2f} m away) was found already", victims_[found.slot()].name, d_found));
  }
  score_ -= rules_.false_report_penalty;
  r.score_change = -rules_.false_report_penalty;
  e.outcome = ReportOutcome::false_report;
  e.score = score_;
  timeline_.push_back(e);
  return finish(ReportOutcome::false_report, fmt::format("no victim within {:g} m", rules_.report_radius_m));
}

}  // namespace rescuesim
