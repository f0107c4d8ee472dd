#include "autonomy/astar.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rescuesim::autonomy {
namespace {

constexpr double kRes = 0.05;

// a 6 m square at 5 cm with every cell set to `fill`
OccupancyMapper grid(CellState fill = CellState::free) {
  OccupancyMapperConfig c;
  c.size = {6, 6};
  OccupancyMapper map(c);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) map.set_state({x, y}, fill);
  }
  return map;
}

// marks the cells of the axis-aligned box [x0, x1] x [y0, y1] (m)
void paint(OccupancyMapper& map, double x0, double y0, double x1, double y1, CellState s) {
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const Vec2 p = map.cell_to_world({x, y});
      if (p.x() >= x0 && p.x() <= x1 && p.y() >= y0 && p.y() <= y1) map.set_state({x, y}, s);
    }
  }
}

// octile distance (m) between the centres of the cells holding a and b
double octile_m(const OccupancyMapper& map, const Vec2& a, const Vec2& b) {
  const Cell ca = *map.world_to_cell(a), cb = *map.world_to_cell(b);
  const double dx = std::abs(ca.x - cb.x), dy = std::abs(ca.y - cb.y);
  return kRes * (std::max(dx, dy) + (std::sqrt(2.0) - 1) * std::min(dx, dy));
}

// the least distance (m) from the path (sampled every 1 cm) to any occupied cell centre
double path_clearance(const OccupancyMapper& map, const std::vector<Vec2>& path) {
  double best = 1e9;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const int n = static_cast<int>(std::ceil((path[i] - path[i - 1]).norm() / 0.01));
    for (int k = 0; k <= n; ++k) {
      const Vec2 p = path[i - 1] + (path[i] - path[i - 1]) * (static_cast<double>(k) / std::max(n, 1));
      for (int y = 0; y < map.height(); ++y) {
        for (int x = 0; x < map.width(); ++x) {
          if (map.is_occupied({x, y})) best = std::min(best, (map.cell_to_world({x, y}) - p).norm());
        }
      }
    }
  }
  return best;
}

TEST(AStar, ShortestPathOnAnEmptyGridIsTheOctileDistance) {
  const OccupancyMapper map = grid();
  AStarPlanner planner;
  for (const auto& [a, b] : std::vector<std::pair<Vec2, Vec2>>{
           {{1.0, 1.0}, {5.0, 2.0}}, {{0.52, 4.9}, {4.7, 0.3}}, {{3.0, 3.0}, {3.0, 5.5}}, {{2.0, 2.0}, {2.0, 2.0}}}) {
    const std::vector<Vec2> path = planner.plan(map, a, b);
    ASSERT_FALSE(path.empty());
    EXPECT_NEAR(path_length(path), octile_m(map, a, b), 1e-9);
    EXPECT_TRUE(path.front().isApprox(map.cell_to_world(*map.world_to_cell(a))));
    EXPECT_TRUE(path.back().isApprox(map.cell_to_world(*map.world_to_cell(b))));
  }
  // collinear points are dropped: a straight run is two points
  EXPECT_EQ(planner.plan(map, {1.0, 3.0}, {5.0, 3.0}).size(), 2u);
}

TEST(AStar, PathGoesThroughTheGapAndKeepsClearOfTheInflatedWall) {
  OccupancyMapper map = grid();
  paint(map, 2.95, 0.0, 3.05, 6.0, CellState::occupied);  // a wall across x = 3 ...
  paint(map, 2.9, 4.0, 3.1, 5.2, CellState::free);        // ... with a 1.2 m gap at y 4..5.2
  AStarPlanner planner;
  const std::vector<Vec2> path = planner.plan(map, {1.0, 1.0}, {5.0, 1.0});
  ASSERT_FALSE(path.empty());
  EXPECT_GE(path_clearance(map, path), planner.config().cost.robot_radius);
  bool through_gap = false;
  for (const Vec2& p : path) through_gap = through_gap || (p.y() > 4.0 && p.y() < 5.2);
  EXPECT_TRUE(through_gap);
  EXPECT_GT(path_length(path), 8.0);  // up to the gap and back down: much longer than 4 m
}

