// CRC-32 as MCAP (and zlib, PNG, Ethernet) computes it.

#include "bridges/mcap/crc32.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace rescuesim::mcap {
namespace {

std::span<const std::uint8_t> bytes(const std::string& s) { return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()}; }

TEST(Crc32, StandardCheckValue) {
  // the catalogued check value of CRC-32/ISO-HDLC
  EXPECT_EQ(crc32(bytes("123456789")), 0xCBF43926u);
  EXPECT_EQ(crc32(bytes("")), 0u);
  EXPECT_EQ(crc32(bytes("a")), 0xE8B7BE43u);
  EXPECT_EQ(crc32(bytes("The quick brown fox jumps over the lazy dog")), 0x414FA339u);
}

TEST(Crc32, PiecesGiveTheSameValueAsTheWhole) {
  std::vector<std::uint8_t> data(1000);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(i * 37 + 11);
  const std::uint32_t whole = crc32(data);
  for (std::size_t cut : {0, 1, 7, 8, 9, 500, 999, 1000}) {
    Crc32 c;
    c.update(std::span(data).first(cut));
    c.update(std::span(data).subspan(cut));
    EXPECT_EQ(c.value(), whole) << cut;
  }
}

TEST(Crc32, AgreesWithBitwiseDefinitionOnOddLengths) {
  // the slicing-by-8 tables against the bit-by-bit definition
  const auto slow = [](std::span<const std::uint8_t> b) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (std::uint8_t x : b) {
      c ^= x;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    }
    return ~c;
  };
  std::vector<std::uint8_t> data;
  for (int n = 0; n < 70; ++n) {
    data.push_back(static_cast<std::uint8_t>(n * n + 3));
    EXPECT_EQ(crc32(data), slow(data)) << n;
  }
}

}  // namespace
}  // namespace rescuesim::mcap
