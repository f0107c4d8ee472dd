#include <gtest/gtest.h>

#include <string>

#include "import/svg/svg_parse.h"

namespace rescuesim::svg {
namespace {

using Kind = Paint::Kind;

/// Parses a paint that must be a colour and returns its channels in 0–255.
Vec3 rgb255(std::string_view s) {
  const Paint p = parse_paint(s);
  EXPECT_EQ(p.kind, Kind::color) << s;
  return p.rgb * 255.0;
}

void expect_rgb(std::string_view s, double r, double g, double b) {
  const Vec3 c = rgb255(s);
  EXPECT_NEAR(c.x(), r, 1e-9) << s;
  EXPECT_NEAR(c.y(), g, 1e-9) << s;
  EXPECT_NEAR(c.z(), b, 1e-9) << s;
}

Semantic classify(std::string_view s) { return classify_color(parse_paint(s).rgb); }

TEST(SvgColor, NamedColours) {
  expect_rgb("red", 255, 0, 0);
  expect_rgb("RED", 255, 0, 0);
  expect_rgb("  Red\t", 255, 0, 0);
  expect_rgb("grey", 128, 128, 128);
  expect_rgb("gray", 128, 128, 128);
  expect_rgb("darkslategrey", 0x2f, 0x4f, 0x4f);
  expect_rgb("lightgoldenrodyellow", 0xfa, 0xfa, 0xd2);
  // both ends of the sorted table
  expect_rgb("aliceblue", 0xf0, 0xf8, 0xff);
  expect_rgb("yellowgreen", 0x9a, 0xcd, 0x32);
  expect_rgb("green", 0, 128, 0);
  expect_rgb("lime", 0, 255, 0);
  EXPECT_EQ(parse_paint("reddish").kind, Kind::invalid);
  EXPECT_EQ(parse_paint("re d").kind, Kind::invalid);
}

TEST(SvgColor, HexForms) {
  // #rgb doubles each digit: f → ff = 255, 8 → 88 = 136
  expect_rgb("#f80", 255, 136, 0);
  expect_rgb("#F80", 255, 136, 0);
  expect_rgb("#f808", 255, 136, 0);  // alpha ignored
  expect_rgb("#c81e1e", 200, 30, 30);
  expect_rgb("#C81E1E80", 200, 30, 30);
  for (const char* s : {"#", "#12", "#12345", "#1234567", "#123456789", "#ggg", "# fff", "fff"})
    EXPECT_EQ(parse_paint(s).kind, Kind::invalid) << s;
}

TEST(SvgColor, RgbFunctions) {
  expect_rgb("rgb(255,0,0)", 255, 0, 0);
  expect_rgb("rgb( 255 , 128 , 0 )", 255, 128, 0);
  expect_rgb("RGB(10,20,30)", 10, 20, 30);
  // percentages: 50% of 255 = 127.5
  expect_rgb("rgb(100%, 50%, 0%)", 255, 127.5, 0);
  expect_rgb("rgba(0,0,255,0.5)", 0, 0, 255);
  expect_rgb("rgba(0,0,255,50%)", 0, 0, 255);
  // CSS Color 4 space syntax with a slash before alpha
  expect_rgb("rgb(0 128 255 / 50%)", 0, 128, 255);
  // out of range clamps
  expect_rgb("rgb(300,-5,0)", 255, 0, 0);
  expect_rgb("rgb(150%,-10%,0)", 255, 0, 0);
  for (const char* s : {"rgb(1,2)", "rgb(1,2,3,4,5)", "rgb(a,b,c)", "rgb(1,,2,3)", "rgb(1,2,3", "rgb 1,2,3",
                        "rgb(1,2,3,)", "rgb(1px,2,3)", "rgb(1,2,3)x", "rgb(1 2 / 3)", "rgb()", "rgb(1,2,inf)",
                        "foo(1,2,3)"})
    EXPECT_EQ(parse_paint(s).kind, Kind::invalid) << s;
}

TEST(SvgColor, HslFunctions) {
  expect_rgb("hsl(120, 100%, 50%)", 0, 255, 0);
  // l = 25%: m2 = 0.25 · 2 = 0.5, m1 = 0; red channel at hue 1/3 + 0 is m2 → 127.5
  expect_rgb("hsl(0, 100%, 25%)", 127.5, 0, 0);
  expect_rgb("hsla(240, 100%, 50%, 0.3)", 0, 0, 255);
  expect_rgb("hsl(480, 100%, 50%)", 0, 255, 0);    // 480 ≡ 120
  expect_rgb("hsl(-120, 100%, 50%)", 0, 0, 255);   // -120 ≡ 240
  expect_rgb("hsl(0.5turn, 100%, 50%)", 0, 255, 255);
  expect_rgb("hsl(120deg 100% 50%)", 0, 255, 0);
  expect_rgb("hsl(0, 0%, 100%)", 255, 255, 255);
  EXPECT_EQ(parse_paint("hsl(120, 100, 50)").kind, Kind::invalid);  // s and l need %
  EXPECT_EQ(parse_paint("hsl(120%, 100%, 50%)").kind, Kind::invalid);
}

TEST(SvgColor, Keywords) {
  EXPECT_EQ(parse_paint("none").kind, Kind::none);
  EXPECT_EQ(parse_paint(" NONE ").kind, Kind::none);
  EXPECT_EQ(parse_paint("transparent").kind, Kind::none);
  EXPECT_EQ(parse_paint("currentColor").kind, Kind::current_color);
  EXPECT_EQ(parse_paint("CURRENTCOLOR").kind, Kind::current_color);
  EXPECT_EQ(parse_paint("inherit").kind, Kind::inherit);
}

TEST(SvgColor, UrlUsesTheFallback) {
  EXPECT_EQ(parse_paint("url(#grad)").kind, Kind::none);
  expect_rgb("url(#grad) red", 255, 0, 0);
  expect_rgb("url( #g )  #00f ", 0, 0, 255);
  EXPECT_EQ(parse_paint("url(#g) none").kind, Kind::none);
  EXPECT_EQ(parse_paint("url(#g) currentColor").kind, Kind::current_color);
  EXPECT_EQ(parse_paint("url(#g").kind, Kind::invalid);
  EXPECT_EQ(parse_paint("url(#g) bogus").kind, Kind::invalid);
  EXPECT_EQ(parse_paint("url(#a) url(#b)").kind, Kind::invalid);
}

TEST(SvgColor, GarbageIsInvalidNeverThrown) {
  for (const char* s : {"", "   ", "12", "rgb", "#", "(", ")", "()", "hsl(", "\xff\xfe", "url(", "rgb(1e400,0,0)"})
    EXPECT_EQ(parse_paint(s).kind, Kind::invalid) << s;
}

TEST(SvgClassify, PureAndNearColours) {
  // value = max channel: #222 = 34/255 = 0.13 ≤ 0.25
  EXPECT_EQ(classify("#000"), Semantic::wall);
  EXPECT_EQ(classify("#222"), Semantic::wall);
  // #c81e1e: v = 200/255 = 0.78, s = 170/200 = 0.85, hue 0
  EXPECT_EQ(classify("#f00"), Semantic::raised);
  EXPECT_EQ(classify("#c81e1e"), Semantic::raised);
  // #2850c8: v = 0.78, s = 160/200 = 0.8, hue = 240 + 60 (40 - 80) / 160 = 225
  EXPECT_EQ(classify("#00f"), Semantic::victim);
  EXPECT_EQ(classify("#2850c8"), Semantic::victim);
  // #008000: v = 0.5, s = 1, hue 120
  EXPECT_EQ(classify("#0f0"), Semantic::start);
  EXPECT_EQ(classify("#008000"), Semantic::start);
  // #ff8000: hue = 60 · 128 / 255 = 30.1; #ffd700: hue = 60 · 215 / 255 = 50.6
  EXPECT_EQ(classify("#ff8000"), Semantic::rubble);
  EXPECT_EQ(classify("#ffd700"), Semantic::rubble);
  // #f5f5f5: s = 0, v = 0.96
  EXPECT_EQ(classify("#fff"), Semantic::background);
  EXPECT_EQ(classify("#f5f5f5"), Semantic::background);
  // #808080: grey with v = 0.5; #ff00ff: hue 300 (magenta)
  EXPECT_EQ(classify("#808080"), Semantic::unknown);
  EXPECT_EQ(classify("#ff00ff"), Semantic::unknown);
}

TEST(SvgClassify, Boundaries) {
  // value exactly 0.25 is still a wall; a touch above with no saturation is unknown
  EXPECT_EQ(classify_color(Vec3(0.25, 0, 0)), Semantic::wall);
  EXPECT_EQ(classify_color(Vec3(0.26, 0.26, 0.26)), Semantic::unknown);
  // saturation 0.35 < 0.40: pinkish, unknown; 0.5 is red
  EXPECT_EQ(classify_color(Vec3(1, 0.65, 0.65)), Semantic::unknown);
  EXPECT_EQ(classify_color(Vec3(1, 0.5, 0.5)), Semantic::raised);
  // near-white: s = 0.1 < 0.15 and v = 0.9 ≥ 0.85
  EXPECT_EQ(classify_color(Vec3(0.9, 0.81, 0.81)), Semantic::background);
  // hue 20 → raised, 22.5 → unknown (the gap before orange), 340 → raised
  EXPECT_EQ(classify_color(Vec3(1, 1.0 / 3, 0)), Semantic::raised);
  EXPECT_EQ(classify_color(Vec3(1, 0.375, 0)), Semantic::unknown);
  EXPECT_EQ(classify_color(Vec3(1, 0, 1.0 / 3)), Semantic::raised);
  // hue 180 (cyan) is between start and victim: unknown
  EXPECT_EQ(classify_color(Vec3(0, 1, 1)), Semantic::unknown);
  // out-of-range and NaN channels are clamped (NaN as 0)
  EXPECT_EQ(classify_color(Vec3(2, -1, std::nan(""))), Semantic::raised);
}

TEST(SvgClassify, Names) {
  EXPECT_STREQ(semantic_name(Semantic::wall), "wall");
  EXPECT_STREQ(semantic_name(Semantic::raised), "raised area");
  EXPECT_STREQ(semantic_name(Semantic::victim), "victim");
  EXPECT_STREQ(semantic_name(Semantic::start), "robot start");
  EXPECT_STREQ(semantic_name(Semantic::rubble), "rubble");
  EXPECT_STREQ(semantic_name(Semantic::background), "background");
  EXPECT_STREQ(semantic_name(Semantic::unknown), "unknown");
}

}  // namespace
}  // namespace rescuesim::svg
