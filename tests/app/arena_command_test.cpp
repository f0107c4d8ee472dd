// rescuesim arena as a user runs it: lanes of test-method terrain written as an SVG world that
// reads back with each element where the layout puts it, and clear errors for bad lanes.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "support/command.h"
#include "world/svg/svg_world.h"

namespace rescuesim {
namespace {

using testing::rescuesim;
using testing::temp_dir;

TEST(ArenaCommand, LanesSideBySideReadBackWithTheirElementsCentredInThem) {
  const auto dir = temp_dir("arena-command");
  const auto svg = dir / "arena.svg";
  const auto r = rescuesim("arena --lanes stepfield,crossing-ramps,curb --lane-width 1.1 --start-lane 1 --seed 5 --out '" + svg.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("lane 1  crossing-ramps  3.60 m long"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "arena.png"));
  const SvgLoadResult world = load_svg_world(svg);
  ASSERT_EQ(world.world.terrain.size(), 3u);
  // three lanes of 1.1 m; the longest element 3.6 m plus 1.5 m each end: 3.3 x 6.6 m
  EXPECT_NEAR(world.world.floor_max.x() - world.world.floor_min.x(), 3.3, 1e-6);
  EXPECT_NEAR(world.world.floor_max.y() - world.world.floor_min.y(), 6.6, 1e-6);
  const double centres[3] = {0.55, 1.65, 2.75};
  for (int i = 0; i < 3; ++i) {
    const TerrainSpec& t = world.world.terrain[static_cast<std::size_t>(i)];
    EXPECT_NEAR(t.pose.x, centres[i], 1e-6);
    EXPECT_NEAR(t.pose.y, 3.3, 1e-6);
    EXPECT_NEAR(t.width, 1.0, 1e-6);  // 5 cm clear of each lane wall
    EXPECT_NEAR(std::sin(t.pose.yaw), 1.0, 1e-9);  // travel north
  }
  EXPECT_EQ(world.world.terrain[0].seed, 5u);
  EXPECT_EQ(world.world.terrain[2].kind, TerrainSpec::Kind::curb);
  ASSERT_EQ(world.world.robots.size(), 1u);
  EXPECT_NEAR(world.world.robots[0].start.x, 1.65, 1e-6);  // the south end of lane 1
  EXPECT_NEAR(world.world.robots[0].start.y, 0.75, 1e-6);
  // and the world it draws checks clean
  EXPECT_EQ(rescuesim("check '" + svg.string() + "'").exit_code, 0);
}

TEST(ArenaCommand, AnUnknownLaneOrStartLaneIsAUsageErrorThatSaysWhatExists) {
  const auto dir = temp_dir("arena-command-bad");
  const auto unknown = rescuesim("arena --lanes stepfield,ladder --out '" + (dir / "a.svg").string() + "'");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("unknown terrain 'ladder'; expected stepfield, stairs, crossing-ramps, curb, hurdle or gap"), std::string::npos)
      << unknown.err;
  const auto start = rescuesim("arena --lanes curb --start-lane 3 --out '" + (dir / "a.svg").string() + "'");
  EXPECT_EQ(start.exit_code, 2);
  EXPECT_NE(start.err.find("start lane 3 does not exist; the arena has 1 lanes"), std::string::npos) << start.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "a.svg"));  // nothing half-written
}

}  // namespace
}  // namespace rescuesim
