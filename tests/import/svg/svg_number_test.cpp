#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "import/svg/svg_parse.h"

namespace rescuesim::svg {
namespace {

/// Reads one number from the start of `s`; `end` receives the position after it.
double first(std::string_view s, std::size_t* end = nullptr) {
  std::size_t pos = 0;
  const double v = read_number(s, pos);
  if (end) *end = pos;
  return v;
}

/// The ParseError that parsing `s` as one number throws (fails the test if none).
ParseError number_error(std::string_view s) {
  try {
    first(s);
  } catch (const ParseError& e) {
    return e;
  }
  ADD_FAILURE() << "no ParseError for '" << s << "'";
  return ParseError("", 0);
}

TEST(SvgNumber, ReadsEverySpelling) {
  std::size_t end = 0;
  EXPECT_EQ(first("42", &end), 42.0);
  EXPECT_EQ(end, 2u);
  EXPECT_EQ(first("-1.5e3"), -1500.0);
  EXPECT_EQ(first(".5"), 0.5);
  EXPECT_EQ(first("+2"), 2.0);
  EXPECT_EQ(first("1."), 1.0);
  EXPECT_EQ(first("1E+2"), 100.0);
  EXPECT_DOUBLE_EQ(first("1e-5"), 1e-5);
  EXPECT_EQ(first("-0"), 0.0);
  EXPECT_EQ(first("007"), 7.0);
}

TEST(SvgNumber, RunTogetherNumbersSplitWhereTheGrammarSays) {
  // "1.5.5": the second point starts a new number .5
  std::size_t pos = 0;
  EXPECT_EQ(read_number("1.5.5", pos), 1.5);
  EXPECT_EQ(pos, 3u);
  EXPECT_EQ(read_number("1.5.5", pos), 0.5);
  // "-1-2": a sign starts a new number
  pos = 0;
  EXPECT_EQ(read_number("-1-2", pos), -1.0);
  EXPECT_EQ(read_number("-1-2", pos), -2.0);
  // "1e2.5" is 100 then .5
  pos = 0;
  EXPECT_EQ(read_number("1e2.5", pos), 100.0);
  EXPECT_EQ(read_number("1e2.5", pos), 0.5);
}

TEST(SvgNumber, ExponentNeedsDigits) {
  // "1em": the e belongs to the unit; "2e+" likewise stops before the e
  std::size_t end = 0;
  EXPECT_EQ(first("1em", &end), 1.0);
  EXPECT_EQ(end, 1u);
  EXPECT_EQ(first("2e+", &end), 2.0);
  EXPECT_EQ(end, 1u);
}

TEST(SvgNumber, SkipsWhitespaceAndAtMostOneComma) {
  std::size_t end = 0;
  EXPECT_EQ(first(" \t, \n3", &end), 3.0);
  EXPECT_EQ(end, 6u);
  // "1,,2": the first comma is a separator, the second is where a number was expected
  std::size_t pos = 0;
  EXPECT_EQ(read_number("1,,2", pos), 1.0);
  try {
    read_number("1,,2", pos);
    FAIL() << "double comma accepted";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.offset, 2u);
  }
}

TEST(SvgNumber, MissingNumbersAreErrors) {
  for (const char* s : {"", "   ", "abc", "-", "+", ".", "-.", "e5", ",", "#1"}) {
    const ParseError e = number_error(s);
    EXPECT_NE(std::string(e.what()).find("expected a number"), std::string::npos) << s << ": " << e.what();
  }
  // the offset points past the skipped blanks to the bad character
  EXPECT_EQ(number_error("  x").offset, 2u);
}

TEST(SvgNumber, InfinitiesAndNansAreErrors) {
  for (const char* s : {"inf", "-inf", "+Infinity", "INF", "nan", "NaN", "-nan"}) {
    const ParseError e = number_error(s);
    EXPECT_NE(std::string(e.what()).find("finite"), std::string::npos) << s << ": " << e.what();
    EXPECT_EQ(e.offset, 0u);
  }
}

TEST(SvgNumber, OutOfRangeIsAnErrorThatQuotesTheToken) {
  const ParseError huge = number_error("  1e400");
  EXPECT_STREQ(huge.what(), "number 1e400 is out of range");
  EXPECT_EQ(huge.offset, 2u);
  // above kMaxMagnitude = 1e9, in both directions
  EXPECT_NE(std::string(number_error("2e9").what()).find("number 2e9 is out of range"), std::string::npos);
  EXPECT_NE(std::string(number_error("-1000000001").what()).find("out of range"), std::string::npos);
  EXPECT_EQ(first("1e9"), 1e9);
  EXPECT_EQ(first("-1e9"), -1e9);
}

TEST(SvgNumber, UnderflowIsZero) {
  // 1e-400 is below the smallest double: harmless, read as zero rather than refused
  EXPECT_EQ(first("1e-400"), 0.0);
  EXPECT_EQ(first("0.000001e-399"), 0.0);
  EXPECT_EQ(number_error("100000e400").offset, 0u);
}

TEST(SvgNumber, AtEnd) {
  EXPECT_TRUE(at_end("", 0));
  EXPECT_TRUE(at_end(" , \t", 0));
  EXPECT_TRUE(at_end("12", 2));
  EXPECT_TRUE(at_end("12", 7));
  EXPECT_FALSE(at_end(" 1", 0));
  EXPECT_FALSE(at_end("1,x", 1));
}

TEST(SvgLength, UnitsAndConversions) {
  // 12.5 cm = 0.125 m = 12.5 * 96 / 2.54 px
  const Length cm = parse_length("12.5cm");
  EXPECT_EQ(cm.value, 12.5);
  EXPECT_EQ(cm.unit, Unit::cm);
  EXPECT_TRUE(cm.physical());
  EXPECT_DOUBLE_EQ(cm.metres(), 0.125);
  EXPECT_DOUBLE_EQ(cm.user_units(), 12.5 * 96 / 2.54);

  // 1 in = 72 pt = 6 pc = 96 px = 0.0254 m
  for (const char* s : {"1in", "72pt", "6pc"}) {
    const Length l = parse_length(s);
    EXPECT_TRUE(l.physical()) << s;
    EXPECT_DOUBLE_EQ(l.metres(), 0.0254) << s;
    EXPECT_DOUBLE_EQ(l.user_units(), 96.0) << s;
  }
  EXPECT_DOUBLE_EQ(parse_length("5mm").metres(), 0.005);
  EXPECT_DOUBLE_EQ(parse_length("2m").metres(), 2.0);
  EXPECT_DOUBLE_EQ(parse_length("1e1mm").metres(), 0.01);
}

TEST(SvgLength, UnitlessAndRelativeUnits) {
  const Length plain = parse_length("10");
  EXPECT_EQ(plain.unit, Unit::none);
  EXPECT_FALSE(plain.physical());
  EXPECT_EQ(plain.user_units(), 10.0);
  EXPECT_EQ(parse_length("3px").unit, Unit::px);
  EXPECT_EQ(parse_length("3px").user_units(), 3.0);
  // percent counts as 0 user units; 1 em = 16 px, 1 ex = 8 px
  const Length pct = parse_length("50%");
  EXPECT_EQ(pct.unit, Unit::percent);
  EXPECT_EQ(pct.user_units(), 0.0);
  EXPECT_EQ(parse_length("2em").user_units(), 32.0);
  EXPECT_EQ(parse_length("2ex").user_units(), 16.0);
  EXPECT_THROW(parse_length("3px").metres(), std::logic_error);
  EXPECT_THROW(parse_length("50%").metres(), std::logic_error);
}

TEST(SvgLength, TrimsAndIgnoresUnitCase) {
  const Length l = parse_length("  5MM \n");
  EXPECT_EQ(l.value, 5.0);
  EXPECT_EQ(l.unit, Unit::mm);
}

TEST(SvgLength, Errors) {
  auto offset_of = [](const char* s) -> std::size_t {
    try {
      parse_length(s);
    } catch (const ParseError& e) {
      return e.offset;
    }
    ADD_FAILURE() << "no ParseError for '" << s << "'";
    return 999;
  };
  EXPECT_EQ(offset_of(""), 0u);
  EXPECT_EQ(offset_of("mm"), 0u);
  EXPECT_EQ(offset_of("5 mm"), 1u);  // no space between number and unit
  EXPECT_EQ(offset_of("5xy"), 1u);
  EXPECT_EQ(offset_of("5mm 6mm"), 1u);
  EXPECT_EQ(offset_of(",5"), 0u);
  EXPECT_EQ(offset_of("1e400cm"), 0u);
  EXPECT_EQ(offset_of("nan"), 0u);
}

}  // namespace
}  // namespace rescuesim::svg
