// The referee against rules worked by hand: victims at known points, reports at known
// distances, and the score each outcome must give.

#include "mission/referee.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"

namespace rescuesim {
namespace {

/// Two victims 10 m apart on the x axis, one robot.
Referee two_victims(MissionRules rules = {}, int robots = 1) {
  return Referee(rules, {{"v1", {0, 0, 0}}, {"v2", {10, 0, 0}}}, robots);
}

VictimReport at(double x, double y, double t_s, int robot = 0, bool contact = true) {
  VictimReport r;
  r.robot = RobotIndex(robot);
  r.p_W = {x, y, 0};
  r.time = SimTime::from_seconds(t_s);
  r.in_contact = contact;
  return r;
}

TEST(Referee, AcceptsAReportWithinTheRadiusAndScoresThePoints) {
  Referee ref = two_victims();
  // 0.9, 1.2 is 1.5 m from v1 (a 3-4-5 triangle scaled by 0.3): exactly on the RoboCup radius
  const ReportReply r = ref.judge(at(0.9, 1.2, 1.0));
  EXPECT_EQ(r.outcome, ReportOutcome::accepted);
  EXPECT_EQ(r.victim, VictimIndex(0));
  EXPECT_NEAR(r.distance_m, 1.5, 1e-12);
  EXPECT_EQ(r.score_change, 1.0);
  EXPECT_EQ(r.score, 1.0);
  EXPECT_EQ(r.id, 1u);
  EXPECT_EQ(ref.victims_found(), 1);
  EXPECT_TRUE(ref.victim_states()[0].found);
  EXPECT_EQ(ref.victim_states()[0].by, RobotIndex(0));
  EXPECT_DOUBLE_EQ(ref.victim_states()[0].time, 1.0);
  EXPECT_NE(r.message.find("'v1'"), std::string::npos) << r.message;
}

TEST(Referee, AReportJustBeyondTheRadiusIsFalseAndPenalised) {
  Referee ref = two_victims();
  const ReportReply r = ref.judge(at(1.501, 0, 1.0));
  EXPECT_EQ(r.outcome, ReportOutcome::false_report);
  EXPECT_EQ(r.victim.valid(), false);
  EXPECT_EQ(r.score_change, -0.5);  // RoboCup VRC: half a victim per false report
  EXPECT_EQ(ref.score(), -0.5);
  EXPECT_EQ(ref.counts()[ReportOutcome::false_report], 1u);
}

TEST(Referee, EachVictimCountsOnceLaterReportsAreDuplicates) {
  Referee ref = two_victims();
  EXPECT_EQ(ref.judge(at(0.5, 0, 1.0)).outcome, ReportOutcome::accepted);
  const ReportReply dup = ref.judge(at(-0.5, 0, 2.0));
  EXPECT_EQ(dup.outcome, ReportOutcome::duplicate);
  EXPECT_EQ(dup.victim, VictimIndex(0));
  EXPECT_EQ(dup.score_change, 0.0);
  EXPECT_EQ(ref.score(), 1.0);
  EXPECT_EQ(ref.counts().charged, 2u);  // a duplicate uses up a report
}

TEST(Referee, TwoVictimsCloseTogetherAreBothFindable) {
  // v1 at 0, v2 at 1 m: a report at 0.4 is nearest v1; the next at 0.4 from another spot
  // within both radii finds v2, the unfound one, though v1 is nearer
  Referee ref({}, {{"v1", {0, 0, 0}}, {"v2", {1, 0, 0}}}, 1);
  EXPECT_EQ(ref.judge(at(0.4, 0, 1)).victim, VictimIndex(0));
  const ReportReply r = ref.judge(at(0.3, 0.1, 2));
  EXPECT_EQ(r.outcome, ReportOutcome::accepted);
  EXPECT_EQ(r.victim, VictimIndex(1));
  EXPECT_NEAR(r.distance_m, std::hypot(0.7, 0.1), 1e-12);
  EXPECT_EQ(ref.victims_found(), 2);
}

TEST(Referee, SubtRulesHaveFiveMetresNoPenaltyAndFortyReports) {
  const MissionRules subt = mission_rules("subt");
  EXPECT_EQ(subt.report_radius_m, 5.0);
  EXPECT_EQ(subt.false_report_penalty, 0.0);
  EXPECT_EQ(subt.report_limit, 40);
  Referee ref = two_victims(subt);
  EXPECT_EQ(ref.judge(at(3, 4, 1)).outcome, ReportOutcome::accepted);  // 5 m from v1
  const ReportReply f = ref.judge(at(5, 5, 2));                         // √50 ≈ 7.07 m from v1, √50 from v2
  EXPECT_EQ(f.outcome, ReportOutcome::false_report);
  EXPECT_EQ(f.score_change, 0.0);
  EXPECT_EQ(f.reports_left, 38);
  EXPECT_THROW(mission_rules("vrc"), Error);
}

TEST(Referee, TheReportLimitStopsJudgingAndRepeatsAreNotCharged) {
  MissionRules rules;
  rules.report_limit = 2;
  Referee ref = two_victims(rules);
  EXPECT_EQ(ref.judge(at(5, 5, 1)).outcome, ReportOutcome::false_report);
  // the same robot at the same place (within 1 cm): not charged, the limit is untouched
  const ReportReply again = ref.judge(at(5.005, 5, 2));
  EXPECT_EQ(again.outcome, ReportOutcome::repeat);
  EXPECT_EQ(again.reports_left, 1);
  EXPECT_EQ(ref.judge(at(0, 0, 3)).outcome, ReportOutcome::accepted);
  const ReportReply over = ref.judge(at(10, 0, 4));
  EXPECT_EQ(over.outcome, ReportOutcome::limit_reached);
  EXPECT_EQ(over.reports_left, 0);
  EXPECT_EQ(ref.score(), 0.5);  // +1 − 0.5
  EXPECT_EQ(ref.victims_found(), 1);
}

TEST(Referee, OutOfContactReportsAreRefusedWithoutCostAndCountWhenRepeatedInContact) {
  Referee ref = two_victims();
  const ReportReply r = ref.judge(at(0, 0, 1, 0, false));
  EXPECT_EQ(r.outcome, ReportOutcome::out_of_contact);
  EXPECT_EQ(ref.counts().charged, 0u);
  EXPECT_EQ(ref.score(), 0.0);
  EXPECT_EQ(ref.judge(at(0, 0, 2, 0, true)).outcome, ReportOutcome::accepted);

  MissionRules anywhere;
  anywhere.require_contact = false;
  Referee free = two_victims(anywhere);
  EXPECT_EQ(free.judge(at(0, 0, 1, 0, false)).outcome, ReportOutcome::accepted);
}

TEST(Referee, AFloodIsRateLimitedPerRobotAndCounted) {
  Referee ref = two_victims({}, 2);  // 2 reports per second per robot: 0.5 s apart at least
  EXPECT_EQ(ref.judge(at(5, 5, 1.0, 0)).outcome, ReportOutcome::false_report);
  EXPECT_EQ(ref.judge(at(6, 5, 1.1, 0)).outcome, ReportOutcome::rate_limited);
  EXPECT_EQ(ref.judge(at(6, 5, 1.1, 1)).outcome, ReportOutcome::false_report);  // the other robot has its own rate
  // 100 reports in the next 0.4 s: all refused, none charged, none lost from the counts
  for (int i = 0; i < 100; ++i) EXPECT_EQ(ref.judge(at(7, 5, 1.1 + 0.004 * i, 0)).outcome, ReportOutcome::rate_limited);
  EXPECT_EQ(ref.judge(at(0, 0, 1.5, 0)).outcome, ReportOutcome::accepted);  // exactly 0.5 s after the last judged one
  EXPECT_EQ(ref.counts()[ReportOutcome::rate_limited], 101u);
  EXPECT_EQ(ref.counts().charged, 3u);
  EXPECT_EQ(ref.score(), 0.0);  // −0.5 −0.5 +1
}

TEST(Referee, InvalidReportsAndLateReportsAreAnsweredNotScored) {
  MissionRules rules;
  rules.time_limit_s = 60;
  Referee ref = two_victims(rules);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ref.judge(at(nan, 0, 1)).outcome, ReportOutcome::invalid);
  EXPECT_EQ(ref.judge(at(0, inf, 2)).outcome, ReportOutcome::invalid);
  EXPECT_EQ(ref.judge(at(0, 0, 3, 7)).outcome, ReportOutcome::invalid);   // no robot 7
  EXPECT_EQ(ref.judge(at(0, 0, 4, -1)).outcome, ReportOutcome::invalid);
  EXPECT_EQ(ref.judge(at(0, 0, 60.001)).outcome, ReportOutcome::time_over);
  EXPECT_EQ(ref.counts()[ReportOutcome::invalid], 4u);
  EXPECT_EQ(ref.counts()[ReportOutcome::time_over], 1u);
  EXPECT_EQ(ref.counts().charged, 0u);
  EXPECT_EQ(ref.score(), 0.0);
  EXPECT_EQ(ref.victims_found(), 0);
}

TEST(Referee, TheTimelineHoldsEveryChargedReport) {
  Referee ref = two_victims();
  ref.judge(at(0, 0, 1));
  ref.judge(at(5, 5, 2));
  ref.judge(at(5, 5, 2.1));   // rate limited: not on the timeline
  ref.judge(at(10, 0.2, 3));
  ASSERT_EQ(ref.timeline().size(), 3u);
  EXPECT_EQ(ref.timeline()[0].outcome, ReportOutcome::accepted);
  EXPECT_EQ(ref.timeline()[0].score, 1.0);
  EXPECT_EQ(ref.timeline()[1].outcome, ReportOutcome::false_report);
  EXPECT_EQ(ref.timeline()[1].score, 0.5);
  EXPECT_EQ(ref.timeline()[2].victim, VictimIndex(1));
  EXPECT_EQ(ref.timeline()[2].score, 1.5);
  EXPECT_DOUBLE_EQ(ref.timeline()[2].t, 3.0);
}

TEST(Referee, ImpossibleRulesAreRefusedNamingTheValue) {
  MissionRules r;
  r.report_radius_m = 0;
  try {
    Referee ref(r, {}, 1);
    FAIL() << "accepted a zero radius";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("report_radius must be > 0 m, not 0"), std::string::npos) << e.what();
  }
  MissionRules rate;
  rate.report_rate_hz = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((Referee(rate, {}, 1)), Error);
  EXPECT_THROW((Referee({}, {{"v", {std::nan(""), 0, 0}}}, 1)), Error);
}

TEST(Referee, OutcomeNamesAreTheWireWords) {
  EXPECT_EQ(report_outcome_name(ReportOutcome::false_report), "false");
  EXPECT_EQ(report_outcome_name(ReportOutcome::out_of_contact), "out_of_contact");
  EXPECT_EQ(report_outcome_name(ReportOutcome::accepted), "accepted");
}

}  // namespace
}  // namespace rescuesim
