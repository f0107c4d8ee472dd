// RealtimePacer (rescuesim run's realtime mode and rescuesim view's simulation thread): sim time follows the wall clock times the
// rate, pauses hold it, step requests advance it, and a simulation that falls behind owes at
// most max_lag of wall time. Every expected time below is worked out by hand from the inputs.

#include "session/realtime_pacer.h"

#include <gtest/gtest.h>

namespace rescuesim {
namespace {

SimTime s(double seconds) { return SimTime::from_seconds(seconds); }

TEST(RealtimePacer, SimTimeFollowsTheWallClockTimesTheRate) {
  RealtimePacer p;
  EXPECT_EQ(p.target(10.0, s(0), 1.0, false), s(0));    // anchored at wall 10 s, sim 0
  EXPECT_EQ(p.target(10.2, s(0.1), 1.0, false), s(0.2));
  // at 2x from wall 10.2 s and sim 0.2 s: 0.2 + 2 x 0.1
  EXPECT_EQ(p.target(10.2, s(0.2), 2.0, false), s(0.2));
  EXPECT_EQ(p.target(10.3, s(0.3), 2.0, false), s(0.4));
  // at a tenth: 0.4 + 0.1 x 1.0
  EXPECT_EQ(p.target(10.3, s(0.4), 0.1, false), s(0.4));
  EXPECT_EQ(p.target(11.3, s(0.49), 0.1, false), s(0.5));
}

TEST(RealtimePacer, PausedItHoldsAndStepRequestsAdvanceIt) {
  RealtimePacer p;
  EXPECT_EQ(p.target(0.0, s(1.0), 1.0, true), s(1.0));
  EXPECT_EQ(p.target(50.0, s(1.0), 1.0, true), s(1.0));  // wall time passes, sim time does not
  p.request_step(s(1.0), 0.1);
  EXPECT_EQ(p.target(50.1, s(1.0), 1.0, true), s(1.1));
  // a second request before the first is done adds on to its end
  p.request_step(s(1.05), 0.1);
  EXPECT_EQ(p.target(50.2, s(1.05), 1.0, true), s(1.2));
  // done: it holds there
  EXPECT_EQ(p.target(60.0, s(1.2), 1.0, true), s(1.2));
}

TEST(RealtimePacer, TheTimeSpentPausedIsNotOwed) {
  RealtimePacer p;
  EXPECT_EQ(p.target(0.0, s(0), 1.0, false), s(0));
  EXPECT_EQ(p.target(1.0, s(1.0), 1.0, false), s(1.0));
  EXPECT_EQ(p.target(1.0, s(1.0), 1.0, true), s(1.0));   // paused at wall 1 s ...
  EXPECT_EQ(p.target(20.0, s(1.0), 1.0, false), s(1.0));  // ... resumed at wall 20 s
  EXPECT_EQ(p.target(20.5, s(1.4), 1.0, false), s(1.5));
}

TEST(RealtimePacer, ASimulationThatFallsBehindOwesAtMostTheLag) {
  RealtimePacer p(0.25);
  EXPECT_EQ(p.target(0.0, s(0), 1.0, false), s(0));
  // at wall 5 s the simulation has only reached 1 s: 4 s behind; it is asked for 0.25 s more
  EXPECT_EQ(p.target(5.0, s(1.0), 1.0, false), s(1.25));
  // and paced on from there: anchored at wall 4.75 s, sim 1 s (0.25 s behind is not yet too far)
  EXPECT_EQ(p.target(5.5, s(1.5), 1.0, false), s(1.75));
  // at 4x the lag is 4 x 0.25 s of sim time
  EXPECT_EQ(p.target(5.5, s(1.5), 4.0, false), s(1.5));
  EXPECT_EQ(p.target(9.5, s(2.0), 4.0, false), s(3.0));
}

TEST(RealtimePacer, EachSimTimeIsDueAtItsWallTimeAndARestartOwesNothing) {
  // rescuesim run's realtime loop: anchored before a step, it sleeps until the step's end is due
  RealtimePacer p;
  EXPECT_EQ(p.target(10.0, s(2.0), 2.0, false), s(2.0));
  EXPECT_DOUBLE_EQ(p.wall_due(s(3.0)), 10.5);  // 1 s of sim time at 2x: half a wall second later
  // steps taken at once (a request while paused, a reset) start the pacing afresh
  p.restart();
  EXPECT_EQ(p.target(30.0, s(1.0), 2.0, false), s(1.0));
  EXPECT_DOUBLE_EQ(p.wall_due(s(1.5)), 30.25);
}

}  // namespace
}  // namespace rescuesim
