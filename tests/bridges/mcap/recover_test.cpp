// Recovering a cut recording: a file of 8 one-second chunks (5 messages each, see
// chunk_budget_test.cpp) is cut at chosen offsets, as a killed writer would leave it, and
// recovered; what survives is counted by hand from where the cut falls. Bad input is refused
// with the file named, by the library and by `rescuesim recover` (exit code 2).

#include "bridges/mcap/mcap_recover.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "mcap_test_support.h"

namespace rescuesim::mcap {
namespace {

constexpr std::uint64_t kSecond = 1'000'000'000;

/// Metadata, an attachment, then 40 messages at log times 0, 0.25, …, 9.75 s on /a (even) and
/// /b (odd), in zstd chunks closed every second of log time: 8 chunks of 5 messages.
std::vector<std::uint8_t> eight_chunk_file() {
  std::vector<std::uint8_t> bytes;
  WriterOptions o;
  o.library = "test";
  o.chunk_log_seconds = 1.0;
  McapWriter w(std::make_unique<MemorySink>(bytes), o);
  w.write_metadata({"rescuesim", {{"seed", "3"}}});
  w.write_attachment({0, 0, "world.svg", "image/svg+xml", {'<', 's', 'v', 'g', '/', '>'}});
  const std::uint16_t s = w.add_schema("pkg/msg/T", "ros2msg", "int32 a");
  const std::uint16_t a = w.add_channel(s, "/a", "cdr");
  const std::uint16_t b = w.add_channel(s, "/b", "cdr");
  for (int i = 0; i < 40; ++i) {
    const std::uint8_t data[4] = {static_cast<std::uint8_t>(i), 1, 2, 3};
    const auto t = static_cast<std::uint64_t>(i) * kSecond / 4;
    w.write_message(i % 2 ? b : a, static_cast<std::uint32_t>(i / 2 + 1), t, t, data);
  }
  w.close();
  return bytes;
}

class Recover : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::temp_dir("mcap-recover");
    whole_ = eight_chunk_file();
    testing::write_bytes(dir_ / "whole.mcap", whole_);
    McapReader r(dir_ / "whole.mcap");
    chunks_ = r.chunk_indexes();
    ASSERT_EQ(chunks_.size(), 8u);
    original_ = testing::all_messages(r);
  }
  /// Writes the first `n` bytes of the file as cut.mcap.part and recovers it to cut.mcap.
  RecoveryReport recover_first(std::uint64_t n) {
    const auto part = dir_ / "cut.mcap.part";
    testing::write_bytes(part, std::vector<std::uint8_t>(whole_.begin(), whole_.begin() + static_cast<long>(n)));
    std::filesystem::remove(dir_ / "cut.mcap");
    return recover_mcap(part, dir_ / "cut.mcap");
  }
  /// The recovered file, checked by the strict reader: its messages must be the original's first `n`.
  void expect_first_messages(std::size_t n) {
    McapReader r(dir_ / "cut.mcap");
    ASSERT_TRUE(r.statistics());
    EXPECT_EQ(r.statistics()->message_count, n);
    EXPECT_EQ(r.chunk_indexes().size(), r.chunk_count());
    EXPECT_EQ(r.header().library, "test");
    ASSERT_TRUE(r.find_metadata("rescuesim"));
    EXPECT_EQ(r.find_metadata("rescuesim")->entries.at(0).second, "3");
    ASSERT_TRUE(r.find_attachment("world.svg"));
    ASSERT_TRUE(r.find_metadata("rescuesim.recovery"));
    const auto messages = testing::all_messages(r);
    ASSERT_EQ(messages.size(), n);
    EXPECT_TRUE(std::equal(messages.begin(), messages.end(), original_.begin()));
    if (n > 0) {
      EXPECT_EQ(r.statistics()->message_end_time, original_[n - 1].log_time);
    }
  }
  std::filesystem::path dir_;
  std::vector<std::uint8_t> whole_;
  std::vector<ChunkIndex> chunks_;
  std::vector<testing::ReadMessage> original_;
};

TEST_F(Recover, ACutThroughAChunkKeepsTheChunksBeforeIt) {
  // cut 20 bytes into chunk 5 (0-based): chunks 0-4 survive, 25 messages, the last at 6.0 s
  const std::uint64_t cut = chunks_[5].chunk_start_offset + 20;
  const RecoveryReport r = recover_first(cut);
  EXPECT_FALSE(r.finished);
  EXPECT_EQ(r.chunks_read, 5u);
  EXPECT_EQ(r.messages, 25u);
  EXPECT_EQ(r.channels, 2u);
  EXPECT_EQ(r.schemas, 1u);
  EXPECT_EQ(r.metadata, 1u);
  EXPECT_EQ(r.attachments, 1u);
  EXPECT_EQ(r.start_time, 0u);
  EXPECT_EQ(r.end_time, 6 * kSecond);
  EXPECT_EQ(r.messages_per_topic.at("/a"), 13u);  // messages 0, 2, …, 24
  EXPECT_EQ(r.messages_per_topic.at("/b"), 12u);
  EXPECT_EQ(r.kept_bytes, chunks_[5].chunk_start_offset);
  EXPECT_EQ(r.dropped_bytes(), 20u);
  EXPECT_NE(r.dropped_reason.find("offset " + std::to_string(chunks_[5].chunk_start_offset) + " (Chunk)"), std::string::npos)
      << r.dropped_reason;
  expect_first_messages(25);
}

