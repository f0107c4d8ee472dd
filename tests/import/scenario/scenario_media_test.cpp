// Smoke and dust from the scenario YAML (world.media): read into the world whatever its source,
// and refused with the file, line and key path when a value is impossible.

#include <gtest/gtest.h>

#include "import/scenario/scenario.h"
#include "robots/rescue_robot.h"

namespace rescuesim {
namespace {

std::string error_of(const std::string& yaml) {
  try {
    parse_scenario(yaml, "s.yaml", builtin_models());
  } catch (const Error& e) {
    return e.what();
  }
  return "(parsed)";
}

const char* kMaze = "world:\n  maze:\n    cols: 4\n    rows: 4\n  media:\n";

TEST(ScenarioMedia, AMazeGetsTheScenariosSmoke) {
  const Scenario s = parse_scenario(std::string(kMaze) +
                                        "    - kind: dust\n"
                                        "      name: plume\n"
                                        "      outline: [[1, 1], [1, 2], [3, 2], [3, 1]]\n"  // clockwise: turned round
                                        "      density: 1.5\n"
                                        "      bottom: 0.1\n"
                                        "      height: 0.5\n"
                                        "      growth: 0.01\n"
                                        "      drift: [0.2, -0.1]\n"
                                        "    - outline: [[0, 0], [1, 0], [0, 1]]\n"
                                        "      density: 0.3\n",
                                    "s.yaml", builtin_models());
  const WorldSpec w = build_world(s);
  ASSERT_EQ(w.media.size(), 2u);
  const MediumSpec& d = w.media[0];
  EXPECT_EQ(d.kind, MediumSpec::Kind::dust);
  EXPECT_EQ(d.name, "plume");
  EXPECT_DOUBLE_EQ(d.density, 1.5);
  EXPECT_DOUBLE_EQ(d.bottom, 0.1);
  EXPECT_DOUBLE_EQ(d.height, 0.5);
  EXPECT_DOUBLE_EQ(d.growth, 0.01);
  EXPECT_DOUBLE_EQ(d.drift.x(), 0.2);
  EXPECT_DOUBLE_EQ(d.drift.y(), -0.1);
  EXPECT_NEAR(signed_area(d.outline), 2.0, 1e-12);  // 2 x 1 m, counter-clockwise
  EXPECT_EQ(d.source.line, 6);
  const MediumSpec& smoke = w.media[1];
  EXPECT_EQ(smoke.kind, MediumSpec::Kind::smoke);
  EXPECT_EQ(smoke.name, "smoke_2");
  EXPECT_DOUBLE_EQ(smoke.height, 2.0);
  EXPECT_FALSE(validate(w).has_errors());
}

TEST(ScenarioMedia, ImpossibleValuesNameTheKeyAndLine) {
  const std::string neg = error_of(std::string(kMaze) + "    - outline: [[0, 0], [1, 0], [0, 1]]\n      density: -1\n");
  EXPECT_NE(neg.find("s.yaml:7"), std::string::npos) << neg;
  EXPECT_NE(neg.find("world.media[0].density"), std::string::npos) << neg;
  EXPECT_NE(neg.find("out of range"), std::string::npos) << neg;
  const std::string nan = error_of(std::string(kMaze) + "    - outline: [[0, 0], [1, 0], [0, 1]]\n      density: .nan\n");
  EXPECT_NE(nan.find("expected a finite number"), std::string::npos) << nan;
  const std::string flat = error_of(std::string(kMaze) + "    - outline: [[0, 0], [1, 0], [0, 1]]\n      density: 1\n      height: 0\n");
  EXPECT_NE(flat.find("world.media[0].height"), std::string::npos) << flat;
  const std::string two = error_of(std::string(kMaze) + "    - outline: [[0, 0], [1, 0]]\n      density: 1\n");
  EXPECT_NE(two.find("s.yaml:6"), std::string::npos) << two;
  EXPECT_NE(two.find("the footprint has 2 points; expected at least 3"), std::string::npos) << two;
  const std::string shrink =
      error_of(std::string(kMaze) + "    - outline: [[0, 0], [1, 0], [0, 1]]\n      density: 1\n      growth: -0.1\n");
  EXPECT_NE(shrink.find("world.media[0].growth"), std::string::npos) << shrink;
  const std::string point = error_of(std::string(kMaze) + "    - outline: [[0, 0], [1, x], [0, 1]]\n      density: 1\n");
  EXPECT_NE(point.find("expected a point [x, y] of two finite numbers"), std::string::npos) << point;
  const std::string unknown =
      error_of(std::string(kMaze) + "    - outline: [[0, 0], [1, 0], [0, 1]]\n      density: 1\n      colour: grey\n");
  EXPECT_NE(unknown.find("world.media[0].colour"), std::string::npos) << unknown;
}

}  // namespace
}  // namespace rescuesim