TEST(AStar, NoPathWhenBlockedOrTheGapIsNarrowerThanTheRobot) {
  OccupancyMapper map = grid();
  paint(map, 2.95, 0.0, 3.05, 6.0, CellState::occupied);
  AStarPlanner planner;
  EXPECT_TRUE(planner.plan(map, {1.0, 1.0}, {5.0, 1.0}).empty());
  paint(map, 2.9, 3.0, 3.1, 3.55, CellState::free);  // a 0.55 m gap: the 0.7 m robot cannot pass
  EXPECT_TRUE(planner.plan(map, {1.0, 1.0}, {5.0, 1.0}).empty());
  paint(map, 2.9, 3.0, 3.1, 4.0, CellState::free);  // a 1 m gap: it can
  EXPECT_FALSE(planner.plan(map, {1.0, 1.0}, {5.0, 1.0}).empty());
}

TEST(AStar, LethalOrOffGridGoalsGiveNoPath) {
  OccupancyMapper map = grid();
  paint(map, 4.0, 4.0, 4.2, 4.2, CellState::occupied);
  AStarPlanner planner;
  EXPECT_TRUE(planner.plan(map, {1.0, 1.0}, {4.1, 4.1}).empty());   // inside the obstacle
  EXPECT_TRUE(planner.plan(map, {1.0, 1.0}, {4.1, 4.45}).empty());  // within the robot's radius of it
  EXPECT_TRUE(planner.plan(map, {1.0, 1.0}, {7.0, 1.0}).empty());   // off the grid
  EXPECT_TRUE(planner.plan(map, {-1.0, 1.0}, {2.0, 1.0}).empty());
}

TEST(AStar, StartPressedAgainstAWallStillGetsOut) {
  OccupancyMapper map = grid();
  paint(map, 2.95, 0.0, 3.05, 6.0, CellState::occupied);
  AStarPlanner planner;
  const std::vector<Vec2> path = planner.plan(map, {2.75, 3.0}, {1.0, 3.0});  // 0.2 m from the wall
  ASSERT_FALSE(path.empty());
  EXPECT_LT(path.back().x(), 1.1);
}

TEST(AStar, UnknownCellsAreCrossedOnlyWhenAllowed) {
  OccupancyMapper map = grid(CellState::unknown);
  paint(map, 0.5, 0.5, 1.5, 1.5, CellState::free);
  PlannerConfig config;
  config.cost.unknown_traversable = false;
  EXPECT_TRUE(AStarPlanner(config).plan(map, {1.0, 1.0}, {5.0, 5.0}).empty());
  config.cost.unknown_traversable = true;
  const std::vector<Vec2> path = AStarPlanner(config).plan(map, {1.0, 1.0}, {5.0, 5.0});
  ASSERT_FALSE(path.empty());
  EXPECT_NEAR(path_length(path), octile_m(map, {1.0, 1.0}, {5.0, 5.0}), 1e-9);
}

TEST(AStar, FrontierIsFoundInTheOpenDirection) {
  // a known 2 m room with walls on three sides, open to the east onto unknown ground
  OccupancyMapper map = grid(CellState::unknown);
  paint(map, 1.0, 1.0, 3.0, 3.0, CellState::free);
  paint(map, 0.9, 0.9, 3.0, 1.0, CellState::occupied);
  paint(map, 0.9, 3.0, 3.0, 3.1, CellState::occupied);
  paint(map, 0.9, 0.9, 1.0, 3.1, CellState::occupied);
  AStarPlanner planner;
  const std::vector<Vec2> path = planner.plan_to_nearest_frontier(map, {1.6, 2.0});
  ASSERT_FALSE(path.empty());
  EXPECT_GT(path.back().x(), 2.9);
  EXPECT_NEAR(path.back().y(), 2.0, 0.6);
  EXPECT_TRUE(is_frontier(map, *map.world_to_cell(path.back())));
  // excluding it leaves nothing
  EXPECT_TRUE(planner.plan_to_nearest_frontier(map, {1.6, 2.0}, {path.back()}).empty());
}

