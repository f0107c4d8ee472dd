// A scenario's `mission:` block: presets, overrides, radio parameters, bases, and a clear
// error naming the key for each class of bad input.

#include <gtest/gtest.h>

#include "import/scenario/scenario.h"
#include "robots/rescue_robot.h"

namespace rescuesim {
namespace {

Scenario parse(const std::string& yaml) { return parse_scenario(yaml, "m.yaml", builtin_models()); }

std::string error_of(const std::string& yaml) {
  try {
    parse(yaml);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioMission, NoBlockMeansNoMission) { EXPECT_FALSE(parse("seed: 3\n").mission.has_value()); }

TEST(ScenarioMission, AnEmptyBlockIsRoboCupRulesWithAnIdealRadio) {
  const Scenario s = parse("mission: {}\n");
  ASSERT_TRUE(s.mission.has_value());
  EXPECT_EQ(s.mission->rules.preset, "robocup");
  EXPECT_EQ(s.mission->rules.report_radius_m, 1.5);
  EXPECT_EQ(s.mission->rules.false_report_penalty, 0.5);
  EXPECT_EQ(s.mission->rules.report_limit, 0);
  EXPECT_EQ(s.mission->radio.model.kind, RadioModelKind::ideal);
  EXPECT_EQ(s.mission->radio.link_rate_hz, 10);
  EXPECT_TRUE(s.mission->bases.empty());
}

TEST(ScenarioMission, PresetThenOverridesThenRadioParameters) {
  const Scenario s = parse(
      "mission:\n"
      "  rules: subt\n"
      "  report_limit: 12\n"
      "  time_limit: 600\n"
      "  radio:\n"
      "    model: wss\n"
      "    link_rate: 5\n"
      "    relays_per_robot: 4\n"
      "    wall_loss_db: 8\n"
      "    max_walls: 3\n"
      "  base: {x: 1.5, y: -2}\n");
  const MissionSpec& m = *s.mission;
  EXPECT_EQ(m.rules.preset, "subt");
  EXPECT_EQ(m.rules.report_radius_m, 5.0);  // from the preset
  EXPECT_EQ(m.rules.report_limit, 12);      // overridden
  EXPECT_EQ(m.rules.time_limit_s, 600);
  EXPECT_EQ(m.radio.model.kind, RadioModelKind::wss);
  EXPECT_EQ(m.radio.model.wss.wall_loss_db, 8);
  EXPECT_EQ(m.radio.model.wss.max_walls, 3);
  EXPECT_EQ(m.radio.model.wss.p0_dbm, -49.67);  // untouched default
  EXPECT_EQ(m.radio.link_rate_hz, 5);
  EXPECT_EQ(m.radio.relays_per_robot, 4);
  ASSERT_EQ(m.bases.size(), 1u);
  EXPECT_EQ(m.bases[0].name, "base");
  EXPECT_EQ(m.bases[0].p_W, Vec3(1.5, -2, 1.0));  // z defaults to 1 m
}

TEST(ScenarioMission, SeveralNamedBases) {
  const Scenario s = parse("mission:\n  bases:\n    - {name: north, x: 0, y: 9, z: 2}\n    - {x: 0, y: -9}\n");
  ASSERT_EQ(s.mission->bases.size(), 2u);
  EXPECT_EQ(s.mission->bases[0].name, "north");
  EXPECT_EQ(s.mission->bases[1].name, "base2");
  EXPECT_NE(error_of("mission:\n  bases:\n    - {name: b, x: 0, y: 0}\n    - {name: b, x: 1, y: 0}\n").find("two bases are named 'b'"),
            std::string::npos);
}

TEST(ScenarioMission, UnknownKeysAreNamedWithTheirPath) {
  EXPECT_NE(error_of("mission:\n  report_radiuss: 2\n").find("mission.report_radiuss"), std::string::npos)
      << error_of("mission:\n  report_radiuss: 2\n");
  EXPECT_NE(error_of("mission:\n  radio: {model: wss, colour: red}\n").find("mission.radio.colour"), std::string::npos);
}

TEST(ScenarioMission, AParameterOfTheOtherModelIsRefusedNamingIt) {
  const std::string e = error_of("mission:\n  radio:\n    model: wss\n    sigma_db: 4\n");
  EXPECT_NE(e.find("m.yaml:4"), std::string::npos) << e;
  EXPECT_NE(e.find("sigma_db"), std::string::npos) << e;
}

TEST(ScenarioMission, ImpossibleRadioParametersAreListed) {
  const std::string e = error_of("mission:\n  radio:\n    model: subt\n    capacity_bps: 0\n    n: -1\n");
  EXPECT_NE(e.find("impossible radio parameters"), std::string::npos) << e;
  EXPECT_NE(e.find("radio.subt.capacity_bps"), std::string::npos) << e;
  EXPECT_NE(e.find("radio.subt.n"), std::string::npos) << e;
}

TEST(ScenarioMission, OutOfRangeAndWrongChoicesSayWhatIsExpected) {
  EXPECT_NE(error_of("mission:\n  report_radius: 0\n").find("report_radius"), std::string::npos);
  EXPECT_NE(error_of("mission:\n  report_rate: -2\n").find("report_rate"), std::string::npos);
  EXPECT_NE(error_of("mission:\n  rules: vrc\n").find("robocup"), std::string::npos);
  EXPECT_NE(error_of("mission:\n  radio: {model: wifi}\n").find("wss"), std::string::npos);
  EXPECT_NE(error_of("mission:\n  base: {x: 1}\n").find("mission.base.y"), std::string::npos);
  EXPECT_NE(error_of("mission:\n  base: {x: 1, y: 1}\n  bases: []\n").find("not both"), std::string::npos);
  EXPECT_NE(error_of("mission:\n  base: {name: a/b, x: 1, y: 1}\n").find("plain word"), std::string::npos);
  EXPECT_NE(error_of("mission: 3\n").find("mission"), std::string::npos);
}

TEST(ScenarioMission, TheShippedTeamScenarioHasAWssMission) {
  const Scenario s = load_scenario(RESCUESIM_SOURCE_DIR "/worlds/team.yaml", builtin_models());
  ASSERT_TRUE(s.mission.has_value());
  EXPECT_EQ(s.mission->radio.model.kind, RadioModelKind::wss);
  EXPECT_EQ(s.robots.size(), 3u);
  ASSERT_TRUE(s.maze.has_value());
  EXPECT_EQ(s.maze->cols, 12);
  EXPECT_EQ(s.maze->victims, 6);
}

}  // namespace
}  // namespace rescuesim
