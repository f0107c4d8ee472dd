// A realtime `rescuesim run --record` killed with SIGKILL loses at most about one chunk budget
// of sim time: the run is stopped (SIGSTOP, so nothing more reaches the file) once it reports
// 2.5 s of sim time, killed, its .part recovered by `rescuesim recover`, and the result read by
// the reference npm reader (McapIndexedReader, chunk CRCs checked, every message decoded).
// The sim time reached comes from the run's own progress line (printed when stderr is a
// terminal, so the run is given one with script(1)), not from the wall clock, so a slow machine
// cannot fail the test: only the chunk budgets bound what is lost.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>

#include "mcap_test_support.h"

namespace rescuesim {
namespace {

using nlohmann::json;

/// The last sim time a progress line in `log` shows ("[###---]   2.6/600 s ..."), or -1.
double last_progress(const std::string& log) {
  static const std::regex line(R"(\]\s+([0-9]+\.[0-9])/600 s)");
  double t = -1;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), line); it != std::sregex_iterator(); ++it) t = std::stod((*it)[1]);
  return t;
}

TEST(RecoverKilledRun, LosesAtMostAChunkBudgetOfSimTime) {
  const auto modules = std::filesystem::path(RESCUESIM_JS_DIR) / "node_modules";
  if (testing::run_command("node --version").exit_code != 0 || !std::filesystem::exists(modules / "@mcap/core")) {
    GTEST_SKIP() << "node or @mcap/core missing (scripts/install-test-js.sh installs it)";
  }
  if (testing::run_command("script --version && pgrep --version").exit_code != 0) GTEST_SKIP() << "script(1) or pgrep missing";
  const auto dir = testing::temp_dir("mcap-kill-recover");
  const std::string rec = (dir / "killed.mcap").string(), part = rec + ".part", log = (dir / "tty.log").string();
  // budgets of 1 s of sim time and 1 s of wall time; stop once 2.5 s of sim time are reported;
  // script(1) itself does not end with its child when its stdin is /dev/null, so it is killed too
  const std::string run = std::string("exec '") + RESCUESIM_EXE + "' run --realtime --duration 600 --no-cameras --record '" + rec +
                          "' --record-chunk-seconds 1 --record-chunk-wall-seconds 1 --out '" + (dir / "out").string() + "'";
  const auto r = testing::run_command("script -qfc \"" + run + "\" '" + log + "' </dev/null >/dev/null 2>&1 & s=$!; p=; " +
                                      "for i in $(seq 1 1200); do p=$(pgrep -P $s); " + "t=$(tr '\\r' '\\n' < '" + log +
                                      "' 2>/dev/null | grep -o '[0-9.]*/600 s' | tail -1 | cut -d/ -f1); " +
                                      "[ -n \"$t\" ] && awk -v t=\"$t\" 'BEGIN { exit !(t >= 2.5) }' && break; sleep 0.05; done; " +
                                      "kill -STOP $p; sleep 0.5; kill -9 $p; sleep 0.2; kill -9 $s 2>/dev/null; wait $s; true");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double reached = last_progress(testing::slurp(log));
  ASSERT_GE(reached, 2.5) << testing::slurp(log);
  ASSERT_TRUE(std::filesystem::exists(part));
  EXPECT_FALSE(std::filesystem::exists(rec));

  const auto recovered = testing::rescuesim("recover '" + part + "'");
  ASSERT_EQ(recovered.exit_code, 0) << recovered.err;
  ASSERT_TRUE(std::filesystem::exists(rec)) << recovered.out;
  const auto node = testing::run_command("NODE_PATH='" + modules.string() + "' timeout 120 node '" + RESCUESIM_SOURCE_DIR +
                                         "/tests/bridges/mcap/read_recording.js' '" + rec + "'");
  ASSERT_EQ(node.exit_code, 0) << node.err;
  const json seen = json::parse(node.out);
  ASSERT_FALSE(seen.contains("error")) << seen.dump().substr(0, 400);
  EXPECT_EQ(seen["dataSectionCrc"]["stored"], seen["dataSectionCrc"]["computed"]);
  EXPECT_TRUE(seen["logTimesInOrder"].get<bool>());
  EXPECT_EQ(seen["statistics"]["chunkCount"], seen["chunks"]);
  std::uint64_t read = 0;
  for (const auto& [topic, c] : seen["channels"].items()) {
    EXPECT_EQ(c["read"], c["statistics"]) << topic;
    EXPECT_EQ(c["decodeErrors"], 0) << topic << ": " << c["firstError"];
    read += c["read"].get<std::uint64_t>();
  }
  EXPECT_EQ(read, seen["statistics"]["messageCount"].get<std::uint64_t>());
  ASSERT_TRUE(seen["channels"].contains("/clock"));
  EXPECT_GT(seen["channels"]["/clock"]["read"].get<int>(), 0);

  // sim time reached when stopped: at least `reached`, at most one progress line later (64
  // steps, 0.32 s) plus a margin. The chunk open at the stop began at most one sim-time budget
  // (1 s) before its newest message, and the recorder's queue holds at most a few ms of messages;
  // everything before it is on disk. So the file ends within 1 s + 0.5 s margin of `reached`.
  const double end = seen["statistics"]["endTime"].get<double>() * 1e-9;
  EXPECT_LE(end, reached + 0.5) << recovered.out;
  EXPECT_GE(end, reached - 1.5) << recovered.out;
  EXPECT_EQ(seen["statistics"]["startTime"].get<double>(), 0.0);
}

}  // namespace
}  // namespace rescuesim
