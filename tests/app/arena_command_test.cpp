// rescuesim arena as a user runs it: lanes of test-method terrain written as an SVG world that
// reads back with each element where the layout puts it, and clear errors for bad lanes.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "import/svg/svg_world.h"
#include "support/command.h"

namespace rescuesim {
namespace {

using testing::rescuesim;
using testing::temp_dir;

TEST(ArenaCommand, LanesSideBySideReadBackWithTheirElementsCentredInThem) {
  const auto dir = temp_dir("arena-command");
  const auto svg = dir / "arena.svg";
  const auto r =
      rescuesim("arena --lanes stepfield,crossing-ramps,curb --lane-width 1.1 --start-lane 1 --seed 5 --out '" + svg.string() + "'");
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

// The figure-8 apparatus: elements 2.4 x 4.8 m in lanes 2.5 m wide, for figure-eights around two
// pylons 1.2 m either side of the centre in loops of 2.4 / 2 - 0.7 = 0.5 m: a figure-eight of
// 2 (2 hypot(1.2, 0.5) + pi 0.5) = 2 (2.6 + 1.5708) = 8.3416 m.
TEST(ArenaCommand, FigureEightLanesHoldTheTestMethodsFigureEightElements) {
  const auto dir = temp_dir("arena-command-eight");
  const auto svg = dir / "eights.svg";
  const auto r = rescuesim("arena --lanes stepfield,crossing-ramps --figure-eight --no-png --out '" + svg.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2 figure-8 lanes of 2.50 m, 5.00 x 7.80 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--lane stepfield --pattern figure-eight"), std::string::npos) << r.out;
  const SvgLoadResult world = load_svg_world(svg);
  ASSERT_EQ(world.world.terrain.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    const TerrainSpec& t = world.world.terrain[static_cast<std::size_t>(i)];
    EXPECT_NEAR(t.width, 2.4, 1e-6);
    EXPECT_NEAR(t.length, 4.8, 1e-6);
    EXPECT_NEAR(t.pose.x, 1.25 + 2.5 * i, 1e-6);
    EXPECT_NEAR(t.pose.y, 3.9, 1e-6);
  }
  EXPECT_EQ(world.world.metadata.at("pattern"), "figure-eight");
  EXPECT_EQ(rescuesim("check '" + svg.string() + "'").exit_code, 0);
  // one figure-eight on the stepfield, as the hint says
  const auto out = dir / "trial";
  const auto trial = rescuesim("trial-terrain '" + svg.string() + "' --lane stepfield --pattern figure-eight --laps 1 --speed 0.5 --out '" +
                               out.string() + "'");
  ASSERT_EQ(trial.exit_code, 0) << trial.err;
  const nlohmann::json j = nlohmann::json::parse(testing::slurp(out / "trial.json"));
  EXPECT_EQ(j["pattern"], "figure-eight");
  EXPECT_EQ(j["kind"], "stepfield");
  EXPECT_NEAR(j["figure_eight_length_m"].get<double>(), 8.3416, 1e-4);
  EXPECT_EQ(j["laps_detail"].size(), 1u);
}

TEST(ArenaCommand, AFigureEightArenaOfStairsOrNarrowLanesIsAUsageError) {
  const auto dir = temp_dir("arena-command-eight-bad");
  const auto stairs = rescuesim("arena --lanes stepfield,stairs --figure-eight --out '" + (dir / "a.svg").string() + "'");
  EXPECT_EQ(stairs.exit_code, 2);
  EXPECT_NE(stairs.err.find("a figure-8 arena holds stepfields and crossing ramps (the test methods' figure-8 terrains), not stairs"),
            std::string::npos)
      << stairs.err;
  const auto narrow = rescuesim("arena --lanes stepfield --figure-eight --lane-width 1.2 --out '" + (dir / "a.svg").string() + "'");
  EXPECT_EQ(narrow.exit_code, 2);
  EXPECT_NE(narrow.err.find("lane width 1.2 m is too narrow for a figure-8 element 2.4 m wide (expected at least 2.5 m)"),
            std::string::npos)
      << narrow.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "a.svg"));
}

TEST(ArenaCommand, AnUnknownLaneOrStartLaneIsAUsageErrorThatSaysWhatExists) {
  const auto dir = temp_dir("arena-command-bad");
  const auto unknown = rescuesim("arena --lanes stepfield,ladder --out '" + (dir / "a.svg").string() + "'");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("unknown terrain 'ladder'; expected stepfield, stairs, crossing-ramps, curb, hurdle or gap"),
            std::string::npos)
      << unknown.err;
  const auto start = rescuesim("arena --lanes curb --start-lane 3 --out '" + (dir / "a.svg").string() + "'");
  EXPECT_EQ(start.exit_code, 2);
  EXPECT_NE(start.err.find("start lane 3 does not exist; the arena has 1 lanes"), std::string::npos) << start.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "a.svg"));  // nothing half-written
}

}  // namespace
}  // namespace rescuesim
