// Run-mode resolution (session/run_mode.h): every combination of the pacing flags with and
// without a live bridge gives the documented mode, contradictions are errors, and controllers
// and duration follow the bridge.

#include "session/run_mode.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"

namespace rescuesim {
namespace {

/// The error text of resolving `r`, or "" when it resolves.
std::string error_of(const RunModeRequest& r) {
  try {
    resolve_run_mode(r);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(RunMode, PacingByPrecedence) {
  struct Case {
    bool scenario_realtime, realtime, lockstep, sync, live;
    Pacing expected;
  };
  // every combination that is not a contradiction
  const Case cases[] = {
      {false, false, false, false, false, Pacing::lockstep},  // the default
      {true, false, false, false, false, Pacing::realtime},   // the scenario's realtime: setting
      {false, true, false, false, false, Pacing::realtime},   // --realtime
      {true, false, true, false, false, Pacing::lockstep},    // --lockstep beats the scenario
      {false, false, false, false, true, Pacing::realtime},   // a live bridge
      {false, false, true, false, true, Pacing::lockstep},    // bridge --lockstep
      {false, true, false, false, true, Pacing::realtime},    // bridge --realtime
      {false, false, false, true, true, Pacing::sync},        // bridge --sync
      {true, false, false, true, true, Pacing::sync},         // --sync beats the scenario
      {false, false, true, true, true, Pacing::sync},         // --sync --lockstep agree: sync
  };
  for (const Case& c : cases) {
    RunModeRequest r;
    r.scenario_realtime = c.scenario_realtime;
    r.realtime = c.realtime;
    r.lockstep = c.lockstep;
    if (c.sync) r.sync = 2.5;
    r.live_bridge = c.live;
    const RunMode m = resolve_run_mode(r);
    EXPECT_EQ(m.pacing, c.expected) << "scenario_realtime " << c.scenario_realtime << " realtime " << c.realtime << " lockstep "
                                    << c.lockstep << " sync " << c.sync << " live " << c.live;
    EXPECT_EQ(m.sync_timeout, c.sync ? 2.5 : 0.0);
  }
}

TEST(RunMode, ContradictionsAreErrorsNamingTheFlags) {
  RunModeRequest r;
  r.realtime = true;
  r.sync = 1.0;
  r.live_bridge = true;
  EXPECT_NE(error_of(r).find("--realtime --sync"), std::string::npos) << error_of(r);
  r.sync.reset();
  r.lockstep = true;
  EXPECT_NE(error_of(r).find("--realtime --lockstep"), std::string::npos) << error_of(r);
  RunModeRequest alone;
  alone.sync = 1.0;  // no bridge: nothing answers the scans
  EXPECT_NE(error_of(alone).find("--ros1 or --ros2"), std::string::npos) << error_of(alone);
}

TEST(RunMode, ControllersAndDurationFollowTheBridge) {
  RunModeRequest r;
  EXPECT_TRUE(resolve_run_mode(r).controllers);
  EXPECT_FALSE(resolve_run_mode(r).until_stopped);
  r.no_controllers = true;
  EXPECT_FALSE(resolve_run_mode(r).controllers);
  r.no_controllers = false;
  r.live_bridge = true;
  EXPECT_FALSE(resolve_run_mode(r).controllers);  // ROS drives the robots
  EXPECT_TRUE(resolve_run_mode(r).until_stopped);
  r.keep_controllers = true;
  EXPECT_TRUE(resolve_run_mode(r).controllers);
  r.no_controllers = true;  // --no-controllers wins over --keep-controllers
  EXPECT_FALSE(resolve_run_mode(r).controllers);
  r.duration_given = true;
  EXPECT_FALSE(resolve_run_mode(r).until_stopped);
}

TEST(RunMode, AppliedToScenarioAndSessionOptions) {
  Scenario s;
  s.duration = 30;
  SessionOptions so;
  RunModeRequest r;
  r.live_bridge = true;
  r.sync = 0.5;
  apply_run_mode(resolve_run_mode(r), s, so);
  EXPECT_FALSE(s.realtime);
  EXPECT_TRUE(std::isinf(s.duration));
  EXPECT_FALSE(so.controllers);
  EXPECT_EQ(so.sync_timeout, 0.5);
  EXPECT_STREQ(pacing_name(Pacing::sync), "lockstep, synchronous with cmd_vel");

  Scenario t;
  t.duration = 30;
  SessionOptions to;
  RunModeRequest realtime;
  realtime.realtime = true;
  apply_run_mode(resolve_run_mode(realtime), t, to);
  EXPECT_TRUE(t.realtime);
  EXPECT_EQ(t.duration, 30);
  EXPECT_TRUE(to.controllers);
  EXPECT_EQ(to.sync_timeout, 0);
}

}  // namespace
}  // namespace rescuesim
