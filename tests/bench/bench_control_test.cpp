// `rescuesim bench --control-only`, short: 3 resets, 3 single steps, one 200-step goal and 2 spawns over
// ROS 2 on loopback. Which figures it reports and how many calls each counts, and that the
// goal's 200 steps leave the run in the state 200 lockstep steps give; no speed.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/command.h"

namespace rescuesim {
namespace {

using nlohmann::json;

TEST(BenchControl, ReportsEachFigureBesideItsBaseline) {
  const testing::CommandResult r = testing::rescuesim(
      "bench --control-only --control-resets 3 --control-steps 3 --control-action-steps 200 --control-rounds 1 --control-spawns 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out)["control"];
  if (j.contains("skipped")) GTEST_SKIP() << j["skipped"];
  ASSERT_FALSE(j.contains("error")) << j["error"];
  for (const char* key : {"reset_simulation", "step_simulation", "simulate_steps", "spawn_entity"}) {
    ASSERT_TRUE(j.contains(key)) << key;
    for (const char* field : {"value", "unit", "baseline", "baseline_is", "ratio", "meets_target"}) {
      EXPECT_TRUE(j[key].contains(field)) << key << "." << field;
    }
  }
  const json& reset = j["reset_simulation"];
  EXPECT_EQ(reset["round_trip"]["calls"], 3);
  EXPECT_EQ(reset["restore"]["calls"], 3);
  EXPECT_EQ(reset["target_ms"], 5.0);
  EXPECT_GT(reset["rebuild_ms"].get<double>(), 0.0);
  const json& step = j["step_simulation"];
  EXPECT_EQ(step["round_trip"]["calls"], 3);
  EXPECT_EQ(step["in_process_step"]["calls"], 3);
  EXPECT_EQ(step["target_ms"], 1.0);
  const json& action = j["simulate_steps"];
  EXPECT_EQ(action["steps"], 200);
  EXPECT_EQ(action["action_wall_s"].size(), 1u);
  EXPECT_EQ(action["lockstep_wall_s"].size(), 1u);
  EXPECT_EQ(action["target_ratio"], 0.9);
  // 200 steps from PAUSED are 200 lockstep steps, bitwise (issue 37)
  EXPECT_EQ(action["same_state_hash"], true);
  // 2 spawns and deletes over the wire (after a warm-up pair), 2 in-process
  const json& spawn = j["spawn_entity"];
  EXPECT_EQ(spawn["round_trip"]["calls"], 2);
  EXPECT_EQ(spawn["delete_round_trip"]["calls"], 2);
  EXPECT_EQ(spawn["add_robot"]["calls"], 2);
  EXPECT_EQ(spawn["remove_robot"]["calls"], 2);
  EXPECT_GT(j["peak_memory_mb"].get<double>(), 0.0);
  EXPECT_GT(j["client_peak_memory_mb"].get<double>(), 0.0);
}

TEST(BenchControl, ACountOfZeroIsAUsageError) {
  const testing::CommandResult r = testing::rescuesim("bench --control-only --control-resets 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--control-resets"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rescuesim
