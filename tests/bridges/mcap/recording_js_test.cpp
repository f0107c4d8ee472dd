// `rescuesim run --record` read by the reference npm clients: McapIndexedReader (@mcap/core +
// @mcap/nodejs + @mcap/support) opens it through its summary, checks the summary and chunk
// CRCs, and every message decodes with @foxglove/rosmsg + @foxglove/rosmsg2-serialization.
// The node side (read_recording.js) only reports; the figures are checked here.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "bridges/mcap/crc32.h"
#include "mcap_test_support.h"

namespace rescuesim {
namespace {

using nlohmann::json;

const std::filesystem::path kScript = std::filesystem::path(RESCUESIM_SOURCE_DIR) / "tests/bridges/mcap/read_recording.js";

/// Why the npm clients cannot run here ("" when they can).
std::string js_missing() {
  if (testing::run_command("node --version").exit_code != 0) return "node is not installed";
  const auto modules = std::filesystem::path(RESCUESIM_JS_DIR) / "node_modules";
  for (const char* m : {"@mcap/core", "@mcap/nodejs", "@mcap/support", "@foxglove/rosmsg", "@foxglove/rosmsg2-serialization"}) {
    if (!std::filesystem::exists(modules / m)) {
      return std::string(m) + " is not in " + modules.string() + " (scripts/install-test-js.sh installs it)";
    }
  }
  return "";
}

/// What read_recording.js saw in `file` (`mode`: "" or "--stream").
json read_with_node(const std::filesystem::path& file, const std::string& mode = "") {
  // a time limit, so a stuck reader fails the test instead of hanging it
  const auto r = testing::run_command("NODE_PATH='" + std::string(RESCUESIM_JS_DIR) + "/node_modules' timeout 120 node '" +
                                      kScript.string() + "' '" + file.string() + "' " + mode);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return json::parse(r.out);
}

class NpmReaders : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    missing_ = js_missing();
    if (!missing_.empty()) return;
    dir_ = testing::temp_dir("mcap-js");
    const auto r = testing::rescuesim("run --duration 2 --no-cameras -q --record '" + (dir_ / "run.mcap").string() + "' --out '" +
                                      (dir_ / "out").string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    seen_ = read_with_node(dir_ / "run.mcap");
  }
  void SetUp() override {
    if (!missing_.empty()) GTEST_SKIP() << missing_;
    ASSERT_FALSE(seen_.contains("error")) << seen_.dump();
  }
  static inline std::string missing_;
  static inline std::filesystem::path dir_;
  static inline json seen_;
};

TEST_F(NpmReaders, IndexedReaderSeesChannelsSchemasAndCounts) {
  EXPECT_EQ(seen_["header"]["profile"], "ros2");
  EXPECT_EQ(seen_["header"]["library"], std::string("rescuesim ") + "0.1.0");
  EXPECT_EQ(seen_["compression"], json::array({"zstd"}));
  // summary offsets for schemas, channels, chunk indexes, attachment and metadata indexes, statistics
  EXPECT_EQ(seen_["summaryOffsets"], json::array({3, 4, 8, 10, 11, 13}));
  // a 2 s lockstep run at dt 5 ms: each f Hz stream publishes at t = 0 and every 1/f s up to
  // and including t = 2 s, so 2 f + 1 messages: /scan (10 Hz) 21, not 20
  const std::map<std::string, std::pair<std::string, int>> expected = {
      {"/clock", {"rosgraph_msgs/msg/Clock", 401}},        {"/scan", {"sensor_msgs/msg/LaserScan", 21}},
      {"/sonar/front_left", {"sensor_msgs/msg/Range", 21}}, {"/sonar/rear_right", {"sensor_msgs/msg/Range", 21}},
      {"/imu/data", {"sensor_msgs/msg/Imu", 201}},          {"/odom", {"nav_msgs/msg/Odometry", 101}},
      {"/ground_truth/pose", {"geometry_msgs/msg/PoseStamped", 101}},
      {"/joint_states", {"sensor_msgs/msg/JointState", 41}}, {"/tf", {"tf2_msgs/msg/TFMessage", 202}},
      {"/tf_static", {"tf2_msgs/msg/TFMessage", 1}}};
  const json& ch = seen_["channels"];
  for (const auto& [topic, e] : expected) {
    ASSERT_TRUE(ch.contains(topic)) << topic;
    EXPECT_EQ(ch[topic]["schemaName"], e.first) << topic;
    EXPECT_EQ(ch[topic]["schemaEncoding"], "ros2msg") << topic;
    EXPECT_EQ(ch[topic]["messageEncoding"], "cdr") << topic;
    EXPECT_EQ(ch[topic]["statistics"], e.second) << topic;
    EXPECT_EQ(ch[topic]["read"], e.second) << topic;
  }
  int total = 0;
  for (const auto& [topic, c] : ch.items()) {
    EXPECT_EQ(c["decodeErrors"], 0) << topic << ": " << c["firstError"];
    EXPECT_EQ(c["read"], c["statistics"]) << topic;
    total += c["read"].get<int>();
  }
  EXPECT_EQ(total, seen_["statistics"]["messageCount"].get<int>());
  EXPECT_EQ(seen_["statistics"]["chunkCount"], seen_["chunks"]);
  EXPECT_EQ(seen_["statistics"]["endTime"], 2'000'000'000);
  EXPECT_TRUE(seen_["logTimesInOrder"].get<bool>());
  EXPECT_EQ(seen_["metadata"]["rescuesim"]["seed"], "7");
  EXPECT_EQ(seen_["metadata"]["rescuesim"]["scenario"], "default");
  EXPECT_EQ(seen_["attachments"]["world.svg"]["mediaType"], "image/svg+xml");
}

TEST_F(NpmReaders, ScansDecodeToTheLaserTheyCameFrom) {
  const json& scans = seen_["scans"];
  ASSERT_EQ(scans.size(), 21u);
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const json& s = scans[k];
    EXPECT_EQ(s["sequence"], k + 1);
    EXPECT_EQ(s["logTime"], static_cast<std::int64_t>(k) * 100'000'000);  // 10 Hz from t = 0
    EXPECT_EQ(s["publishTime"], s["stamp"]);
    EXPECT_EQ(s["stamp"], s["logTime"]);
    // the rescue robot's laser: 541 beams over 270 degrees, so 0.5 degrees apart
    EXPECT_EQ(s["ranges"], 541);
    EXPECT_EQ(s["frameId"], "laser");
    EXPECT_NEAR(s["angleIncrement"].get<double>(), M_PI / 360, 1e-7);
    EXPECT_NEAR(s["angleMin"].get<double>(), -0.75 * M_PI, 1e-6);
  }
}

TEST_F(NpmReaders, DataSectionCrcMatches) {
  EXPECT_NE(seen_["dataSectionCrc"]["stored"], 0);
  EXPECT_EQ(seen_["dataSectionCrc"]["stored"], seen_["dataSectionCrc"]["computed"]);
}

TEST_F(NpmReaders, TheReaderChecksChunkAndSummaryCrcs) {
  // the same file with a wrong chunk CRC: the reader refuses the chunk when it reads it
  auto bytes = testing::read_bytes(dir_ / "run.mcap");
  const std::size_t chunk = testing::first_record(bytes, mcap::Op::chunk);  // after the run's metadata and attachments
  ASSERT_EQ(bytes[chunk], 0x06);
  auto bad = bytes;
  testing::put_u32_at(bad, chunk + 9 + 24, testing::u32_at(bad, chunk + 9 + 24) ^ 1);
  testing::write_bytes(dir_ / "bad-chunk-crc.mcap", bad);
  const json a = read_with_node(dir_ / "bad-chunk-crc.mcap");
  EXPECT_NE(a.value("error", "").find("Incorrect chunk CRC"), std::string::npos) << a.dump().substr(0, 300);
  // a flipped byte in the summary: refused when opened
  bad = bytes;
  bad[bad.size() - 100] ^= 1;
  testing::write_bytes(dir_ / "bad-summary.mcap", bad);
  const json b = read_with_node(dir_ / "bad-summary.mcap");
  EXPECT_NE(b.value("error", "").find("Incorrect summary CRC"), std::string::npos) << b.dump().substr(0, 300);
}

TEST_F(NpmReaders, StreamReaderReadsTheWholeFile) {
  const json s = read_with_node(dir_ / "run.mcap", "--stream");
  EXPECT_EQ(s["error"], "");
  EXPECT_EQ(s["messages"], seen_["statistics"]["messageCount"]);
  EXPECT_TRUE(s["footer"].get<bool>());
}

TEST_F(NpmReaders, AKilledRunLeavesAStreamReadablePartFile) {
  // kill -9 a long recording once a few chunks are on disk
  const auto dir = testing::temp_dir("mcap-killed");
  const std::string part = (dir / "killed.mcap.part").string();
  const auto r = testing::run_command(std::string("( '") + RESCUESIM_EXE + "' run --duration 600 --no-cameras -q --record '" +
                                      (dir / "killed.mcap").string() + "' --out '" + (dir / "out").string() + "' & p=$!; " +
                                      "for i in $(seq 1 600); do s=$(stat -c %s '" + part + "' 2>/dev/null || echo 0); " +
                                      "[ \"$s\" -gt 600000 ] && break; sleep 0.05; done; kill -9 $p; wait $p; true ) >/dev/null 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(std::filesystem::exists(part));
  EXPECT_FALSE(std::filesystem::exists(dir / "killed.mcap"));  // never a file that looks finished
  const json s = read_with_node(part, "--stream");
  EXPECT_EQ(s["error"], "") << s.dump();
  EXPECT_FALSE(s["footer"].get<bool>());
  EXPECT_GT(s["messages"].get<int>(), 2000);  // at least a chunk's worth (~0.5 MB of small messages)
}

}  // namespace
}  // namespace rescuesim
