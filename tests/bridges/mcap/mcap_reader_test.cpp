// The strict reader against damaged files: each kind of damage gives an Error naming the file,
// the offset and the problem; no damage crashes it or goes unnoticed.

#include "bridges/mcap/mcap_reader.h"

#include <gtest/gtest.h>

#include "bridges/mcap/crc32.h"
#include "core/error.h"
#include "mcap_test_support.h"

namespace rescuesim::mcap {
namespace {

using testing::read_bytes;
using testing::write_bytes;

class McapReaderBadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::temp_dir("mcap-reader");
    WriterOptions o;
    o.chunk_size = 200;  // several chunks
    McapWriter w(std::make_unique<MemorySink>(good_), o);
    const std::uint16_t c = w.add_channel(w.add_schema("pkg/msg/T", "ros2msg", "int32 a"), "/t", "cdr");
    const std::uint8_t data[40] = {7};
    for (std::uint32_t i = 1; i <= 12; ++i) w.write_message(c, i, 100 * i, 100 * i, data);
    w.write_metadata({"rescuesim", {{"seed", "1"}}});
    w.close();
  }
  /// Opens `bytes` as a file and reads every message; returns the error text ("" if none).
  std::string error_of(const std::vector<std::uint8_t>& bytes, const std::string& name = "bad.mcap") {
    const auto path = dir_ / name;
    write_bytes(path, bytes);
    try {
      McapReader r(path);
      testing::all_messages(r);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
  std::filesystem::path dir_;
  std::vector<std::uint8_t> good_;
};

TEST_F(McapReaderBadInput, GoodFileReads) {
  EXPECT_EQ(error_of(good_), "");
  const auto path = dir_ / "good.mcap";
  write_bytes(path, good_);
  McapReader r(path);
  EXPECT_GT(r.chunk_count(), 2u);
  EXPECT_EQ(testing::all_messages(r).size(), 12u);
}

TEST_F(McapReaderBadInput, NotAnMcapFileSaysWhatItStartsWith) {
  const std::string text = "hello: world\n";
  const std::string e = error_of({text.begin(), text.end()}, "notes.yaml");
  EXPECT_NE(e.find("notes.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("not an MCAP file"), std::string::npos) << e;
  EXPECT_NE(e.find("68 65 6C 6C"), std::string::npos) << e;  // "hell"
}

TEST_F(McapReaderBadInput, Ros1BagIsNamed) {
  const std::string text = "#ROSBAG V2.0\nxxxxxxxxxxxxxxxx";
  const std::string e = error_of({text.begin(), text.end()}, "old.bag");
  EXPECT_NE(e.find("ROS 1 bag"), std::string::npos) << e;
}

TEST_F(McapReaderBadInput, MagicCutAfterItsFifthByte) {
  // found by the mcap_reader fuzz target: the version byte was read past the end
  const std::string text = "\x89MCAP";
  const std::string e = error_of({text.begin(), text.end()}, "cut.mcap");
  EXPECT_NE(e.find("cut.mcap"), std::string::npos) << e;
  EXPECT_NE(e.find("not an MCAP file"), std::string::npos) << e;
}

TEST_F(McapReaderBadInput, EmptyFile) {
  const std::string e = error_of({}, "empty.mcap");
  EXPECT_NE(e.find("empty.mcap"), std::string::npos) << e;
  EXPECT_NE(e.find("empty"), std::string::npos) << e;
}

TEST_F(McapReaderBadInput, MissingFile) {
  try {
    McapReader r(dir_ / "nowhere.mcap");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere.mcap: no such file"), std::string::npos) << e.what();
  }
}

TEST_F(McapReaderBadInput, EveryTruncationIsAnErrorNamingTheRecord) {
  for (std::size_t n = 0; n < good_.size(); ++n) {
    const std::string e = error_of({good_.begin(), good_.begin() + static_cast<long>(n)});
    ASSERT_FALSE(e.empty()) << "cut at " << n << " went unnoticed";
    EXPECT_NE(e.find("bad.mcap"), std::string::npos) << e;
    if (n > 50) {
      EXPECT_NE(e.find("truncated"), std::string::npos) << n << ": " << e;
    }
  }
  // half a file: the chunk it cuts through is named with its offset
  const std::string half = error_of({good_.begin(), good_.begin() + static_cast<long>(good_.size() / 2)});
  EXPECT_NE(half.find("offset "), std::string::npos) << half;
  EXPECT_NE(half.find("(Chunk)"), std::string::npos) << half;
}

TEST_F(McapReaderBadInput, EveryFlippedByteIsNoticed) {
  // the data-section CRC covers everything before Data End, the summary CRC everything after
  for (std::size_t i = 0; i < good_.size(); ++i) {
    auto bad = good_;
    bad[i] ^= 0x5A;
    EXPECT_NE(error_of(bad), "") << "a flipped byte at " << i << " went unnoticed";
  }
}

TEST_F(McapReaderBadInput, CorruptDataSectionNamesTheCrc) {
  auto bad = good_;
  bad[100] ^= 1;
  const std::string e = error_of(bad);
  EXPECT_NE(e.find("(Data End): the data section's CRC-32 is 0x"), std::string::npos) << e;
}

TEST_F(McapReaderBadInput, CorruptSummaryNamesTheCrc) {
  auto bad = good_;
  bad[bad.size() - 60] ^= 1;
  const std::string e = error_of(bad);
  EXPECT_NE(e.find("(Footer): the summary's CRC-32"), std::string::npos) << e;
}

TEST_F(McapReaderBadInput, WrongChunkCrcIsFoundWhenTheChunkIsRead) {
  // a chunk whose stored CRC is wrong, in a file whose data-section CRC is made to agree
  auto bad = good_;
  const std::size_t chunk = 8 + 9 + mcap::load_u64(bad.data() + 9);  // after the header
  ASSERT_EQ(bad[chunk], 0x06);
  testing::put_u32_at(bad, chunk + 9 + 24, testing::u32_at(bad, chunk + 9 + 24) ^ 0xFFFF);
  const std::size_t data_end = testing::u64_at(bad, bad.size() - 8 - 20) - kDataEndRecordSize;
  ASSERT_EQ(bad[data_end], 0x0F);
  testing::put_u32_at(bad, data_end + 9, crc32(std::span(bad).first(data_end)));
  const std::string e = error_of(bad);
  EXPECT_NE(e.find("offset " + std::to_string(chunk) + " (Chunk): the CRC-32 of its uncompressed records"), std::string::npos) << e;
}

TEST_F(McapReaderBadInput, HugeClaimedChunkIsRefused) {
  auto bad = good_;
  const std::size_t chunk = 8 + 9 + mcap::load_u64(bad.data() + 9);
  for (int k = 0; k < 8; ++k) bad[chunk + 9 + 16 + static_cast<std::size_t>(k)] = 0x7F;  // uncompressed_size
  const std::string e = error_of(bad);
  EXPECT_NE(e.find("over this reader's limit"), std::string::npos) << e;
}

}  // namespace
}  // namespace rescuesim::mcap
