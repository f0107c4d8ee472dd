// `rescuesim replay` as a user meets it: a good recording replays; a truncated file, a file that
// is not MCAP and one with a wrong CRC each give a clear error naming the file and the problem,
// with exit code 2 and no crash.

#include <gtest/gtest.h>

#include "bridges/mcap/mcap_records.h"
#include "mcap_test_support.h"

namespace rescuesim {
namespace {

using testing::rescuesim;

class ReplayCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = testing::temp_dir("mcap-replay-cli");
    const auto r = rescuesim("run --duration 2 --no-cameras -q --record '" + file("good.mcap") + "' --out '" + file("out") + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    good_ = testing::read_bytes(dir_ / "good.mcap");
  }
  static std::string file(const std::string& name) { return (dir_ / name).string(); }
  static testing::CommandResult replay_bytes(const std::string& name, const std::vector<std::uint8_t>& bytes) {
    testing::write_bytes(dir_ / name, bytes);
    return rescuesim("replay '" + file(name) + "' --rate 1000 -q");
  }
  static inline std::filesystem::path dir_;
  static inline std::vector<std::uint8_t> good_;
};

TEST_F(ReplayCli, GoodRecordingReplays) {
  const auto r = rescuesim("replay '" + file("good.mcap") + "' --rate 50 -q");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("scenario      default (seed 7)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("replayed 1194 messages (2.0 s of recording)"), std::string::npos) << r.out;
}

TEST_F(ReplayCli, ReplayCanBeRecordedAgain) {
  const auto r = rescuesim("replay '" + file("good.mcap") + "' --rate 50 -q --record '" + file("again.mcap") + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("bridge mcap: 1194 messages sent, 0 dropped"), std::string::npos) << r.out;
}

TEST_F(ReplayCli, TruncatedFileNamesTheRecordAndOffset) {
  const auto r = replay_bytes("cut.mcap", {good_.begin(), good_.begin() + static_cast<long>(good_.size() / 2)});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cut.mcap: offset "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(Chunk)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
}

TEST_F(ReplayCli, FileCutInTheSummaryIsTruncatedToo) {
  const auto r = replay_bytes("cut-end.mcap", {good_.begin(), good_.end() - 20});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cut-end.mcap"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
}

TEST_F(ReplayCli, NotAnMcapFile) {
  const std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\"/>";
  const auto r = replay_bytes("world.svg", {svg.begin(), svg.end()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("world.svg: offset 0: not an MCAP file: it starts with 3C 73 76 67"), std::string::npos) << r.err;
}

TEST_F(ReplayCli, WrongCrcNamesTheCrc) {
  auto bad = good_;
  bad[bad.size() / 3] ^= 0x10;
  const auto r = replay_bytes("flipped.mcap", bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("flipped.mcap: offset "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("CRC-32"), std::string::npos) << r.err;
}

TEST_F(ReplayCli, MissingFile) {
  const auto r = rescuesim("replay '" + file("nowhere.mcap") + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nowhere.mcap: no such file"), std::string::npos) << r.err;
}

TEST_F(ReplayCli, HelpTeachesWithExamples) {
  const auto r = rescuesim("replay --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("rescuesim replay runs/demo.mcap --foxglove"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--rate"), std::string::npos);
  EXPECT_EQ(r.out.find("--lockstep"), std::string::npos) << "a replay takes no steps";
  EXPECT_NE(rescuesim("run --help").out.find("--record"), std::string::npos);
}

}  // namespace
}  // namespace rescuesim
