#include "autonomy/occupancy_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "autonomy/kinematic_sim.h"
#include "core/error.h"

namespace rescuesim::autonomy {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// a full-circle scan of n beams, all reading `range`
msg::LaserScan uniform_scan(int n, float range, float range_max = 10.0f) {
  msg::LaserScan s;
  s.header = {SimTime::from_ms(100), "laser"};
  s.angle_min = static_cast<float>(-M_PI);
  s.angle_increment = static_cast<float>(2 * M_PI / n);
  s.angle_max = s.angle_min + (n - 1) * s.angle_increment;
  s.range_min = 0.05f;
  s.range_max = range_max;
  s.ranges.assign(n, range);
  return s;
}

// a 720-beam scan of the given segments (zero thickness) from sensor pose X_OS
msg::LaserScan scan_of(const std::vector<testing::Segment>& walls, const Pose2& X_OS) {
  msg::LaserScan s = uniform_scan(720, kInf);
  for (int i = 0; i < 720; ++i) {
    const double a = X_OS.yaw + s.angle_min + i * static_cast<double>(s.angle_increment);
    const double r = testing::ray_cast(X_OS.position(), Vec2(std::cos(a), std::sin(a)), walls);
    s.ranges[i] = r < s.range_max ? static_cast<float>(r) : kInf;
  }
  return s;
}

// a mapper over [-3, 3]^2 at 5 cm
OccupancyMapper six_metre_box() {
  OccupancyMapperConfig c;
  c.origin_O = {-3, -3};
  c.size = {6, 6};
  return OccupancyMapper(c);
}

TEST(OccupancyMapper, SquareRoomMarksWallsOccupiedAndTheInsideFree) {
  // walls through cell centres (x, y = +-1.975), so every return falls in one known cell
  OccupancyMapper map = six_metre_box();
  const double h = 1.975;
  const auto room = testing::box(-h, -h, h, h);
  const Pose2 X_OS{0.3, -0.2, 0.4};
  map.integrate(scan_of(room, X_OS), X_OS);

  int wall_cells = 0, occupied = 0;
  for (double t = -h + 0.05; t <= h - 0.05; t += 0.05) {
    for (const Vec2& p : {Vec2(t, -h), Vec2(t, h), Vec2(-h, t), Vec2(h, t)}) {
      ++wall_cells;
      occupied += map.is_occupied(*map.world_to_cell(p)) ? 1 : 0;
    }
  }
  EXPECT_GE(occupied, 0.97 * wall_cells);

  // inside (0.1 m clear of the walls) all free, outside all unknown
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const Vec2 p = map.cell_to_world({x, y});
      const double inside = h - std::max(std::abs(p.x()), std::abs(p.y()));
      if (inside > 0.1) {
        EXPECT_TRUE(map.is_free({x, y})) << p.transpose();
      } else if (inside < -0.1) {
        EXPECT_TRUE(map.is_unknown({x, y})) << p.transpose();
      }
    }
  }
}

TEST(OccupancyMapper, RepeatedScansSettleAndLearnNothingNew) {
  OccupancyMapper map = six_metre_box();
  const auto room = testing::box(-1.975, -1.975, 1.975, 1.975);
  const Pose2 X_OS{0.0, 0.0, 0.0};
  const msg::LaserScan scan = scan_of(room, X_OS);
  EXPECT_GT(map.integrate(scan, X_OS), 4000);  // about pi * 2^2 m^2 / 25 cm^2 of new cells
  EXPECT_EQ(map.integrate(scan, X_OS), 0);
  const Cell wall = *map.world_to_cell({1.975, 0.0});
  EXPECT_FLOAT_EQ(map.log_odds(wall), 1.8f);  // two hits of 0.9
}

