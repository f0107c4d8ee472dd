// Loading a scenario with command-line overrides (session/scenario_load.h): the seed reaches the
// generated maze, an SVG world replaces the maze, unset overrides change nothing, and a bad file
// is reported by name.

#include "session/scenario_load.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/error.h"
#include "robots/rescue_robot.h"
#include "support/command.h"

namespace rescuesim {
namespace {

TEST(ScenarioLoad, NoOverridesIsTheDefaultScenario) {
  const ModelMap models = builtin_models();
  const Scenario s = load_scenario_with_overrides("", models);
  // worlds/default.yaml: seed 7, 180 s, an 8 × 8 maze seeded like the run
  EXPECT_EQ(s.seed, 7u);
  EXPECT_EQ(s.duration, 180.0);
  ASSERT_TRUE(s.maze.has_value());
  EXPECT_EQ(s.maze->seed, 7u);
  EXPECT_EQ(s.maze->cols, 8);
}

TEST(ScenarioLoad, SeedOverrideReseedsTheMaze) {
  const ModelMap models = builtin_models();
  ScenarioOverrides o;
  o.seed = 42;
  o.duration = 12.5;
  o.rate = 2.0;
  o.render_quality = "high";
  const Scenario s = load_scenario_with_overrides("", models, o);
  EXPECT_EQ(s.seed, 42u);
  ASSERT_TRUE(s.maze.has_value());
  EXPECT_EQ(s.maze->seed, 42u);
  EXPECT_EQ(s.duration, 12.5);
  EXPECT_EQ(s.rate, 2.0);
  EXPECT_EQ(s.render_quality, "high");
}

TEST(ScenarioLoad, ReseedCanKeepTheMaze) {
  Scenario s = load_scenario_with_overrides("", builtin_models());
  reseed_scenario(s, 9, /*reseed_maze=*/false);
  EXPECT_EQ(s.seed, 9u);
  EXPECT_EQ(s.maze->seed, 7u);
}

TEST(ScenarioLoad, SvgWorldReplacesTheMaze) {
  ScenarioOverrides o;
  o.world = "office.svg";
  const Scenario s = load_scenario_with_overrides("", builtin_models(), o);
  EXPECT_FALSE(s.maze.has_value());
  ASSERT_TRUE(s.svg.has_value());
  EXPECT_EQ(s.svg->string(), "office.svg");
}

TEST(ScenarioLoad, SdfWorldReplacesTheMazeWithItsModelsAndStep) {
  // worlds/rescue_yard.sdf: 14 solids, 3 crates, 2 victims, one robot_start, a 5 ms step;
  // model://rescue_ramp and model://crate come from the --resource-path folder
  const std::string worlds = std::string(RESCUESIM_SOURCE_DIR) + "/worlds";
  ScenarioOverrides o;
  o.world = std::string(worlds).append("/rescue_yard.sdf");  // (not worlds + "...": GCC 12 warns falsely, -Warray-bounds)
  o.resource_paths = {worlds + "/models"};
  const Scenario s = load_scenario_with_overrides("", builtin_models(), o);
  EXPECT_FALSE(s.maze.has_value());
  EXPECT_FALSE(s.svg.has_value());
  ASSERT_TRUE(s.sdf.has_value());
  ASSERT_NE(s.models, nullptr);
  EXPECT_EQ(s.models->spec.solids.size(), 14u);
  EXPECT_EQ(s.models->spec.bodies.size(), 3u);
  EXPECT_DOUBLE_EQ(s.physics_dt, 0.005);
  // the default scenario's robot takes the world's robot_start
  const WorldSpec w = build_world(s);
  ASSERT_EQ(w.robots.size(), 1u);
  EXPECT_DOUBLE_EQ(w.robots[0].start.x, 5.0);
  EXPECT_DOUBLE_EQ(w.robots[0].start.y, 5.0);
  EXPECT_EQ(w.victims.size(), 2u);
  // without the resource path, model://rescue_ramp is nowhere: an Error naming the URI
  ScenarioOverrides no_path;
  no_path.world = o.world;
  try {
    load_scenario_with_overrides("", builtin_models(), no_path);
    FAIL() << "model://rescue_ramp was found without its folder";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("model://rescue_ramp"), std::string::npos) << e.what();
    EXPECT_NE(e.where().file.find("rescue_yard.sdf"), std::string::npos) << e.what();
  }
}

TEST(ScenarioLoad, FromAFileAndABadFileNamed) {
  const auto dir = testing::temp_dir("scenario-load");
  const auto good = dir / "small.yaml";
  std::ofstream(good) << "name: small\nseed: 3\nduration: 5\nworld:\n  maze:\n    cols: 3\n    rows: 3\n";
  ScenarioOverrides o;
  o.seed = 11;
  const Scenario s = load_scenario_with_overrides(good.string(), builtin_models(), o);
  EXPECT_EQ(s.name, "small");
  EXPECT_EQ(s.seed, 11u);
  EXPECT_EQ(s.maze->seed, 11u);
  EXPECT_EQ(s.duration, 5.0);

  const auto bad = dir / "bad.yaml";
  std::ofstream(bad) << "name: bad\nduration: [\n";
  try {
    load_scenario_with_overrides(bad.string(), builtin_models());
    FAIL() << "bad YAML was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rescuesim
