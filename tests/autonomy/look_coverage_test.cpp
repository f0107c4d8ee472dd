#include "autonomy/look_coverage.h"

#include <gtest/gtest.h>

#include <cmath>

#include "autonomy/astar.h"

namespace rescuesim::autonomy {
namespace {

// a 6 m square at 5 cm, origin (0, 0), every cell free but a wall across x in [4.0, 4.1]
OccupancyMapper room_with_wall() {
  OccupancyMapperConfig c;
  c.size = {6, 6};
  OccupancyMapper map(c);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const Vec2 p = map.cell_to_world({x, y});
      map.set_state({x, y}, p.x() > 4.0 && p.x() < 4.1 ? CellState::occupied : CellState::free);
    }
  }
  return map;
}

bool looked_at(const LookCoverage& look, const OccupancyMapper& map, double x, double y) {
  return look.looked(*map.world_to_cell({x, y}));
}

TEST(LookCoverage, AFanMarksWhatIsInsideItsAngleAndRangeAndStopsAtTheWall) {
  const OccupancyMapper map = room_with_wall();
  LookCoverage look;
  CameraFan fan;
  fan.hfov = M_PI / 3;  // 60 degrees: +-30 about the heading
  fan.range = 2.5;
  // from (2, 3) looking along +x: the wall is 2 m ahead
  const int added = look.look(map, {2.0, 3.0}, 0.0, fan);
  EXPECT_GT(added, 0);
  EXPECT_EQ(look.count(), added);
  EXPECT_TRUE(looked_at(look, map, 3.0, 3.0));   // 1 m straight ahead
  EXPECT_TRUE(looked_at(look, map, 3.0, 3.5));   // bearing atan(0.5 / 1) = 26.6 degrees: inside
  EXPECT_FALSE(looked_at(look, map, 3.0, 3.7));  // atan(0.7 / 1) = 35 degrees: outside
  EXPECT_FALSE(looked_at(look, map, 1.0, 3.0));  // behind
  EXPECT_TRUE(looked_at(look, map, 4.05, 3.0));  // the wall's face: seen
  EXPECT_FALSE(looked_at(look, map, 4.3, 3.0));  // behind the wall, though within 2.5 m
  // 1.5 m along the beam at 20 degrees: inside
  EXPECT_TRUE(looked_at(look, map, 2.0 + 1.5 * std::cos(0.349), 3.0 + 1.5 * std::sin(0.349)));
  // looking the other way: 2.5 m of range reaches x = -0.5 (off the map); x = 0.1 is looked at
  LookCoverage back;
  back.look(map, {2.0, 3.0}, M_PI, fan);
  EXPECT_TRUE(looked_at(back, map, 0.1, 3.0));
  EXPECT_FALSE(looked_at(back, map, 3.0, 3.0));
  // looking again adds nothing new
  EXPECT_EQ(look.look(map, {2.0, 3.0}, 0.0, fan), 0);
}

TEST(LookCoverage, UnknownCellsStopTheViewAndTheRobotCoversItsOwnFootprint) {
  OccupancyMapper map = room_with_wall();
  // an unknown band across x in [2.5, 2.6]: the camera cannot know what lies beyond
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const Vec2 p = map.cell_to_world({x, y});
      if (p.x() > 2.5 && p.x() < 2.6) map.set_state({x, y}, CellState::unknown);
    }
  }
  LookCoverage look;
  CameraFan fan;
  fan.range = 3.0;
  look.look(map, {2.0, 3.0}, 0.0, fan);
  EXPECT_TRUE(looked_at(look, map, 2.4, 3.0));
  EXPECT_FALSE(looked_at(look, map, 2.55, 3.0));
  EXPECT_FALSE(looked_at(look, map, 3.0, 3.0));
  // a disc of 0.3 m around (1, 1): pi 0.3^2 / 0.05^2 = 113 cells, give or take the rim
  LookCoverage disc;
  const int n = disc.cover_disc(map, {1.0, 1.0}, 0.3);
  EXPECT_NEAR(n, M_PI * 0.09 / 0.0025, 12);
  EXPECT_TRUE(looked_at(disc, map, 1.25, 1.0));
  EXPECT_FALSE(looked_at(disc, map, 1.35, 1.0));
}

