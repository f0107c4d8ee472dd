// rescuesim trial-terrain's trials: laps across a lane counted as the test methods count them,
// each outcome checked against what the robots are known to do there (tests/robots).

#include "session/terrain_trial.h"

#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "robots/rescue_robot.h"
#include "world/terrain.h"

namespace rescuesim {
namespace {

WorldSpec arena(std::vector<TerrainSpec::Kind> lanes) {
  ArenaOptions o;
  o.lanes = std::move(lanes);
  return test_method_arena(o);
}

TEST(TerrainTrial, TheTrackedRobotClimbsTheCurbLaneAndTheWheeledRobotIsStuckAtIt) {
  const WorldSpec world = arena({TerrainSpec::Kind::curb});
  TerrainTrialOptions o;
  o.lane = "curb";
  o.laps = 2;
  o.stuck_time = 5;
  const TerrainTrialResult tracked = run_terrain_trial(world, builtin_models(), o);
  ASSERT_EQ(tracked.laps.size(), 2u);
  EXPECT_EQ(tracked.repetitions, 2);
  EXPECT_EQ(tracked.falls + tracked.stuck + tracked.timeouts, 0);
  for (const auto& l : tracked.laps) {
    EXPECT_EQ(l.outcome, "completed");
    // the lane from start line to end line at 0.3 m/s, and a little for the climb
    const double lane = tracked.element.length + 2 * o.approach;
    EXPECT_GT(l.time, lane / o.speed);
    EXPECT_LT(l.time, 2 * lane / o.speed);
    EXPECT_NEAR(l.max_height, 0.15, 0.05);  // up onto the 15 cm curb
  }
  EXPECT_NE(tracked.laps[0].time, tracked.laps[1].time);  // each lap starts a little differently

  o.robot = "rescue_robot";
  o.laps = 1;
  const TerrainTrialResult wheeled = run_terrain_trial(world, builtin_models(), o);
  EXPECT_EQ(wheeled.repetitions, 0);
  EXPECT_EQ(wheeled.stuck, 1);
  // stopped at the face, which is `approach` + half the element past the start line
  EXPECT_LT(wheeled.laps[0].progress, o.approach + 0.5 * wheeled.element.length);

  const nlohmann::json j = nlohmann::json::parse(terrain_trial_json(tracked));
  EXPECT_EQ(j["kind"], "curb");
  EXPECT_EQ(j["robot"], "tracked_robot");
  EXPECT_EQ(j["repetitions"], 2);
  EXPECT_EQ(j["laps_detail"].size(), 2u);
  EXPECT_EQ(j["laps_detail"][0]["outcome"], "completed");
  const Canvas figure = terrain_trial_figure(world, tracked);
  EXPECT_GT(figure.width(), 200);
}

// Back and forth without a reset over a 3 cm curb: every crossing completes, alternating forward
// and back, so --laps 3 gives three repetitions. Each crossing runs the lane from line to line,
// 2 x 0.3 m of approach + 1.2 m of curb = 1.8 m, at 0.6 m/s: 3 s, and less than 1.5 s more to
// get going (or to stop and reverse).
TEST(TerrainTrial, BackAndForthCountsEveryCrossingAsARepetition) {
  WorldSpec world = arena({TerrainSpec::Kind::curb});
  world.terrain[0].height = 0.03;
  TerrainTrialOptions o;
  o.lane = "curb";
  o.pattern = TerrainPattern::back_and_forth;
  o.laps = 3;
  o.approach = 0.3;
  o.speed = 0.6;
  const TerrainTrialResult r = run_terrain_trial(world, builtin_models(), o);
  ASSERT_EQ(r.laps.size(), 3u);
  EXPECT_EQ(r.repetitions, 3);
  const double lane = 2 * o.approach + r.element.length;
  double total = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const TerrainLap& l = r.laps[i];
    EXPECT_EQ(l.outcome, "completed") << i;
    EXPECT_EQ(l.reverse, i == 1) << i;
    EXPECT_GT(l.time, lane / o.speed) << i;
    EXPECT_LT(l.time, lane / o.speed + 1.5) << i;
    EXPECT_GT(l.progress, lane - 0.05) << i;
    total += l.time;
  }
  EXPECT_NEAR(r.sim_time, total, 0.02);  // one simulation, crossing after crossing
  const nlohmann::json j = nlohmann::json::parse(terrain_trial_json(r));
  EXPECT_EQ(j["pattern"], "back-and-forth");
  EXPECT_EQ(j["repetitions"], 3);
  EXPECT_EQ(j["laps_detail"][1]["direction"], "back");
  EXPECT_EQ(parse_terrain_pattern("back-and-forth"), TerrainPattern::back_and_forth);
  EXPECT_THROW(parse_terrain_pattern("figure-8"), Error);
}

// A crossing that fails ends a back-and-forth trial: the wheeled robot is stuck at a 15 cm curb
// on its first crossing, and there is no second.
TEST(TerrainTrial, BackAndForthEndsAtTheFirstFailure) {
  const WorldSpec world = arena({TerrainSpec::Kind::curb});
  TerrainTrialOptions o;
  o.lane = "curb";
  o.robot = "rescue_robot";
  o.pattern = TerrainPattern::back_and_forth;
  o.laps = 4;
  o.stuck_time = 3;
  const TerrainTrialResult r = run_terrain_trial(world, builtin_models(), o);
  ASSERT_EQ(r.laps.size(), 1u);
  EXPECT_EQ(r.repetitions, 0);
  EXPECT_EQ(r.stuck, 1);
}

// Figure-eights on crossing ramps of the test methods' figure-8 size (2.3 x 4.8 m, here 5 degree
// ramps the robot turns on without trouble): pylons a quarter of the length in from each end
// (1.2 m from the centre), loops of half the width less 0.7 m (0.45 m), and each figure-eight a
// path of 2 (2 hypot(1.2, 0.45) + pi 0.45) = 7.95 m (four diagonals, two half circles), driven
// without a reset.
TEST(TerrainTrial, FigureEightsLoopAroundBothPylonsWithoutAReset) {
  ArenaOptions ao;
  ao.lanes = {TerrainSpec::Kind::crossing_ramps};
  ao.lane_width = 2.4;
  ao.approach = 2.5;
  WorldSpec world = test_method_arena(ao);
  TerrainSpec& ramps = world.terrain.at(0);
  ramps.length = 4.8;
  ramps.angle = 5;
  TerrainTrialOptions o;
  o.lane = "crossing-ramps";
  o.pattern = TerrainPattern::figure_eight;
  o.laps = 2;
  o.time_limit = 120;
  const TerrainTrialResult r = run_terrain_trial(world, builtin_models(), o);
  ASSERT_EQ(r.pylons.size(), 2u);
  const Vec2 centre(ramps.pose.x, ramps.pose.y);
  const Vec2 along(std::cos(ramps.pose.yaw), std::sin(ramps.pose.yaw));
  EXPECT_NEAR((r.pylons[0] - centre).dot(along), -1.2, 1e-9);
  EXPECT_NEAR((r.pylons[1] - centre).dot(along), 1.2, 1e-9);
  EXPECT_NEAR(r.loop_radius, 0.45, 1e-9);
  const double eight = 2 * (2 * std::hypot(1.2, 0.45) + M_PI * 0.45);
  EXPECT_NEAR(r.eight_length, eight, 1e-9);
  ASSERT_EQ(r.laps.size(), 2u);
  EXPECT_EQ(r.repetitions, 2);
  for (const auto& l : r.laps) {
    EXPECT_EQ(l.outcome, "completed");
    // progress is the path's length from where the lap began (near the centre)
    EXPECT_NEAR(l.progress, eight, 0.5);
    // at the speed along at least the figure-eight's path, and not much longer: turns in place
    EXPECT_GT(l.time, (eight - 0.5) / o.speed);
    EXPECT_LT(l.time, 2 * eight / o.speed);
    // around both pylons: the path reaches beyond each pylon's far side, left and right of it
    double beyond_far = -1e9, beyond_near = 1e9, left = -1e9, right = 1e9;
    for (const Vec2& p : l.path) {
      const Vec2 d = p - centre;
      const double u = d.dot(along), v = along.x() * d.y() - along.y() * d.x();
      beyond_far = std::max(beyond_far, u), beyond_near = std::min(beyond_near, u);
      left = std::max(left, v), right = std::min(right, v);
    }
    EXPECT_GT(beyond_far, 1.2 + 0.3);
    EXPECT_LT(beyond_near, -1.2 - 0.3);
    EXPECT_GT(left, 0.3);
    EXPECT_LT(right, -0.3);
  }
  // the second lap starts where the first ended (no reset): near the centre
  ASSERT_FALSE(r.laps[1].path.empty());
  EXPECT_LT((r.laps[1].path.front() - centre).norm(), 0.3);
  const nlohmann::json j = nlohmann::json::parse(terrain_trial_json(r));
  EXPECT_EQ(j["pattern"], "figure-eight");
  EXPECT_EQ(j["laps_detail"][0]["direction"], "figure-eight");
  EXPECT_NEAR(j["figure_eight_length_m"].get<double>(), eight, 1e-9);
  EXPECT_EQ(parse_terrain_pattern("figure-eight"), TerrainPattern::figure_eight);
}

// Figure-eights are driven on the figure-8 terrains only; elsewhere an error says what to use.
TEST(TerrainTrial, AFigureEightOnStairsIsAnErrorNamingThePatternsThatFit) {
  const WorldSpec world = arena({TerrainSpec::Kind::stairs});
  TerrainTrialOptions o;
  o.lane = "stairs";
  o.pattern = TerrainPattern::figure_eight;
  try {
    run_terrain_trial(world, builtin_models(), o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(e.message().find("figure-eights are driven on stepfields and crossing ramps"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("is stairs: use --pattern laps or back-and-forth"), std::string::npos) << e.message();
  }
}

TEST(TerrainTrial, TheSameSeedRunsTheSameLaps) {
  const WorldSpec world = arena({TerrainSpec::Kind::curb});
  TerrainTrialOptions o;
  o.lane = "curb";
  o.laps = 1;
  const TerrainTrialResult a = run_terrain_trial(world, builtin_models(), o);
  const TerrainTrialResult b = run_terrain_trial(world, builtin_models(), o);
  EXPECT_EQ(a.laps[0].time, b.laps[0].time);
  EXPECT_EQ(a.laps[0].path, b.laps[0].path);
  // the final states too, to the bit; another seed starts the lap elsewhere and ends elsewhere
  EXPECT_EQ(a.state_hash, b.state_hash);
  o.seed = 2;
  EXPECT_NE(run_terrain_trial(world, builtin_models(), o).state_hash, a.state_hash);
}

TEST(TerrainTrial, AnUnknownLaneOrRobotIsAnErrorThatSaysWhatThereIs) {
  const WorldSpec world = arena({TerrainSpec::Kind::curb, TerrainSpec::Kind::hurdle});
  TerrainTrialOptions o;
  o.lane = "stairs";
  try {
    run_terrain_trial(world, builtin_models(), o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(e.message().find("no lane 'stairs'"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("lane_00_curb (curb), lane_01_hurdle (hurdle)"), std::string::npos) << e.message();
  }
  o.lane = "curb";
  o.robot = "tank";
  try {
    run_terrain_trial(world, builtin_models(), o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(e.message().find("unknown robot 'tank' (known: rescue_robot, tracked_robot)"), std::string::npos) << e.message();
  }
}

}  // namespace
}  // namespace rescuesim
