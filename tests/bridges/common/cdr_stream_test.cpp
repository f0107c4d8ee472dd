// The CDR stream beneath the control codecs (bridges/common/cdr_stream.h), where the codecs'
// own tests do not reach: numbers stored and loaded in either byte order, the byte order an
// encapsulation header names, and a big-endian body (encapsulation 00 00) read only by a reader
// that takes either byte order, every number in that order; bytes worked out by hand.

#include "bridges/common/cdr_stream.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.h"

namespace rescuesim::cdr {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(CdrStream, NumbersAreStoredAndLoadedInEitherByteOrder) {
  Bytes b(8);
  store<std::uint64_t>(b.data(), 0x0102030405060708u, std::endian::little);
  EXPECT_EQ(b, (Bytes{0x08, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01}));
  EXPECT_EQ(load<std::uint64_t>(b.data(), std::endian::little), 0x0102030405060708u);
  EXPECT_EQ(load<std::uint64_t>(b.data(), std::endian::big), 0x0807060504030201u);
  store<std::int64_t>(b.data(), -2, std::endian::big);
  EXPECT_EQ(b, (Bytes{0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xfe}));
  EXPECT_EQ(load<std::int64_t>(b.data(), std::endian::big), -2);
  store(b.data(), 1.0, std::endian::big);  // IEEE 754: sign 0, exponent 0x3ff, mantissa 0
  EXPECT_EQ(b, (Bytes{0x3f, 0xf0, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(load<double>(b.data(), std::endian::big), 1.0);
  store<std::int16_t>(b.data(), -2, std::endian::little);
  EXPECT_EQ(b[0], 0xfe);
  EXPECT_EQ(b[1], 0xff);
}

TEST(CdrStream, TheEncapsulationHeaderNamesTheByteOrder) {
  EXPECT_EQ(xcdr1_byte_order(Bytes{0x00, 0x01, 0x00, 0x00}), std::endian::little);
  EXPECT_EQ(xcdr1_byte_order(Bytes{0x00, 0x00, 0x00, 0x03, 0x07}), std::endian::big);
  EXPECT_FALSE(xcdr1_byte_order(Bytes{0x00, 0x01, 0x00}));        // shorter than the header
  EXPECT_FALSE(xcdr1_byte_order(Bytes{0x00, 0x07, 0x00, 0x00}));  // CDR2_LE (XCDR2)
  EXPECT_FALSE(xcdr1_byte_order(Bytes{0x01, 0x01, 0x00, 0x00}));
  EXPECT_FALSE(xcdr1_byte_order(Bytes{}));
}

// uint8 u8 = 7; uint32 u32 = 0x01020304; string s = "ab"; float64 d = 1.0; int16[] q = {1, -2},
// big endian: u8 at 0, padding 1..3, u32 at 4, s's length 3 at 8, "ab\0" at 12..14, padding 15,
// d at 16, q's count 2 at 24, its elements at 28 and 30
const Bytes kBig = {0x00, 0x00, 0x00, 0x00,                          // encapsulation: CDR_BE
                    0x07, 0x00, 0x00, 0x00,                          // u8, padding
                    0x01, 0x02, 0x03, 0x04,                          // u32
                    0x00, 0x00, 0x00, 0x03, 'a', 'b', 0x00, 0x00,    // s, padding
                    0x3f, 0xf0, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // d
                    0x00, 0x00, 0x00, 0x02, 0x00, 0x01, 0xff, 0xfe};  // q

TEST(CdrStream, AReaderOfEitherByteOrderReadsABigEndianBodyInItsOrder) {
  Reader in(kBig, "Big", Encapsulations::either_endian);
  std::uint8_t u8 = 0;
  std::uint32_t u32 = 0;
  std::string s;
  double d = 0;
  std::vector<std::int16_t> q;
  in.value("u8", u8);
  in.value("u32", u32);
  in.string("s", s);
  in.value("d", d);
  in.sequence("q", q);
  EXPECT_NO_THROW(in.finish());
  EXPECT_EQ(u8, 7);
  EXPECT_EQ(u32, 0x01020304u);
  EXPECT_EQ(s, "ab");
  EXPECT_EQ(d, 1.0);
  EXPECT_EQ(q, (std::vector<std::int16_t>{1, -2}));
  // cut in d (body bytes 0..19): after s (at 15) come d's padding byte and its 8 bytes, 5 left
  const Bytes cut(kBig.begin(), kBig.begin() + 4 + 20);
  Reader short_in(cut, "Big", Encapsulations::either_endian);
  short_in.value("u8", u8);
  short_in.value("u32", u32);
  short_in.string("s", s);
  try {
    short_in.value("d", d);
    ADD_FAILURE() << "a double in 4 bytes was read";
  } catch (const Error& e) {
    EXPECT_EQ(e.message(), "Big: d: 9 bytes needed (1 of them alignment padding), 5 left");
  }
}

TEST(CdrStream, OnlyAReaderOfEitherByteOrderTakesBigEndian) {
  try {
    Reader in(kBig, "Big");
    ADD_FAILURE() << "a little-endian reader took 00 00";
  } catch (const Error& e) {
    EXPECT_EQ(e.message(), "Big: encapsulation 00 00 (big-endian CDR) is not supported; expected 00 01 (XCDR1 little endian)");
  }
  const Bytes xcdr2 = {0x00, 0x07, 0x00, 0x00};
  try {
    Reader in(xcdr2, "X", Encapsulations::either_endian);
    ADD_FAILURE() << "a reader of either byte order took 00 07";
  } catch (const Error& e) {
    EXPECT_EQ(e.message(),
              "X: encapsulation 00 07 is not supported; expected 00 01 (XCDR1 little endian) or 00 00 (XCDR1 big endian)");
  }
  // the little-endian reading of the same numbers
  const Bytes little = {0x00, 0x01, 0x00, 0x00, 0x07, 0x00, 0x00, 0x00, 0x04, 0x03, 0x02, 0x01};
  Reader in(little, "Little", Encapsulations::either_endian);
  std::uint8_t u8 = 0;
  std::uint32_t u32 = 0;
  in.value("u8", u8);
  in.value("u32", u32);
  EXPECT_EQ(u32, 0x01020304u);
  EXPECT_NO_THROW(in.finish());
}

}  // namespace
}  // namespace rescuesim::cdr