TEST(LookCoverage, WhatATeammateSawIsLookedAtButNotByThisRobot) {
  const OccupancyMapper map = room_with_wall();
  LookCoverage look;
  // a 0.5 m square round (1.25, 1.25): cell centres 1.025 .. 1.475, 10 x 10
  EXPECT_EQ(look.mark_team_square(map, {1.25, 1.25}, 0.25), 100);
  EXPECT_TRUE(look.looked(*map.world_to_cell({1.1, 1.4})));
  EXPECT_TRUE(look.looked_by_team(*map.world_to_cell({1.1, 1.4})));
  EXPECT_FALSE(look.looked_self(*map.world_to_cell({1.1, 1.4})));
  EXPECT_FALSE(look.looked(*map.world_to_cell({1.55, 1.25})));
  EXPECT_EQ(look.count(), 0);  // count() is this robot's own looking
  // a square half off the grid is clipped to it: 5 columns of 10
  EXPECT_EQ(look.mark_team_square(map, {0.0, 3.0}, 0.25), 50);
  // far off the grid, however far: nothing
  EXPECT_EQ(look.mark_team_square(map, {1e12, -1e12}, 0.25), 0);
  EXPECT_EQ(look.mark_team_square(map, {-7.0, 3.0}, 0.25), 0);
}

TEST(LookCoverage, ThePlannerDrivesToTheNearestUnseenPocketBigEnoughToMatter) {
  const OccupancyMapper map = room_with_wall();
  LookCoverage look;
  // everything looked at but two pockets: 3 x 3 cells around (1.025, 1.025) and 8 x 8 cells
  // around (3, 5)
  look.cover_disc(map, {2.0, 3.0}, 10.0);
  LookCoverage partial;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const Vec2 p = map.cell_to_world({x, y});
      const bool small = std::abs(p.x() - 1.025) < 0.06 && std::abs(p.y() - 1.025) < 0.06;
      const bool big = std::abs(p.x() - 3.0) < 0.2 && std::abs(p.y() - 5.0) < 0.2;
      if (!small && !big) partial.cover_disc(map, p, 0.01);
    }
  }
  EXPECT_FALSE(partial.looked(*map.world_to_cell({1.0, 1.0})));
  EXPECT_FALSE(partial.looked(*map.world_to_cell({3.0, 5.0})));
  AStarPlanner planner;
  const auto unseen = [&](Cell c) { return map.is_free(c) && !partial.looked(c); };
  // the small pocket (9 cells) is nearer from (1.5, 1.5), but a trip needs 40 cells
  const std::vector<Vec2> path =
      planner.plan_to_nearest_target(map, {1.5, 1.5}, unseen, [](Cell) { return 40; });
  ASSERT_FALSE(path.empty());
  EXPECT_LT(std::abs(path.back().x() - 3.0), 0.25);
  EXPECT_LT(std::abs(path.back().y() - 5.0), 0.25);
  // with 9 cells enough, the small pocket wins
  const std::vector<Vec2> near = planner.plan_to_nearest_target(map, {1.5, 1.5}, unseen, [](Cell) { return 9; });
  ASSERT_FALSE(near.empty());
  EXPECT_LT((near.back() - Vec2(1.025, 1.025)).norm(), 0.08);
  // nothing unseen: no trip
  EXPECT_TRUE(planner.plan_to_nearest_target(map, {1.5, 1.5}, [&](Cell c) { return !look.looked(c) && map.is_free(c) && c.x < 80; },
                                             [](Cell) { return 1; })
                  .empty());
}

}  // namespace
}  // namespace rescuesim::autonomy