TEST_F(Recover, ACutThroughTheMessageIndexesKeepsTheirChunk) {
  // the writer flushes a chunk and then its message indexes: a cut 5 bytes into those keeps chunk 5
  const std::uint64_t cut = chunks_[5].chunk_start_offset + chunks_[5].chunk_length + 5;
  const RecoveryReport r = recover_first(cut);
  EXPECT_EQ(r.chunks_read, 6u);
  EXPECT_EQ(r.messages, 30u);
  EXPECT_EQ(r.end_time, 7 * kSecond + kSecond / 4);  // 5 * 1.25 + 1
  EXPECT_NE(r.dropped_reason.find("(Message Index)"), std::string::npos) << r.dropped_reason;
  expect_first_messages(30);
}

TEST_F(Recover, ACutBeforeAnyChunkGivesAFileWithoutMessages) {
  const RecoveryReport r = recover_first(chunks_[0].chunk_start_offset + 3);
  EXPECT_EQ(r.messages, 0u);
  EXPECT_EQ(r.channels, 0u);
  expect_first_messages(0);
}

TEST_F(Recover, AChunkWithAWrongCrcAndEverythingAfterItIsDropped) {
  // chunk 3's stored CRC (9 + 8 + 8 + 8 bytes into the record) no longer matches its records
  auto bad = whole_;
  const std::size_t crc_at = chunks_[3].chunk_start_offset + 9 + 24;
  testing::put_u32_at(bad, crc_at, testing::u32_at(bad, crc_at) ^ 0xFFFF);
  testing::write_bytes(dir_ / "cut.mcap.part", bad);
  const RecoveryReport r = recover_mcap(dir_ / "cut.mcap.part", dir_ / "cut.mcap");
  EXPECT_EQ(r.chunks_read, 3u);
  EXPECT_EQ(r.messages, 15u);
  EXPECT_NE(r.dropped_reason.find("CRC-32"), std::string::npos) << r.dropped_reason;
  expect_first_messages(15);
}

TEST_F(Recover, AFinishedFileIsCopiedWhole) {
  const RecoveryReport r = recover_mcap(dir_ / "whole.mcap", dir_ / "cut.mcap");
  EXPECT_TRUE(r.finished);
  EXPECT_EQ(r.messages, 40u);
  EXPECT_EQ(r.chunks_read, 8u);
  EXPECT_EQ(r.dropped_reason, "");
  expect_first_messages(40);
}

/// The text of the Error recover_mcap throws for a file holding `bytes`.
std::string refusal(const std::filesystem::path& dir, const std::string& bytes) {
  const auto p = dir / "bad.mcap.part";
  testing::write_text(p, bytes);
  try {
    recover_mcap(p, dir / "bad.mcap");
  } catch (const Error& e) {
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.mcap"));
    return e.what();
  }
  return "(no error)";
}

TEST_F(Recover, RefusesWhatIsNotARecording) {
  EXPECT_NE(refusal(dir_, "").find("bad.mcap.part: the file is empty"), std::string::npos) << refusal(dir_, "");
  EXPECT_NE(refusal(dir_, "hello, world").find("not an MCAP file"), std::string::npos);
  EXPECT_NE(refusal(dir_, "\x89MCAP").find("ends 5 bytes into the 8-byte MCAP magic"), std::string::npos) << refusal(dir_, "\x89MCAP");
  const std::string magic_and_half_header(whole_.begin(), whole_.begin() + 8 + 9 + 3);
  EXPECT_NE(refusal(dir_, magic_and_half_header).find("no complete Header record"), std::string::npos);
}

TEST_F(Recover, TheCommandWritesFileMcapAndSaysWhatItDropped) {
  const auto part = dir_ / "run.mcap.part";
  testing::write_bytes(part,
                       std::vector<std::uint8_t>(whole_.begin(), whole_.begin() + static_cast<long>(chunks_[5].chunk_start_offset + 20)));
  std::filesystem::remove(dir_ / "run.mcap");
  const auto r = testing::rescuesim("recover '" + part.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "run.mcap"));
  EXPECT_NE(r.out.find("25 messages on 2 channels"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0.000 .. 6.000 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("dropped       20 of"), std::string::npos) << r.out;
  // once there, it is not overwritten unless asked
  const auto again = testing::rescuesim("recover '" + part.string() + "'");
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.err.find("exists already"), std::string::npos) << again.err;
  EXPECT_EQ(testing::rescuesim("recover --force '" + part.string() + "'").exit_code, 0);
}

TEST_F(Recover, TheCommandRefusesBadInputWithExitCode2) {
  testing::write_text(dir_ / "empty.mcap.part", "");
  const auto r = testing::rescuesim("recover '" + (dir_ / "empty.mcap.part").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("empty.mcap.part: the file is empty"), std::string::npos) << r.err;
  const auto missing = testing::rescuesim("recover '" + (dir_ / "nothing.mcap.part").string() + "'");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("nothing.mcap.part: no such file"), std::string::npos) << missing.err;
}

TEST_F(Recover, ReplayOfAPartFileSaysToRecoverIt) {
  const auto part = dir_ / "cut.mcap.part";
  testing::write_bytes(part,
                       std::vector<std::uint8_t>(whole_.begin(), whole_.begin() + static_cast<long>(chunks_[5].chunk_start_offset + 20)));
  const auto r = testing::rescuesim("replay '" + part.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("rescuesim recover"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rescuesim::mcap
