// Scenario YAML: defaults, paths, and a clear error naming the key path for each class of
// bad input.

#include "import/scenario/scenario.h"

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
  for (const char* f : {"default.yaml", "arena.yaml", "office.yaml", "smoke_corridor.yaml", "smoke_victim.yaml", "ground_materials.yaml"}) {
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

TEST(Scenario, AComplexKeyIsAnErrorNotACrash) {
  // "? key" makes a map the key (legal YAML; found by the scenario fuzz target)
  const std::string e = error_of("name: x\nworld:\n? maze:\n    cols: 8\n");
  EXPECT_NE(e.find("s.yaml:3"), std::string::npos) << e;
  EXPECT_NE(e.find("plain name"), std::string::npos) << e;
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

TEST(Scenario, PhysicsGroupsAreACountOfWorldsOrZeroForAutomatic) {
  EXPECT_EQ(parse_scenario("physics:\n  groups: 4\n", "s.yaml", builtin_models()).physics_groups, 4);
  EXPECT_EQ(parse_scenario("name: x\n", "s.yaml", builtin_models()).physics_groups, 0);
  for (const char* bad : {"physics:\n  groups: -1\n", "physics:\n  groups: 257\n", "physics:\n  groups: two\n"}) {
    const std::string e = error_of(bad);
    EXPECT_NE(e.find("physics.groups"), std::string::npos) << bad << ": " << e;
  }
}

TEST(Scenario, StartCellOutsideTheGrid) {
  const std::string e = error_of("world:\n  maze:\n    cols: 3\n    rows: 3\n    start_cell: [3, 0]\n");
  EXPECT_NE(e.find("world.maze.start_cell"), std::string::npos) << e;
}

TEST(Scenario, SvgAndMazeTogetherIsAnError) {
  EXPECT_NE(error_of("world:\n  svg: a.svg\n  maze: {cols: 3}\n").find("give one of world.svg, world.maze or world.sdf"),
            std::string::npos);
  EXPECT_NE(error_of("world:\n  sdf: a.sdf\n  maze: {cols: 3}\n").find("not several"), std::string::npos);
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

namespace rescuesim {
namespace {

std::string robot_error(const std::string& robot_yaml) {
  try {
    parse_scenario("robots:\n  - name: r1\n" + robot_yaml, "s.yaml", builtin_models());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioRobots, SensorSettingsAreApplied) {
  const Scenario s = parse_scenario(
      "robots:\n  - name: scout\n    controller: none\n    head: [10, 0, 90, -70]\n    sensors:\n"
      "      laser: {fov: 180, samples: 181, max_range: 8, noise: 0, rate: 20}\n      sonar_rear_left: {enabled: false}\n",
      "s.yaml", builtin_models());
  ASSERT_EQ(s.robots.size(), 1u);
  const RobotSpec& spec = s.robots[0].spec;
  const SensorSpec* laser = spec.find_sensor("laser");
  EXPECT_NEAR(laser->lidar.min_angle, -M_PI / 2, 1e-12);
  EXPECT_EQ(laser->lidar.samples, 181);
  EXPECT_DOUBLE_EQ(laser->lidar.max_range, 8);
  EXPECT_DOUBLE_EQ(laser->rate, 20);
  EXPECT_FALSE(spec.find_sensor("sonar_rear_left")->enabled);
  EXPECT_NEAR(spec.joints[static_cast<std::size_t>(spec.joint_index("mast_yaw"))].initial, 10 * M_PI / 180, 1e-12);
  EXPECT_EQ(s.robots[0].controller, "none");
}

TEST(ScenarioRobots, ZeroFieldOfViewIsRejected) {
  const std::string e = robot_error("    sensors:\n      laser: {fov: 0}\n");
  EXPECT_NE(e.find("robots[0].sensors.laser.fov"), std::string::npos) << e;
}

TEST(ScenarioRobots, NegativeRangeIsRejected) {
  const std::string e = robot_error("    sensors:\n      sonar_front_left: {min_range: -1}\n");
  EXPECT_NE(e.find("robots[0].sensors.sonar_front_left.min_range"), std::string::npos) << e;
}

TEST(ScenarioRobots, MinAboveMaxRangeIsRejected) {
  const std::string e = robot_error("    sensors:\n      laser: {min_range: 5, max_range: 2}\n");
  EXPECT_NE(e.find("must be below max_range"), std::string::npos) << e;
}

TEST(ScenarioRobots, ZeroRateIsRejected) {
  const std::string e = robot_error("    sensors:\n      imu: {rate: 0}\n");
  EXPECT_NE(e.find("robots[0].sensors.imu.rate"), std::string::npos) << e;
}

TEST(ScenarioRobots, UnknownSensorSettingIsNamed) {
  const std::string e = robot_error("    sensors:\n      laser: {resolution: 3}\n");
  EXPECT_NE(e.find("robots[0].sensors.laser.resolution"), std::string::npos) << e;
}

TEST(ScenarioRobots, UnknownSensorNameIsNamed) {
  const std::string e = robot_error("    sensors:\n      radar: {rate: 3}\n");
  EXPECT_NE(e.find("robots[0].sensors.radar"), std::string::npos) << e;
}

TEST(ScenarioRobots, UnknownModelAndController) {
  EXPECT_NE(robot_error("    model: tank\n").find("unknown robot model 'tank'"), std::string::npos);
  EXPECT_NE(robot_error("    controller: magic\n").find("robots[0].controller"), std::string::npos);
}

TEST(ScenarioRobots, HeadOutsideItsLimits) {
  EXPECT_NE(robot_error("    head: [0, 120, 0, 0]\n").find("shoulder_pitch"), std::string::npos);
}

TEST(ScenarioRobots, WrongTypeForASensorSetting) {
  const std::string e = robot_error("    sensors:\n      laser: {samples: many}\n");
  EXPECT_NE(e.find("robots[0].sensors.laser.samples"), std::string::npos) << e;
}

}  // namespace
}  // namespace rescuesim

namespace rescuesim {
namespace {

// `lamps:` on a robot: an item named as an existing lamp changes it (the rescue robot's
// head_lamp), any other is added on its link with its pose, cone and range; `lights: true` then
// switches them all on.
TEST(ScenarioRobots, LampsAreAddedAndChangedOnAnyLink) {
  const Scenario s = parse_scenario(
      "robots:\n  - name: scout\n    lights: true\n    lamps:\n"
      "      - {name: head_lamp, cone: 20, inner_cone: 10}\n"
      "      - {name: tail, link: base_link, pose: {x: -0.3, z: 0.2, yaw: 180}, color: [1, 0, 0], intensity: 2, range: 6, cone: 60}\n",
      "s.yaml", builtin_models());
  const RobotSpec& spec = s.robots[0].spec;
  ASSERT_EQ(spec.lights.size(), 2u);
  EXPECT_TRUE(spec.lights_on);
  EXPECT_EQ(spec.lights[0].name, "head_lamp");
  EXPECT_EQ(spec.lights[0].link, "head");  // kept
  EXPECT_NEAR(spec.lights[0].cone, 20 * M_PI / 180, 1e-12);
  EXPECT_NEAR(spec.lights[0].inner_cone, 10 * M_PI / 180, 1e-12);
  const RobotLightSpec& tail = spec.lights[1];
  EXPECT_EQ(tail.link, "base_link");
  EXPECT_LT((tail.X_LF.p - Vec3(-0.3, 0, 0.2)).norm(), 1e-12);
  EXPECT_LT((tail.X_LF.q * Vec3::UnitX() - Vec3(-1, 0, 0)).norm(), 1e-12);  // shines backwards
  EXPECT_EQ(tail.color, Vec3(1, 0, 0));
  EXPECT_DOUBLE_EQ(tail.intensity, 2);
  EXPECT_DOUBLE_EQ(tail.range, 6);
  EXPECT_NEAR(tail.cone, M_PI / 3, 1e-12);
  EXPECT_NEAR(tail.inner_cone, 0.3, 1e-12);  // the default core, within the cone
}

TEST(ScenarioRobots, BadLampsAreNamed) {
  const std::string link = robot_error("    lamps:\n      - {link: mast_top}\n");
  EXPECT_NE(link.find("lamp 'lamp_2': 'mast_top' is not a link of the robot (links: base_link"), std::string::npos) << link;
  const std::string wide = robot_error("    lamps:\n      - {name: head_lamp, cone: 10, inner_cone: 20}\n");
  EXPECT_NE(wide.find("robots[0].lamps[0].inner_cone"), std::string::npos) << wide;
  EXPECT_NE(wide.find("inner_cone 20 degrees is wider than its cone, 10"), std::string::npos) << wide;
  const std::string colour = robot_error("    lamps:\n      - {color: [1, 2, 0]}\n");
  EXPECT_NE(colour.find("color components are linear RGB in [0, 1]"), std::string::npos) << colour;
  const std::string cone = robot_error("    lamps:\n      - {cone: 120}\n");
  EXPECT_NE(cone.find("robots[0].lamps[0].cone"), std::string::npos) << cone;
  const std::string unknown = robot_error("    lamps:\n      - {colour: [1, 1, 1]}\n");
  EXPECT_NE(unknown.find("colour"), std::string::npos) << unknown;
  const std::string map = robot_error("    lamps: {link: base_link}\n");
  EXPECT_NE(map.find("lamps: expected a list"), std::string::npos) << map;
}

}  // namespace
}  // namespace rescuesim
