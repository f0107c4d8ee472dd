#pragma once
/// The referee of a rescue mission: judges victim reports against the ground truth under a
/// scenario's MissionRules, keeps the score and its timeline. Pure logic on plain data (no
/// Bus, no radio): the caller says whether the reporter had a route to a base.
///
/// A report is judged in this order (the first that applies decides):
///   invalid         position not finite, or robot index unknown    (not counted, no score)
///   time_over       after the rules' time limit                     (not counted)
///   rate_limited    sooner than 1/report_rate after the same robot's previous report that was
///                   neither invalid nor rate limited itself (not charged; counted apart)
///   out_of_contact  no route to a base while the rules require one  (not counted; retry later)
///   repeat          the same robot reported this position (to 1 cm) before (SubT: an identical
///                   repeat is not charged); the earlier answer is not changed
///   limit_reached   the report limit is used up                     (not counted)
///   accepted        an unfound victim within report_radius: the nearest such victim is found,
///                   +victim_points
///   duplicate       victims within the radius, all found already    (charged, no score)
///   false_report    no victim within the radius                     (charged, −false_report_penalty)
/// "Charged" reports use up the report limit. Matching the nearest *unfound* victim within the
/// radius (SubT matches the nearest artifact, found or not) keeps two victims lying close
/// together both findable.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/index.h"
#include "core/pose.h"
#include "core/sim_time.h"
#include "world/mission_spec.h"

namespace rescuesim {

/// How a report was judged (see the file comment for the order).
enum class ReportOutcome { accepted, duplicate, false_report, repeat, out_of_contact, limit_reached, rate_limited, time_over, invalid };

/// "accepted", "duplicate", "false", "repeat", "out_of_contact", "limit_reached", "rate_limited",
/// "time_over", "invalid".
std::string_view report_outcome_name(ReportOutcome outcome);

/// A victim as the referee knows it.
struct RefereeVictim {
  std::string name;
  Vec3 p_W = Vec3::Zero();  ///< world frame, the point reports are measured to (m)
};

/// One report.
struct VictimReport {
  RobotIndex robot;          ///< index of the reporting robot
  Vec3 p_W = Vec3::Zero();   ///< reported position in the map frame, which is the world frame (m)
  SimTime time;              ///< when it was made
  bool in_contact = true;    ///< the robot had a radio route to a base
};

/// The answer to a report.
struct ReportReply {
  std::uint64_t id = 0;           ///< reports judged so far, this one included (1, 2, ...)
  ReportOutcome outcome = ReportOutcome::invalid;
  VictimIndex victim;             ///< the victim found (accepted) or nearest within the radius (duplicate), else invalid
  double distance_m = -1;         ///< from the report to that victim (m), else -1
  double score_change = 0;
  double score = 0;               ///< the score after this report
  int reports_left = -1;          ///< charged reports still allowed, -1 without a limit
  std::string message;            ///< one line for people ("found victim 'v2' 0.42 m away")
};

/// A change of score, for the timeline.
struct ScoreEvent {
  double t = 0;         ///< s
  RobotIndex robot;
  ReportOutcome outcome = ReportOutcome::accepted;
  VictimIndex victim;
  double score = 0;     ///< after the event
};

/// A victim's record.
struct RefereeVictimState {
  bool found = false;
  double time = -1;     ///< s when found
  RobotIndex by;        ///< robot that reported it (invalid: not found)
  double error_m = -1;  ///< distance of the accepted report (m)
};

/// Counts of every outcome, and the charged total.
struct RefereeCounts {
  std::uint64_t by_outcome[9] = {};  ///< indexed by ReportOutcome
  std::uint64_t charged = 0;         ///< accepted + duplicate + false_report

  std::uint64_t operator[](ReportOutcome o) const { return by_outcome[static_cast<int>(o)]; }
};

class Referee {
 public:
  /// `robots` is the number of robots that may report (indices 0 .. robots−1). Throws Error
  /// for impossible rules (radius ≤ 0, rate ≤ 0, negative points, limit or time).
  Referee(MissionRules rules, std::vector<RefereeVictim> victims, int robots);

  /// Judges a report (see the file comment) and returns the answer.
  ReportReply judge(const VictimReport& report);

  double score() const { return score_; }
  int victims_found() const { return found_; }
  int victim_count() const { return static_cast<int>(victims_.size()); }
  const RefereeCounts& counts() const { return counts_; }
  const MissionRules& rules() const { return rules_; }
  const std::vector<RefereeVictim>& victims() const { return victims_; }
  const std::vector<RefereeVictimState>& victim_states() const { return states_; }
  /// Every judged report that changed the score or was charged, in order.
  const std::vector<ScoreEvent>& timeline() const { return timeline_; }
  /// Charged reports still allowed, -1 without a limit.
  int reports_left() const;

 private:
  struct Remembered {
    RobotIndex robot;
    Vec3 p_W;
  };

  MissionRules rules_;
  std::vector<RefereeVictim> victims_;
  std::vector<RefereeVictimState> states_;
  int robots_ = 0;
  std::vector<std::int64_t> last_report_ns_;  ///< per robot, INT64_MIN before the first
  std::vector<Remembered> charged_;           ///< positions of charged reports (repeat detection)
  std::vector<ScoreEvent> timeline_;
  RefereeCounts counts_;
  double score_ = 0;
  int found_ = 0;
  std::uint64_t next_id_ = 1;
};

}  // namespace rescuesim
