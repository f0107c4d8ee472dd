// Missions from the command line: `check` describes the rules, radio and base; `run` prints
// and writes the score (summary.json's mission section, score.png); bad mission blocks are
// input errors (exit 2) naming the key.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "support/command.h"

namespace rescuesim {
namespace {

using testing::rescuesim;
using testing::temp_dir;
using testing::write_text;

TEST(MissionCli, CheckDescribesTheShippedTeamScenario) {
  const auto r = rescuesim("check '" RESCUESIM_SOURCE_DIR "/worlds/team.yaml'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("robot starts  3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mission       robocup rules: victims within 1.5 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("radio         wss: -49.67 dBm at 2 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("base          base, 1 m above r1's start (1.25, 1.25) m"), std::string::npos) << r.out;
}

TEST(MissionCli, ARunWritesTheScoreAndItsFigure) {
  // two explorers in a 4 x 4 maze with two victims, 40 s, an ideal radio: every victim one of
  // them sees is reported, so the score is what the referee's counts say
  const auto dir = temp_dir("mission-run");
  write_text(dir / "m.yaml",
             "name: m\nseed: 5\nduration: 40\n"
             "world:\n  maze: {cols: 4, rows: 4, victims: 2, start_cells: [[0, 0], [1, 0]]}\n"
             "robots:\n  - {name: a}\n  - {name: b}\n"
             "mission: {}\n");
  const auto r = rescuesim("run --quiet '" + (dir / "m.yaml").string() + "' --out '" + (dir / "out").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("mission score "), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "score.png"));
  const auto j = nlohmann::json::parse(read_file(dir / "out" / "summary.json", 1 << 20));
  ASSERT_TRUE(j.contains("mission")) << j.dump(2);
  const auto& m = j["mission"];
  EXPECT_EQ(m["rules"], "robocup");
  EXPECT_EQ(m["radio_model"], "ideal");
  EXPECT_EQ(m["victims"], 2);
  EXPECT_EQ(m["robots"].size(), 2u);
  EXPECT_EQ(m["robots"][0]["contact_fraction"], 1.0);  // ideal: always in contact
  const double expected = m["reports"]["accepted"].get<double>() * 1.0 - m["reports"]["false"].get<double>() * 0.5;
  EXPECT_DOUBLE_EQ(m["score"].get<double>(), expected);
  EXPECT_EQ(m["victims_found"], m["reports"]["accepted"]);
  // every victim the run saw was reported by its finder, within the time left after the sighting
  EXPECT_LE(m["victims_found"].get<int>(), j["victims_found"].get<int>());
  // cameras render, so each report carries the finder's thermal frame of the sighting (the
  // rescue robot's 160 x 120 thermal camera), written as reports/<id>_<robot>_<outcome>.png
  ASSERT_GT(m["reports"]["charged"].get<int>(), 0) << "seed 5 sees and reports both victims";
  ASSERT_EQ(m["report_pictures"].size(), m["reports"]["charged"].get<std::size_t>()) << m.dump(2);
  for (const auto& p : m["report_pictures"]) {
    const std::string file = p["file"];
    EXPECT_EQ(file, "reports/" + std::to_string(p["report"].get<int>()) + "_" + p["robot"].get<std::string>() + "_" +
                        p["outcome"].get<std::string>() + ".png");
    const std::string png = read_file(dir / "out" / file, 1 << 20);
    ASSERT_GT(png.size(), 24u) << file;
    EXPECT_EQ(png.substr(1, 3), "PNG");
    const auto be32 = [&](std::size_t at) {
      return (static_cast<unsigned>(static_cast<unsigned char>(png[at])) << 24) | (static_cast<unsigned char>(png[at + 1]) << 16) |
             (static_cast<unsigned char>(png[at + 2]) << 8) | static_cast<unsigned char>(png[at + 3]);
    };
    EXPECT_EQ(be32(16), 160u) << file;  // IHDR width, height
    EXPECT_EQ(be32(20), 120u) << file;
  }
}

TEST(MissionCli, BadMissionBlocksAreInputErrors) {
  const auto dir = temp_dir("mission-bad");
  const auto run = [&](const std::string& yaml) {
    write_text(dir / "s.yaml", yaml);
    return rescuesim("run --duration 1 --quiet '" + (dir / "s.yaml").string() + "'");
  };
  auto r = run("mission:\n  radio:\n    model: subt\n    capacity_bps: -5\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("radio.subt.capacity_bps"), std::string::npos) << r.err;
  r = run("mission:\n  report_radius: -1\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("s.yaml:2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("mission.report_radius"), std::string::npos) << r.err;
  r = run("world:\n  maze: {cols: 3, rows: 3, start_cells: [[0, 0], [0, 0]]}\nrobots: [{name: a}, {name: b}]\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("already a start"), std::string::npos) << r.err;
  r = run("world:\n  maze: {cols: 3, rows: 3, start_cells: [[0, 0], [5, 0]]}\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not a cell of a 3 x 3 maze"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rescuesim