TEST(OccupancyMapper, MemoryGrowsWithTheGroundSeenNotWithTheBox) {
  // a 40 m box (800 x 800 cells: 625 tiles of 32 x 32 cells, 5 MB whole) around a sensor in a
  // 2 m square room: the room's 40 x 40 cells and the walls lie within 1.0 m of the sensor, which
  // at 1.6 m a tile side spans at most 3 x 3 tiles
  OccupancyMapperConfig c;
  c.origin_O = {-20, -20};
  c.size = {40, 40};
  OccupancyMapper map(c);
  const std::size_t index_bytes = 625 * sizeof(void*), tile_bytes = 32 * 32 * (sizeof(float) + sizeof(std::uint32_t));
  EXPECT_EQ(map.cell_bytes(), index_bytes);  // nothing seen, no tile
  const auto room = testing::box(-0.975, -0.975, 0.975, 0.975);
  const Pose2 X_OS{0.0, 0.0, 0.0};
  map.integrate(scan_of(room, X_OS), X_OS);
  EXPECT_GT(map.cell_bytes(), index_bytes);
  EXPECT_LE(map.cell_bytes(), index_bytes + 9 * tile_bytes);
  // a copy holds the same cells in tiles of its own
  OccupancyMapper copy = map;
  map.set_state(*map.world_to_cell({0, 0}), CellState::occupied);
  EXPECT_TRUE(copy.is_free(*copy.world_to_cell({0, 0})));
  EXPECT_TRUE(copy.is_occupied(*copy.world_to_cell({0.975, 0})));
  EXPECT_EQ(copy.cell_bytes(), map.cell_bytes());
  // a cell in a tile never touched reads unknown
  EXPECT_TRUE(map.is_unknown(*map.world_to_cell({15, 15})));
}

TEST(OccupancyMapper, InfiniteBeamsClearUpToTheCap) {
  OccupancyMapper map = six_metre_box();
  // +inf: no return; cleared to min(range_max 10, inf_free_range 4) = 4 m, but the box ends at 3
  map.integrate(uniform_scan(720, kInf), {0, 0, 0});
  EXPECT_TRUE(map.is_free(*map.world_to_cell({2.9, 0.0})));
  EXPECT_TRUE(map.is_free(*map.world_to_cell({0.0, -2.9})));
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) EXPECT_FALSE(map.is_occupied({x, y}));
  }

  // with range_max 1.5 the cap is 1.5 m
  OccupancyMapper short_map = six_metre_box();
  short_map.integrate(uniform_scan(720, kInf, 1.5f), {0, 0, 0});
  EXPECT_TRUE(short_map.is_free(*short_map.world_to_cell({1.4, 0.0})));
  EXPECT_TRUE(short_map.is_unknown(*short_map.world_to_cell({1.6, 0.0})));

  // a finite range at range_max is no return either: cleared, not occupied
  OccupancyMapper max_map = six_metre_box();
  max_map.integrate(uniform_scan(720, 1.5f, 1.5f), {0, 0, 0});
  EXPECT_TRUE(max_map.is_free(*max_map.world_to_cell({1.45, 0.02})));
  EXPECT_TRUE(max_map.is_unknown(*max_map.world_to_cell({1.6, 0.0})));
}

TEST(OccupancyMapper, NegativeInfinityNaNAndTooShortRangesAreIgnored) {
  OccupancyMapper map = six_metre_box();
  msg::LaserScan scan = uniform_scan(360, -kInf);
  for (std::size_t i = 0; i < scan.ranges.size(); i += 3) scan.ranges[i] = kNaN;
  for (std::size_t i = 1; i < scan.ranges.size(); i += 3) scan.ranges[i] = 0.01f;  // below range_min
  EXPECT_EQ(map.integrate(scan, {0, 0, 0}), 0);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) ASSERT_TRUE(map.is_unknown({x, y}));
  }
  EXPECT_FALSE(map.observed_box().has_value());
}

