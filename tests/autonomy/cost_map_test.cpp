#include "autonomy/cost_map.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rescuesim::autonomy {
namespace {

// a 5 m square of known free cells at 5 cm
OccupancyMapper free_square() {
  OccupancyMapperConfig c;
  c.size = {5, 5};
  OccupancyMapper map(c);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) map.set_state({x, y}, CellState::free);
  }
  return map;
}

TEST(CostMap, ClearanceIsTheExactDistanceToTheNearestObstacle) {
  OccupancyMapper map = free_square();
  map.set_state({50, 50}, CellState::occupied);
  map.set_state({80, 20}, CellState::occupied);
  const CostMap costs(map, {}, {0, 0}, {99, 99});
  EXPECT_DOUBLE_EQ(costs.clearance({50, 50}), 0.0);
  EXPECT_NEAR(costs.clearance({53, 54}), 0.25, 1e-6);  // a 3-4-5 triangle of cells
  EXPECT_NEAR(costs.clearance({50, 10}), 0.05 * std::hypot(30, 10), 1e-6);  // (80, 20) is nearer than (50, 50)
  EXPECT_NEAR(costs.clearance({80, 25}), 0.25, 1e-6);
  // brute force over the whole window
  for (int y = 0; y < 100; y += 7) {
    for (int x = 0; x < 100; x += 7) {
      const double expected = 0.05 * std::min(std::hypot(x - 50, y - 50), std::hypot(x - 80, y - 20));
      EXPECT_NEAR(costs.clearance({x, y}), expected, 1e-5) << x << ", " << y;
    }
  }
}

TEST(CostMap, LethalInsideTheRadiusDearerNearObstaclesUnitFarAway) {
  OccupancyMapper map = free_square();
  map.set_state({50, 50}, CellState::occupied);
  CostMapConfig config;
  config.robot_radius = 0.35;
  config.comfort_distance = 0.75;
  const CostMap costs(map, config, {0, 0}, {99, 99});
  EXPECT_EQ(costs.factor({50, 50}), CostMap::kLethal);
  EXPECT_EQ(costs.factor({57, 50}), CostMap::kLethal);  // 0.35 m < 0.35 + half a cell
  EXPECT_LT(costs.factor({58, 50}), CostMap::kLethal);  // 0.40 m
  EXPECT_GT(costs.factor({58, 50}), costs.factor({60, 50}));
  EXPECT_FLOAT_EQ(costs.factor({66, 50}), 1.0f);  // 0.80 m: beyond comfort
  EXPECT_FLOAT_EQ(costs.factor({5, 5}), 1.0f);
}

TEST(CostMap, KeepOutDiscsCountAsObstaclesTheirRadiusWide) {
  // a free square with no obstacle but a disc of 0.3 m around the centre of cell (50, 50)
  OccupancyMapper map = free_square();
  CostMapConfig config;
  config.robot_radius = 0.35;
  config.keep_out = {map.cell_to_world({50, 50})};
  config.keep_out_radius = 0.3;
  const CostMap costs(map, config, {0, 0}, {99, 99});
  EXPECT_NEAR(costs.clearance({60, 50}), 0.5 - 0.3, 1e-6);
  EXPECT_NEAR(costs.clearance({53, 54}), 0.0, 1e-6);  // 0.25 m from the centre: inside the disc
  EXPECT_NEAR(costs.clearance({50, 90}), 2.0 - 0.3, 1e-6);
  // lethal within robot_radius + half a cell of the disc's edge: closer than 0.675 m to its centre
  EXPECT_EQ(costs.factor({63, 50}), CostMap::kLethal);  // 0.65 m
  EXPECT_LT(costs.factor({64, 50}), CostMap::kLethal);  // 0.70 m
  // without the disc the square is free everywhere
  EXPECT_FLOAT_EQ(CostMap(map, {}, {0, 0}, {99, 99}).factor({50, 50}), 1.0f);
}

TEST(CostMap, UnknownCellsAreDearerOrLethalAsConfigured) {
  OccupancyMapper map = free_square();
  map.set_state({10, 10}, CellState::unknown);
  CostMapConfig config;
  config.unknown_cost = 2.5;
  EXPECT_FLOAT_EQ(CostMap(map, config, {0, 0}, {99, 99}).factor({10, 10}), 2.5f);
  config.unknown_traversable = false;
  EXPECT_EQ(CostMap(map, config, {0, 0}, {99, 99}).factor({10, 10}), CostMap::kLethal);
}

TEST(CostMap, WindowIsClampedToTheGrid) {
  OccupancyMapper map = free_square();
  const CostMap costs(map, {}, {-10, 90}, {10, 120});
  EXPECT_EQ(costs.lo(), (Cell{0, 90}));
  EXPECT_EQ(costs.hi(), (Cell{10, 99}));
  EXPECT_EQ(costs.size(), 11 * 10);
  EXPECT_TRUE(costs.in_window({0, 99}));
  EXPECT_FALSE(costs.in_window({11, 95}));
  EXPECT_EQ(costs.cell_at(costs.local({7, 93})), (Cell{7, 93}));
}

}  // namespace
}  // namespace rescuesim::autonomy
