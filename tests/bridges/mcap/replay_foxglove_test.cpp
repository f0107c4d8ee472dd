// `rescuesim replay --foxglove` seen by the reference Foxglove WebSocket client: the recording's
// scans arrive and decode, the server's time follows the recording, and a /cmd_vel sent during
// the replay is ignored (and said so).

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/local_ports.h"
#include "mcap_test_support.h"

namespace rescuesim {
namespace {

TEST(ReplayFoxglove, ClientSeesTheRecording) {
  const auto modules = std::filesystem::path(RESCUESIM_JS_DIR) / "node_modules";
  if (testing::run_command("node --version").exit_code != 0) GTEST_SKIP() << "node is not installed";
  if (!std::filesystem::exists(modules / "@foxglove/ws-protocol") || !std::filesystem::exists(modules / "ws")) {
    GTEST_SKIP() << "@foxglove/ws-protocol or ws is not in " << modules << " (scripts/install-test-js.sh installs them)";
  }
  if (testing::rescuesim("replay --help").out.find("--foxglove") == std::string::npos) GTEST_SKIP() << "built without the Foxglove bridge";
  const auto dir = testing::temp_dir("mcap-replay-foxglove");
  const std::string file = (dir / "run.mcap").string();
  ASSERT_EQ(testing::rescuesim("run --duration 4 --no-cameras -q --record '" + file + "' --out '" + (dir / "out").string() + "'").exit_code,
            0);

  // the client starts first and retries until the server is up; the replay takes 4 s
  const int port = free_local_port();  // a port the kernel has just handed out, not one from the pid
  const std::string script = std::string(RESCUESIM_SOURCE_DIR) + "/tests/bridges/mcap/replay_foxglove.js";
  const auto r = testing::run_command("( NODE_PATH='" + modules.string() + "' timeout 60 node '" + script +
                                      "' ws://127.0.0.1:" + std::to_string(port) + " 6 > '" + (dir / "client.json").string() +
                                      "' & c=$!; sleep 0.5; '" + RESCUESIM_EXE + "' replay '" + file + "' --foxglove " +
                                      std::to_string(port) + " -q; e=$?; wait $c; exit $e )");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("commands received through foxglove are ignored"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("replayed 2374 messages"), std::string::npos) << r.out;
  const auto seen = nlohmann::json::parse(testing::slurp(dir / "client.json"));
  ASSERT_TRUE(seen["connected"].get<bool>()) << seen.dump();
  EXPECT_EQ(seen["error"], "");
  EXPECT_TRUE(seen["sentCmdVel"].get<bool>());
  // 41 scans in 4 s at 10 Hz; the client misses the first ones while it connects
  EXPECT_GE(seen["scans"].get<int>(), 25) << seen.dump();
  EXPECT_LE(seen["scans"].get<int>(), 41);
  EXPECT_EQ(seen["scan"]["ranges"], 541);
  EXPECT_EQ(seen["scan"]["frameId"], "laser");
  EXPECT_EQ(seen["scan"]["stamp"], 4e9);
  EXPECT_EQ(seen["lastClock"], 4e9);
  // the server's time is the replayed sim time
  EXPECT_GT(seen["maxTime"].get<double>(), 3.9e9);
  EXPECT_LE(seen["maxTime"].get<double>(), 4e9);
}

}  // namespace
}  // namespace rescuesim