TEST(OccupancyMapper, ASingleReturnClearsItsBeamAndMarksItsEnd) {
  OccupancyMapper map = six_metre_box();
  msg::LaserScan scan = uniform_scan(4, kInf, 10.0f);  // beams at -180, -90, 0, 90 degrees
  scan.ranges = {kNaN, kNaN, 2.0f, kNaN};              // one return 2 m along the sensor's x
  const Pose2 X_OS{-1.0, 0.5, M_PI / 2};               // sensor facing +y: the return is at (-1, 2.5)
  map.integrate(scan, X_OS);
  EXPECT_TRUE(map.is_occupied(*map.world_to_cell({-1.0, 2.52})));
  for (double y = 0.5; y < 2.3; y += 0.05) EXPECT_TRUE(map.is_free(*map.world_to_cell({-1.0, y}))) << y;
  EXPECT_TRUE(map.is_unknown(*map.world_to_cell({-1.0, 2.7})));
  EXPECT_TRUE(map.is_unknown(*map.world_to_cell({-0.8, 1.5})));
}

TEST(OccupancyMapper, MessageIsRowMajorFromTheOrigin) {
  OccupancyMapperConfig c;
  c.resolution = 0.1;
  c.origin_O = {2.0, -1.0};
  c.size = {1.0, 0.5};  // 10 x 5 cells
  OccupancyMapper map(c);
  map.set_state({3, 1}, CellState::occupied);
  map.set_state({9, 4}, CellState::free);
  const msg::OccupancyGrid m = map.to_message("odom", SimTime::from_seconds(2.5));
  EXPECT_EQ(m.header.frame_id, "odom");
  EXPECT_EQ(m.header.stamp, SimTime::from_seconds(2.5));
  EXPECT_FLOAT_EQ(m.resolution, 0.1f);
  EXPECT_EQ(m.width, 10u);
  EXPECT_EQ(m.height, 5u);
  EXPECT_TRUE(m.origin.p.isApprox(Vec3(2.0, -1.0, 0.0)));
  EXPECT_TRUE(m.origin.q.isApprox(Quat::Identity()));
  ASSERT_EQ(m.data.size(), 50u);
  // occupied at the clamp 3.5 -> 97 %, free at -2 -> 12 %, the rest unknown
  EXPECT_EQ(m.data[1 * 10 + 3], 97);
  EXPECT_EQ(m.data[4 * 10 + 9], 12);
  int unknown = 0;
  for (std::int8_t v : m.data) unknown += v == -1 ? 1 : 0;
  EXPECT_EQ(unknown, 48);
}

TEST(OccupancyMapper, WorldAndCellCoordinatesRoundTrip) {
  OccupancyMapper map = six_metre_box();
  EXPECT_EQ(map.width(), 120);
  EXPECT_EQ(map.height(), 120);
  EXPECT_EQ(*map.world_to_cell({-3.0, -3.0}), (Cell{0, 0}));
  EXPECT_EQ(*map.world_to_cell({0.01, -0.01}), (Cell{60, 59}));
  EXPECT_TRUE(map.cell_to_world({60, 59}).isApprox(Vec2(0.025, -0.025)));
  EXPECT_FALSE(map.world_to_cell({3.0, 0.0}).has_value());
  EXPECT_FALSE(map.world_to_cell({0.0, -3.01}).has_value());
  for (int i : {0, 7, 119, 120 * 60 + 5, 120 * 120 - 1}) EXPECT_EQ(map.index(map.cell_at(i)), i);
}

TEST(OccupancyMapper, AutoSizeCentresOnTheFirstScan) {
  OccupancyMapper map;  // auto: 40 m square around the first sensor pose
  EXPECT_FALSE(map.allocated());
  map.integrate(uniform_scan(90, 1.0f), {10.0, -5.0, 0.3});
  ASSERT_TRUE(map.allocated());
  EXPECT_EQ(map.width(), 800);
  EXPECT_EQ(map.height(), 800);
  EXPECT_TRUE(map.origin().isApprox(Vec2(-10.0, -25.0)));
  EXPECT_TRUE(map.is_free(*map.world_to_cell({10.0, -5.0})));
}

TEST(OccupancyMapper, RejectsBadSettingsWithTheirName) {
  OccupancyMapperConfig c;
  c.resolution = 0;
  try {
    OccupancyMapper m(c);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("resolution"), std::string::npos) << e.what();
  }
  OccupancyMapperConfig big;
  big.size = {1e5, 1e5};
  EXPECT_THROW(OccupancyMapper{big}, Error);
}

}  // namespace
}  // namespace rescuesim::autonomy
