// The MCAP writer's byte layout, checked against offsets and lengths computed by hand from the
// spec (https://mcap.dev/spec) for a file with one schema, one channel and three messages.

#include "bridges/mcap/mcap_writer.h"

#include <gtest/gtest.h>

#include "bridges/mcap/crc32.h"
#include "mcap_test_support.h"

namespace rescuesim::mcap {
namespace {

using testing::u32_at;
using testing::u64_at;

/// ros2 profile, library "test", uncompressed chunks: 1 schema, 1 channel, 3 messages.
std::vector<std::uint8_t> three_message_file(Compression compression = Compression::none) {
  std::vector<std::uint8_t> bytes;
  WriterOptions o;
  o.library = "test";
  o.compression = compression;
  McapWriter w(std::make_unique<MemorySink>(bytes), o);
  const std::uint16_t s = w.add_schema("pkg/msg/T", "ros2msg", "int32 a");
  const std::uint16_t c = w.add_channel(s, "/t", "cdr");
  const std::uint8_t data[4] = {1, 2, 3, 4};
  for (std::uint32_t i = 1; i <= 3; ++i) w.write_message(c, i, 10 * i, 10 * i - 5, data);
  w.close();
  return bytes;
}

TEST(McapWriter, HeaderBytes) {
  const auto b = three_message_file();
  // magic, then Header: opcode 01, length 16 = (4 + "ros2") + (4 + "test")
  const std::vector<std::uint8_t> expected = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n', 0x01, 16, 0, 0, 0, 0, 0, 0, 0,
                                              4,    0,   0,   0,   'r', 'o', 's', '2', 4,    0,  0, 0, 't', 'e', 's', 't'};
  ASSERT_GE(b.size(), expected.size());
  EXPECT_EQ(std::vector<std::uint8_t>(b.begin(), b.begin() + static_cast<long>(expected.size())), expected);
}

TEST(McapWriter, LayoutComputedByHand) {
  const auto b = three_message_file();
  // records inside the chunk: Schema 9 + 2 + (4+9) + (4+7) + (4+7) = 46; Channel 9 + 2 + 2 +
  // (4+2) + (4+3) + 4 = 30; each Message 9 + 2 + 4 + 8 + 8 + 4 = 35: 181 bytes in all
  // Chunk record at 33: 9 + 8 + 8 + 8 + 4 + (4+0) + 8 + 181 = 230 -> Message Index at 263
  // (9 + 2 + 4 + 3 * 16 = 63) -> Data End at 326 (13) -> summary at 339
  ASSERT_EQ(b.size(), 704u);
  EXPECT_EQ(b[33], 0x06);
  EXPECT_EQ(u64_at(b, 34), 221u);
  EXPECT_EQ(u64_at(b, 42), 10u);   // message_start_time
  EXPECT_EQ(u64_at(b, 50), 30u);   // message_end_time
  EXPECT_EQ(u64_at(b, 58), 181u);  // uncompressed_size
  const std::size_t records = 33 + 9 + 8 + 8 + 8 + 4 + 4 + 8;
  EXPECT_EQ(u32_at(b, 66), crc32(std::span(b).subspan(records, 181)));
  EXPECT_EQ(u32_at(b, 70), 0u);    // compression ""
  EXPECT_EQ(u64_at(b, 74), 181u);  // records length

  // the second message record, byte for byte: offset 46 + 30 + 35 in the chunk's records
  const std::vector<std::uint8_t> message = {0x05, 26, 0, 0, 0, 0, 0, 0, 0,  // opcode, length 26
                                             1,    0,                         // channel 1
                                             2,    0, 0, 0,                   // sequence 2
                                             20,   0, 0, 0, 0, 0, 0, 0,       // log_time 20
                                             15,   0, 0, 0, 0, 0, 0, 0,       // publish_time 15
                                             1,    2, 3, 4};
  EXPECT_EQ(std::vector<std::uint8_t>(b.begin() + static_cast<long>(records + 111), b.begin() + static_cast<long>(records + 146)), message);

  // the message index: channel 1, entries (10, 76), (20, 111), (30, 146)
  EXPECT_EQ(b[263], 0x07);
  EXPECT_EQ(u64_at(b, 264), 54u);
  EXPECT_EQ(u32_at(b, 274), 48u);
  EXPECT_EQ(u64_at(b, 278), 10u);
  EXPECT_EQ(u64_at(b, 286), 76u);
  EXPECT_EQ(u64_at(b, 310), 30u);
  EXPECT_EQ(u64_at(b, 318), 146u);

  // Data End holds the CRC of everything before it
  EXPECT_EQ(b[326], 0x0F);
  EXPECT_EQ(u32_at(b, 335), crc32(std::span(b).first(326)));

  // summary: Schema (46) at 339, Channel (30) at 385, Statistics (9 + 42 + 4 + 10 = 65) at
  // 415, Chunk Index (9 + 32 + 14 + 8 + 4 + 16 = 83) at 480; four Summary Offsets (26 each)
  // at 563; Footer at 667; magic at 696
  EXPECT_EQ(b[339], 0x03);
  EXPECT_EQ(b[385], 0x04);
  EXPECT_EQ(b[415], 0x0B);
  EXPECT_EQ(u64_at(b, 424), 3u);  // message_count
  EXPECT_EQ(b[480], 0x08);
  EXPECT_EQ(u64_at(b, 480 + 9 + 16), 33u);   // chunk_start_offset
  EXPECT_EQ(u64_at(b, 480 + 9 + 24), 230u);  // chunk_length
  EXPECT_EQ(b[563], 0x0E);
  EXPECT_EQ(b[563 + 9], 0x03);              // the Schema group...
  EXPECT_EQ(u64_at(b, 563 + 10), 339u);     // ...starts at 339
  EXPECT_EQ(u64_at(b, 563 + 18), 46u);      // ...and is 46 bytes long
  EXPECT_EQ(b[667], 0x02);
  EXPECT_EQ(u64_at(b, 676), 339u);  // summary_start
  EXPECT_EQ(u64_at(b, 684), 563u);  // summary_offset_start
  EXPECT_EQ(u32_at(b, 692), crc32(std::span(b).subspan(339, 667 + 25 - 339)));
  EXPECT_TRUE(std::equal(kMagic.begin(), kMagic.end(), b.end() - 8));
}

TEST(McapWriter, ReadsBackThroughTheReader) {
  for (Compression c : {Compression::none, Compression::zstd, Compression::lz4}) {
    const auto dir = testing::temp_dir("mcap-roundtrip");
    const auto path = dir / "three.mcap";
    testing::write_bytes(path, three_message_file(c));
    McapReader r(path);
    EXPECT_EQ(r.header().profile, "ros2");
    EXPECT_EQ(r.header().library, "test");
    ASSERT_EQ(r.schemas().size(), 1u);
    EXPECT_EQ(r.schemas().at(1).name, "pkg/msg/T");
    ASSERT_EQ(r.channels().size(), 1u);
    EXPECT_EQ(r.channels().at(1).topic, "/t");
    ASSERT_TRUE(r.statistics());
    EXPECT_EQ(r.statistics()->message_count, 3u);
    EXPECT_EQ(r.statistics()->channel_message_counts.at(1), 3u);
    EXPECT_EQ(r.chunk_count(), 1u);
    const auto messages = testing::all_messages(r);
    ASSERT_EQ(messages.size(), 3u);
    EXPECT_EQ(messages[2], (testing::ReadMessage{"/t", 3, 30, 25, {1, 2, 3, 4}}));
    EXPECT_EQ(r.stored_data_crc(), r.computed_data_crc());
  }
}

TEST(McapWriter, ChunksFillAndEachIsIndexed) {
  std::vector<std::uint8_t> bytes;
  WriterOptions o;
  o.chunk_size = 4096;
  McapWriter w(std::make_unique<MemorySink>(bytes), o);
  const std::uint16_t c1 = w.add_channel(w.add_schema("a/msg/A", "ros2msg", ""), "/a", "cdr");
  const std::uint16_t c2 = w.add_channel(w.add_schema("b/msg/B", "ros2msg", ""), "/b", "cdr");
  std::vector<std::uint8_t> data(300);
  for (std::uint32_t i = 0; i < 100; ++i) {
    for (auto& x : data) x = static_cast<std::uint8_t>(i);
    w.write_message(i % 3 ? c1 : c2, i, 1000 + i, 1000 + i, data);
  }
  w.close();
  // messages of 9 + 26 + 300 = 335 bytes, chunks closed at 4096: the first holds the schema
  // and channel records (2 * 37 + 2 * 30 = 134 bytes) and 12 messages, the next ones 13 each
  // (6 of them), the last the 10 left: 8 chunks
  EXPECT_EQ(w.stats().chunks, 8u);
  const auto path = testing::temp_dir("mcap-chunks") / "chunks.mcap";
  testing::write_bytes(path, bytes);
  McapReader r(path);
  ASSERT_EQ(r.chunk_indexes().size(), 8u);
  for (const auto& ci : r.chunk_indexes()) {
    EXPECT_EQ(ci.compression, "zstd");
    EXPECT_LT(ci.compressed_size, ci.uncompressed_size);
    EXPECT_FALSE(ci.message_index_offsets.empty());
  }
  const auto messages = testing::all_messages(r);
  ASSERT_EQ(messages.size(), 100u);
  for (std::uint32_t i = 0; i < 100; ++i) {
    EXPECT_EQ(messages[i].log_time, 1000 + i);
    EXPECT_EQ(messages[i].topic, i % 3 ? "/a" : "/b");
    EXPECT_EQ(messages[i].data[299], static_cast<std::uint8_t>(i));
  }
  EXPECT_EQ(r.statistics()->channel_message_counts.at(c1), 66u);
  EXPECT_EQ(r.statistics()->channel_message_counts.at(c2), 34u);
}

TEST(McapWriter, MetadataAndAttachmentsAreIndexed) {
  std::vector<std::uint8_t> bytes;
  {
    McapWriter w(std::make_unique<MemorySink>(bytes));
    w.write_metadata({"run", {{"seed", "7"}, {"scenario", "default"}}});
    w.write_attachment({0, 0, "scenario.yaml", "application/yaml", {'a', ':', ' ', '1'}});
  }  // the destructor closes the file
  const auto path = testing::temp_dir("mcap-meta") / "meta.mcap";
  testing::write_bytes(path, bytes);
  McapReader r(path);
  ASSERT_NE(r.find_metadata("run"), nullptr);
  EXPECT_EQ(r.find_metadata("run")->entries[0], (std::pair<std::string, std::string>{"seed", "7"}));
  ASSERT_NE(r.find_attachment("scenario.yaml"), nullptr);
  EXPECT_EQ(r.find_attachment("scenario.yaml")->data.size(), 4u);
  EXPECT_EQ(r.statistics()->metadata_count, 1u);
  EXPECT_EQ(r.statistics()->attachment_count, 1u);
}

TEST(McapWriter, SameInputGivesTheSameBytes) {
  EXPECT_EQ(three_message_file(Compression::zstd), three_message_file(Compression::zstd));
}

}  // namespace
}  // namespace rescuesim::mcap