TEST(AStar, FrontiersTeammatesClaimedAreLeftToThem) {
  // a known corridor from x = 0.5 to 5 m, open at both ends onto unknown ground; from x = 4 the
  // east end (1 m) is nearer than the west (3.5 m)
  OccupancyMapper map = grid(CellState::unknown);
  paint(map, 0.5, 2.0, 5.0, 4.0, CellState::free);
  paint(map, 0.5, 1.9, 5.0, 2.0, CellState::occupied);
  paint(map, 0.5, 4.0, 5.0, 4.1, CellState::occupied);
  AStarPlanner planner;
  ASSERT_EQ(planner.config().claimed_radius, 3.0);
  const std::vector<Vec2> east = planner.plan_to_nearest_frontier(map, {4.0, 3.0});
  ASSERT_FALSE(east.empty());
  EXPECT_GT(east.back().x(), 4.9);
  // a teammate is going to the east end: every frontier cell within 3 m of (5, 3) is its, so
  // the west end (4.5 m from the claim) is next
  const std::vector<Vec2> west = planner.plan_to_nearest_frontier(map, {4.0, 3.0}, {}, {{5.0, 3.0}});
  ASSERT_FALSE(west.empty());
  EXPECT_LT(west.back().x(), 0.6);
}

TEST(AStar, SmallFrontierClustersAreSkippedForBigOnes) {
  // a long known corridor open at its east end, with a one-cell hole in the map near the
  // start (8 frontier cells round it, fewer than the 12 a frontier needs)
  OccupancyMapper map = grid(CellState::unknown);
  paint(map, 0.5, 2.0, 5.0, 4.0, CellState::free);
  paint(map, 0.4, 1.9, 5.0, 2.0, CellState::occupied);
  paint(map, 0.4, 4.0, 5.0, 4.1, CellState::occupied);
  paint(map, 0.4, 1.9, 0.5, 4.1, CellState::occupied);
  map.set_state(*map.world_to_cell({2.0, 3.0}), CellState::unknown);
  AStarPlanner planner;
  ASSERT_EQ(planner.config().min_frontier_cells, 12);
  const std::vector<Vec2> path = planner.plan_to_nearest_frontier(map, {1.0, 3.0});
  ASSERT_FALSE(path.empty());
  EXPECT_GT(path.back().x(), 4.9);
  // with a lower bar the hole is the nearest frontier
  PlannerConfig config;
  config.min_frontier_cells = 8;
  const std::vector<Vec2> near = AStarPlanner(config).plan_to_nearest_frontier(map, {1.0, 3.0});
  ASSERT_FALSE(near.empty());
  EXPECT_LT((near.back() - Vec2(2.0, 3.0)).norm(), 0.1);
}

TEST(AStar, SameQueryGivesTheSamePath) {
  OccupancyMapper map = grid();
  paint(map, 2.0, 2.0, 4.0, 4.0, CellState::occupied);  // a block in the middle: two equal ways round
  AStarPlanner a, b;
  const std::vector<Vec2> first = a.plan(map, {1.0, 1.0}, {5.0, 5.0});
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first, a.plan(map, {1.0, 1.0}, {5.0, 5.0}));
  EXPECT_EQ(first, b.plan(map, {1.0, 1.0}, {5.0, 5.0}));
  const int expansions = a.last_expansions();
  b.plan(map, {1.0, 1.0}, {5.0, 5.0});
  EXPECT_EQ(expansions, b.last_expansions());
}

TEST(AStar, PathBlockedSeesObstaclesOnTheRestOfThePath) {
  OccupancyMapper map = grid();
  const std::vector<Vec2> path = {{1.0, 1.0}, {5.0, 1.0}, {5.0, 5.0}};
  EXPECT_FALSE(path_blocked(map, path, 1, {1.0, 1.0}, 0.28));
  map.set_state(*map.world_to_cell({5.2, 3.0}), CellState::occupied);  // 0.2 m beside the last leg
  EXPECT_TRUE(path_blocked(map, path, 1, {1.0, 1.0}, 0.28));
  EXPECT_FALSE(path_blocked(map, path, 1, {1.0, 1.0}, 0.1));
  // an obstacle behind the robot does not count
  map.set_state(*map.world_to_cell({5.2, 3.0}), CellState::free);
  map.set_state(*map.world_to_cell({1.5, 1.1}), CellState::occupied);
  EXPECT_FALSE(path_blocked(map, path, 1, {3.0, 1.0}, 0.28));
  EXPECT_TRUE(path_blocked(map, path, 1, {1.2, 1.0}, 0.28));
}

}  // namespace
}  // namespace rescuesim::autonomy
