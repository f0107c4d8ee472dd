#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "import/svg/svg_parse.h"

namespace rescuesim::svg {
namespace {

/// Maps a point through a parsed transform list.
Vec2 apply(std::string_view transform, const Vec2& p) { return parse_transform(transform) * p; }

/// The ParseError a transform list throws (fails the test if none).
ParseError transform_error(std::string_view s) {
  try {
    parse_transform(s);
  } catch (const ParseError& e) {
    return e;
  }
  ADD_FAILURE() << "no ParseError for '" << s << "'";
  return ParseError("", 0);
}

void expect_near(const Vec2& got, const Vec2& want, double eps = 1e-12) {
  EXPECT_NEAR(got.x(), want.x(), eps);
  EXPECT_NEAR(got.y(), want.y(), eps);
}

TEST(SvgTransform, EmptyIsIdentity) {
  EXPECT_TRUE(parse_transform("").isApprox(Eigen::Affine2d::Identity()));
  EXPECT_TRUE(parse_transform(" \n\t ").isApprox(Eigen::Affine2d::Identity()));
}

TEST(SvgTransform, Translate) {
  EXPECT_EQ(apply("translate(10,5)", {1, 1}), Vec2(11, 6));
  // ty defaults to 0
  EXPECT_EQ(apply("translate(10)", {1, 1}), Vec2(11, 1));
  EXPECT_EQ(apply("translate(-2.5 .5)", {0, 0}), Vec2(-2.5, 0.5));
}

TEST(SvgTransform, Scale) {
  EXPECT_EQ(apply("scale(2)", {3, 4}), Vec2(6, 8));  // sy defaults to sx
  EXPECT_EQ(apply("scale(2,3)", {3, 4}), Vec2(6, 12));
  EXPECT_EQ(apply("scale(1 -1)", {3, 4}), Vec2(3, -4));
}

TEST(SvgTransform, Rotate) {
  // right angles are exact: (1,0) turns to (0,1), (-1,0), (0,-1)
  EXPECT_EQ(apply("rotate(90)", {1, 0}), Vec2(0, 1));
  EXPECT_EQ(apply("rotate(180)", {1, 0}), Vec2(-1, 0));
  EXPECT_EQ(apply("rotate(-90)", {1, 0}), Vec2(0, -1));
  EXPECT_EQ(apply("rotate(450)", {1, 0}), Vec2(0, 1));
  // 30°: (cos 30°, sin 30°) = (√3/2, 1/2)
  expect_near(apply("rotate(30)", {1, 0}), {std::sqrt(3.0) / 2, 0.5});
  // about (10,10): (20,10) is (10,0) from the centre, turns to (0,10), lands on (10,20)
  EXPECT_EQ(apply("rotate(90 10 10)", {20, 10}), Vec2(10, 20));
  EXPECT_EQ(apply("rotate(90,10,10)", {10, 10}), Vec2(10, 10));
}

TEST(SvgTransform, Skew) {
  // skewX(45): x += y tan 45° → (1,2) to (3,2); skewY(45): y += x → (1,2) to (1,3)
  expect_near(apply("skewX(45)", {1, 2}), {3, 2});
  expect_near(apply("skewY(45)", {1, 2}), {1, 3});
  // tan(-30°) = -1/√3
  expect_near(apply("skewX(-30)", {0, 3}), {-3 / std::sqrt(3.0), 3});
}

TEST(SvgTransform, Matrix) {
  // matrix(a b c d e f): (x,y) → (a x + c y + e, b x + d y + f) = (1+3+5, 2+4+6)
  EXPECT_EQ(apply("matrix(1 2 3 4 5 6)", {1, 1}), Vec2(9, 12));
  EXPECT_EQ(apply("matrix(1,0,0,1,-7,8)", {0, 0}), Vec2(-7, 8));
}

TEST(SvgTransform, LeftmostIsAppliedLast) {
  // translate(10) scale(2): p → 10 + 2p, so (3,0) → (16,0)
  EXPECT_EQ(apply("translate(10) scale(2)", {3, 0}), Vec2(16, 0));
  // scale(2) translate(10): p → 2 (p + 10), so (3,0) → (26,0)
  EXPECT_EQ(apply("scale(2) translate(10)", {3, 0}), Vec2(26, 0));
  // translate(10,0) rotate(90): (1,0) → (0,1) → (10,1)
  EXPECT_EQ(apply("translate(10,0) rotate(90)", {1, 0}), Vec2(10, 1));
  // rotate(90 10 10) equals translate(10 10) rotate(90) translate(-10 -10)
  EXPECT_TRUE(parse_transform("rotate(90 10 10)")
                  .isApprox(parse_transform("translate(10 10) rotate(90) translate(-10 -10)")));
}

TEST(SvgTransform, SeparatorsAndCase) {
  const Eigen::Affine2d want = parse_transform("translate(1 2) scale(3)");
  for (const char* s : {"translate(1,2),scale(3)", "translate(1 2)scale(3)", "  translate( 1 , 2 )  ,  scale( 3 ) ",
                        "translate\n(1\t2) scale(3)", "TRANSLATE(1 2) Scale(3)"})
    EXPECT_TRUE(parse_transform(s).isApprox(want)) << s;
}

TEST(SvgTransform, UnknownFunction) {
  const ParseError e = transform_error("translate(1) bar(2)");
  EXPECT_EQ(e.offset, 13u);
  EXPECT_NE(std::string(e.what()).find("unknown transform function 'bar'"), std::string::npos) << e.what();
  EXPECT_EQ(transform_error("foo(1)").offset, 0u);
  EXPECT_EQ(transform_error("(1)").offset, 0u);
  EXPECT_EQ(transform_error("translate(1) 5").offset, 13u);
}

TEST(SvgTransform, WrongArgumentCounts) {
  const ParseError e = transform_error("translate(1,2,3)");
  EXPECT_EQ(e.offset, 0u);
  EXPECT_NE(std::string(e.what()).find("translate takes 1 or 2 numbers, found 3"), std::string::npos) << e.what();
  for (const char* s : {"translate()", "scale(1 2 3)", "rotate(1,2)", "rotate(1 2 3 4)", "matrix(1 2 3 4 5)",
                        "matrix(1 2 3 4 5 6 7)", "skewX()", "skewY(1 2)", "matrix(1 2 3 4 5 6 7 8 9 10)"})
    transform_error(s);
}

TEST(SvgTransform, MissingParentheses) {
  const ParseError open = transform_error("translate 10");
  EXPECT_EQ(open.offset, 10u);
  EXPECT_NE(std::string(open.what()).find("expected '('"), std::string::npos) << open.what();
  const ParseError close = transform_error("translate(10");
  EXPECT_EQ(close.offset, 12u);
  EXPECT_NE(std::string(close.what()).find("expected ')'"), std::string::npos) << close.what();
  EXPECT_EQ(transform_error("scale").offset, 5u);
}

TEST(SvgTransform, MalformedNumbersAndSeparators) {
  EXPECT_EQ(transform_error("scale(1,,2)").offset, 8u);
  EXPECT_EQ(transform_error("scale(,2)").offset, 6u);
  EXPECT_EQ(transform_error("scale(2,)").offset, 8u);
  EXPECT_EQ(transform_error("scale(2),").offset, 9u);
  EXPECT_EQ(transform_error("scale(2),,scale(3)").offset, 9u);
  EXPECT_EQ(transform_error("translate(inf)").offset, 10u);
  EXPECT_STREQ(transform_error("rotate(1e400)").what(), "number 1e400 is out of range");
}

TEST(SvgTransform, DegenerateOrOverflowingMaps) {
  // skew by a right angle would need an infinite matrix entry
  EXPECT_EQ(transform_error("skewX(90)").offset, 0u);
  EXPECT_EQ(transform_error("skewY(-270)").offset, 0u);
  // (1e9)^35 overflows a double
  std::string many;
  for (int i = 0; i < 40; ++i) many += "scale(1e9) ";
  EXPECT_NE(std::string(transform_error(many).what()).find("not finite"), std::string::npos);
}

}  // namespace
}  // namespace rescuesim::svg
