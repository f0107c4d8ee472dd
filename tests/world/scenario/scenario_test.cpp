// Scenario YAML: defaults, paths, and a clear error naming the key path for each class of
// bad input.

#include "world/scenario/scenario.h"

#include <gtest/gtest.h>

#include "robots/rescue_robot.h"

namespace rescuesim {
namespace {

std::string error_of(const std::string& yaml) {
  try {
    parse_scenario(yaml, "s.yaml", builtin_models());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Scenario, BuiltInDefaultIsAMazeWithVictims) {
  const Scenario s = default_scenario(builtin_models());
  EXPECT_EQ(s.name, "default");
  ASSERT_TRUE(s.maze.has_value());
  EXPECT_GT(s.maze->victims, 0);
  EXPECT_EQ(s.maze->seed, s.seed);  // the maze follows the run seed unless it sets its own
  const WorldSpec w = build_world(s);
  EXPECT_EQ(w.victims.size(), static_cast<std::size_t>(s.maze->victims));
  EXPECT_FALSE(validate(w).has_errors());
}

TEST(Scenario, SvgPathIsRelativeToTheScenarioFile) {
  const Scenario s = parse_scenario("world:\n  svg: arena.svg\n  svg_scale: 50\n", "/data/worlds/s.yaml", builtin_models());
  ASSERT_TRUE(s.svg.has_value());
  EXPECT_EQ(s.svg->string(), "/data/worlds/arena.svg");
  EXPECT_DOUBLE_EQ(s.svg_options.units_per_metre, 50);
  EXPECT_FALSE(s.maze.has_value());
}

TEST(Scenario, ShippedWorldsLoadAndValidate) {
  for (const char* f : {"default.yaml", "arena.yaml", "office.yaml"}) {
    const Scenario s = load_scenario(std::string(RESCUESIM_SOURCE_DIR) + "/worlds/" + f, builtin_models());
    Diagnostics d;
    const WorldSpec w = build_world(s, &d);
    d.append(validate(w));
    EXPECT_FALSE(d.has_errors()) << f << ": " << (d.items().empty() ? "" : d.items()[0].str());
    EXPECT_EQ(d.warning_count(), 0) << f << ": " << (d.items().empty() ? "" : d.items()[0].str());
    EXPECT_FALSE(w.robots.empty()) << f;
  }
}

TEST(Scenario, UnknownKeyNamesTheKeyPathAndLine) {
  const std::string e = error_of("name: x\nworld:\n  maze:\n    cols: 4\n    colour: red\n");
  EXPECT_NE(e.find("s.yaml:5"), std::string::npos) << e;
  EXPECT_NE(e.find("world.maze.colour"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key"), std::string::npos) << e;
}

TEST(Scenario, WrongTypeNamesTheKey) {
  const std::string e = error_of("world:\n  maze:\n    cols: eight\n");
  EXPECT_NE(e.find("world.maze.cols"), std::string::npos) << e;
  EXPECT_NE(e.find("expected a whole number"), std::string::npos) << e;
}

TEST(Scenario, OutOfRangeValueSaysTheRange) {
  const std::string e = error_of("world:\n  maze:\n    loop_fraction: 1.5\n");
  EXPECT_NE(e.find("world.maze.loop_fraction"), std::string::npos) << e;
  EXPECT_NE(e.find("[0, 1]"), std::string::npos) << e;
}

TEST(Scenario, StartCellOutsideTheGrid) {
  const std::string e = error_of("world:\n  maze:\n    cols: 3\n    rows: 3\n    start_cell: [3, 0]\n");
  EXPECT_NE(e.find("world.maze.start_cell"), std::string::npos) << e;
}

TEST(Scenario, SvgAndMazeTogetherIsAnError) {
  EXPECT_NE(error_of("world:\n  svg: a.svg\n  maze: {cols: 3}\n").find("not both"), std::string::npos);
}

TEST(Scenario, SyntaxErrorHasALine) {
  const std::string e = error_of("name: x\nworld: [unclosed\n");
  EXPECT_NE(e.find("YAML syntax error"), std::string::npos) << e;
  EXPECT_NE(e.find("s.yaml:"), std::string::npos) << e;
}

TEST(Scenario, EmptyAndNonMappingFiles) {
  EXPECT_NE(error_of("").find("empty"), std::string::npos);
  EXPECT_NE(error_of("- a\n- b\n").find("mapping"), std::string::npos);
}

TEST(Scenario, NegativeSeedIsRejected) { EXPECT_NE(error_of("seed: -4\n").find("seed"), std::string::npos); }

TEST(Scenario, MissingSvgFileNamesThePath) {
  const Scenario s = parse_scenario("world:\n  svg: /nonexistent/world.svg\n", "s.yaml", builtin_models());
  try {
    build_world(s);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/world.svg"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rescuesim
