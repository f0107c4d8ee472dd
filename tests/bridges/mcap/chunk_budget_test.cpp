// The writer closes a chunk on a time budget as well as on size, so a killed recording loses at
// most about one budget of messages: log (sim) time, deterministic, and wall time, through an
// injected clock here. Chunk counts and spans below follow from the message times by hand.

#include <gtest/gtest.h>

#include "mcap_test_support.h"

namespace rescuesim::mcap {
namespace {

constexpr std::uint64_t kSecond = 1'000'000'000;

/// 40 messages of 4 bytes on one channel, log times 0, 0.25, …, 9.75 s, through `o`
/// (uncompressed chunks); `before_each(i)` runs before message i is written.
std::vector<std::uint8_t> quarter_second_file(WriterOptions o, const std::function<void(int)>& before_each = {}) {
  std::vector<std::uint8_t> bytes;
  o.compression = Compression::none;
  McapWriter w(std::make_unique<MemorySink>(bytes), o);
  const std::uint16_t c = w.add_channel(w.add_schema("pkg/msg/T", "ros2msg", "int32 a"), "/t", "cdr");
  for (int i = 0; i < 40; ++i) {
    if (before_each) before_each(i);
    const std::uint8_t data[4] = {static_cast<std::uint8_t>(i), 0, 0, 0};
    w.write_message(c, static_cast<std::uint32_t>(i + 1), static_cast<std::uint64_t>(i) * kSecond / 4,
                    static_cast<std::uint64_t>(i) * kSecond / 4, data);
  }
  w.close();
  return bytes;
}

std::vector<ChunkIndex> chunk_indexes(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  const auto path = testing::temp_dir("mcap-budget") / name;
  testing::write_bytes(path, bytes);
  McapReader r(path);
  EXPECT_EQ(r.statistics()->message_count, 40u);
  return r.chunk_indexes();
}

TEST(ChunkBudget, WithoutTimeBudgetsOneChunkHoldsEverything) {
  // 40 messages of 35 bytes are far below the 1 MiB size budget
  EXPECT_EQ(chunk_indexes(quarter_second_file({}), "none.mcap").size(), 1u);
}

TEST(ChunkBudget, LogTimeBudgetClosesAChunkPerSecondOfLogTime) {
  WriterOptions o;
  o.chunk_log_seconds = 1.0;
  const auto chunks = chunk_indexes(quarter_second_file(o), "log.mcap");
  // a chunk starting at t closes with the message at t + 1 s: 5 messages (t, t+.25, …, t+1),
  // the next starts at t + 1.25 s; 40 messages make exactly 8 chunks, the last closed by the
  // message at 9.75 s, leaving nothing for close()
  ASSERT_EQ(chunks.size(), 8u);
  for (std::size_t k = 0; k < chunks.size(); ++k) {
    EXPECT_EQ(chunks[k].message_start_time, k * 5 * kSecond / 4) << "chunk " << k;
    EXPECT_EQ(chunks[k].message_end_time, k * 5 * kSecond / 4 + kSecond) << "chunk " << k;
  }
}

TEST(ChunkBudget, LogTimeBudgetIsDeterministic) {
  WriterOptions o;
  o.chunk_log_seconds = 1.0;
  EXPECT_EQ(quarter_second_file(o), quarter_second_file(o));
}

TEST(ChunkBudget, WallTimeBudgetUsesTheWallClockNotTheLogTimes) {
  // a wall clock advancing 0.3 s per message and a 1 s budget: a chunk opened at wall time w
  // closes with the first message at or after w + 1 s, its 5th (w + 1.2 s); the log-time budget
  // is off, so the log times (0.25 s apart) play no part: 40 / 5 = 8 chunks of 1.0 s of log time
  double now = 0;
  WriterOptions o;
  o.chunk_wall_seconds = 1.0;
  o.wall_clock = [&now] { return now; };
  const auto chunks = chunk_indexes(quarter_second_file(o, [&now](int i) { now = 0.3 * i; }), "wall.mcap");
  ASSERT_EQ(chunks.size(), 8u);
  EXPECT_EQ(chunks[1].message_start_time, 5 * kSecond / 4);
  EXPECT_EQ(chunks[1].message_end_time, 2 * kSecond + kSecond / 4);

  // the same messages arriving 0.125 s apart: 9 per chunk (w, w + 0.125, …, w + 1.0 s): 4 × 9,
  // then the 4 left, written by close()
  const auto fewer = chunk_indexes(quarter_second_file(o, [&now](int i) { now = 0.125 * i; }), "wall-fast.mcap");
  EXPECT_EQ(fewer.size(), 5u);
}

TEST(ChunkBudget, SizeStillClosesChunksUnderATimeBudget) {
  // 35-byte messages and a 100-byte chunk size: the schema and channel records (46 + 30 = 76
  // bytes) plus one message pass 100, then every 3rd message does (105): 1 + 39 / 3 = 14 chunks,
  // each spanning at most 0.5 s, so the 1 s log-time budget never closes one
  WriterOptions o;
  o.chunk_log_seconds = 1.0;
  o.chunk_size = 100;
  EXPECT_EQ(chunk_indexes(quarter_second_file(o), "size.mcap").size(), 14u);
}

}  // namespace
}  // namespace rescuesim::mcap
