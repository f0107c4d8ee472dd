#include "viz/canvas.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "viz/font.h"

namespace rescuesim {
namespace {

constexpr Rgb8 kWhite{255, 255, 255};
constexpr Rgb8 kBlack{0, 0, 0};

// coverage drawn in black on white, in pixels: the summed darkness of the red channel / 255
double darkness(const Canvas& c) {
  double sum = 0;
  for (int y = 0; y < c.height(); ++y) {
    for (int x = 0; x < c.width(); ++x) sum += (255 - c.at(x, y).r) / 255.0;
  }
  return sum;
}

// a canvas with a different colour in every pixel, for round trips
Canvas pattern(int w, int h) {
  Canvas c(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      c.set(x, y, {static_cast<std::uint8_t>(x * 7 + y), static_cast<std::uint8_t>(y * 13 + 3 * x),
                   static_cast<std::uint8_t>((x * y) ^ 0x5a)});
    }
  }
  return c;
}

// -- pixels and blending ---------------------------------------------------------------------

TEST(CanvasPixels, BackgroundSetAndClipping) {
  Canvas c(4, 3, {1, 2, 3});
  EXPECT_EQ(c.width(), 4);
  EXPECT_EQ(c.height(), 3);
  EXPECT_EQ(c.pixels().size(), 36u);
  EXPECT_EQ(c.at(3, 2), (Rgb8{1, 2, 3}));
  c.set(1, 1, {9, 8, 7});
  EXPECT_EQ(c.at(1, 1), (Rgb8{9, 8, 7}));
  // writes outside the image are dropped quietly
  c.set(-1, 0, kBlack);
  c.set(4, 0, kBlack);
  c.blend(0, 3, kBlack, 1.0);
  EXPECT_EQ(c.at(0, 0), (Rgb8{1, 2, 3}));
}

TEST(CanvasPixels, BlendMixesByCoverage) {
  Canvas c(3, 1);
  c.blend(0, 0, kBlack, 0.5);
  c.blend(1, 0, kBlack, 1.0);
  c.blend(2, 0, kBlack, 0.0);
  EXPECT_NEAR(c.at(0, 0).r, 127.5, 0.6);
  EXPECT_EQ(c.at(1, 0), kBlack);
  EXPECT_EQ(c.at(2, 0), kWhite);
}

TEST(CanvasPixels, RejectsAbsurdSizes) {
  EXPECT_THROW(Canvas(-1, 5), Error);
  EXPECT_THROW(Canvas(100000, 5), Error);
  EXPECT_NO_THROW(Canvas(0, 0));
}

TEST(CanvasPixels, FillRectAndPasteClip) {
  Canvas c(10, 10);
  c.fill_rect(-5, -5, 3, 2, kBlack);
  EXPECT_DOUBLE_EQ(darkness(c), 6.0);
  Canvas small(4, 4, {10, 20, 30});
  c.paste(small, 8, 8);   // only a 2x2 corner lands
  c.paste(small, -3, 9);  // a 1x1 corner
  c.paste(small, 20, 20);  // nothing
  int n = 0;
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 10; ++x) n += c.at(x, y) == Rgb8{10, 20, 30};
  }
  EXPECT_EQ(n, 5);
  EXPECT_EQ(c.at(9, 9), (Rgb8{10, 20, 30}));
  EXPECT_EQ(c.at(0, 9), (Rgb8{10, 20, 30}));
}

// -- shapes ----------------------------------------------------------------------------------

TEST(CanvasShapes, RectanglePolygonCoversItsArea) {
  // a 10 x 20 px axis-aligned rectangle, on pixel edges and at a fractional offset
  for (const Vec2& o : {Vec2(5, 5), Vec2(5.3, 4.7), Vec2(2.25, 3.5)}) {
    Canvas c(40, 40);
    c.fill_polygon({o, o + Vec2(10, 0), o + Vec2(10, 20), o + Vec2(0, 20)}, kBlack);
    EXPECT_NEAR(darkness(c), 200.0, 1.0) << o.transpose();
  }
  // on pixel edges it is exact, and nothing leaks outside
  Canvas c(40, 40);
  c.fill_polygon({{5, 5}, {15, 5}, {15, 25}, {5, 25}}, kBlack);
  EXPECT_EQ(c.at(5, 5), kBlack);
  EXPECT_EQ(c.at(14, 24), kBlack);
  EXPECT_EQ(c.at(4, 10), kWhite);
  EXPECT_EQ(c.at(15, 10), kWhite);
  EXPECT_EQ(c.at(10, 25), kWhite);
}

TEST(CanvasShapes, PolygonOrientationDoesNotMatter) {
  Canvas cw(30, 30), ccw(30, 30);
  const std::vector<Vec2> tri{{3.2, 4.1}, {25.7, 8.3}, {11.4, 27.9}};
  ccw.fill_polygon(tri, kBlack);
  cw.fill_polygon({tri[2], tri[1], tri[0]}, kBlack);
  EXPECT_EQ(cw.pixels(), ccw.pixels());
  // triangle area by the shoelace formula
  const double area = 0.5 * std::abs((tri[1] - tri[0]).x() * (tri[2] - tri[0]).y() -
                                     (tri[1] - tri[0]).y() * (tri[2] - tri[0]).x());
  EXPECT_NEAR(darkness(ccw), area, 0.01 * area);
}

TEST(CanvasShapes, PolygonIsEvenOdd) {
  // a pentagram: with the even-odd rule its inner pentagon stays empty
  std::vector<Vec2> star;
  const Vec2 c(50, 50);
  for (int i = 0; i < 5; ++i) {
    const double a = -M_PI / 2 + i * 4 * M_PI / 5;
    star.push_back(c + 40 * Vec2(std::cos(a), std::sin(a)));
  }
  Canvas canvas(100, 100);
  canvas.fill_polygon(star, kBlack);
  EXPECT_EQ(canvas.at(50, 52), kWhite);  // centre
  EXPECT_EQ(canvas.at(50, 16), kBlack);  // inside the top point
}

TEST(CanvasShapes, FilledCircleArea) {
  Canvas c(60, 60);
  c.fill_circle({30.3, 29.6}, 20, kBlack);
  EXPECT_NEAR(darkness(c), M_PI * 400, 0.01 * M_PI * 400);
  EXPECT_EQ(c.at(30, 30), kBlack);
  EXPECT_EQ(c.at(30, 5), kWhite);
}

TEST(CanvasShapes, CircleOutlineIsARing) {
  Canvas c(60, 60);
  c.circle({30, 30}, 15, kBlack, 2.0);
  // a ring of width 2 around radius 15 has area 2 pi r w
  EXPECT_NEAR(darkness(c), 2 * M_PI * 15 * 2, 0.02 * 2 * M_PI * 15 * 2);
  EXPECT_EQ(c.at(30, 30), kWhite);
  EXPECT_EQ(c.at(44, 29), kBlack);  // on the rim, right of the centre (centre x 44.5, radius 14.5..15.5)
}

TEST(CanvasShapes, HorizontalHairline) {
  Canvas c(40, 12);
  c.line({10.5, 5.5}, {30.5, 5.5}, kBlack, 1.0);
  for (int x = 11; x <= 29; ++x) EXPECT_EQ(c.at(x, 5), kBlack) << x;
  for (int x = 0; x < 40; ++x) {
    EXPECT_EQ(c.at(x, 3), kWhite) << x;
    EXPECT_EQ(c.at(x, 7), kWhite) << x;
  }
}

TEST(CanvasShapes, WideLineCoversLengthTimesWidthPlusCaps) {
  // round caps add a disc of the line's width
  Canvas c(80, 40);
  c.line({20, 20}, {60, 20}, kBlack, 4.0);
  EXPECT_NEAR(darkness(c), 40 * 4 + M_PI * 4, 0.01 * (40 * 4 + M_PI * 4));
  // a diagonal line of the same length covers the same area
  Canvas d(80, 80);
  const Vec2 a(20, 20), b = a + 40 * Vec2(1, 1).normalized();
  d.line(a, b, kBlack, 4.0);
  EXPECT_NEAR(darkness(d), darkness(c), 0.02 * darkness(c));
}

TEST(CanvasShapes, ThinLinesFadeInsteadOfVanishing) {
  Canvas c(40, 10);
  c.line({5, 5.5}, {35, 5.5}, kBlack, 0.25);
  EXPECT_NEAR(darkness(c), 30 * 0.25 + 0.25, 1.0);
}

TEST(CanvasShapes, PolylineJoinsWithoutGapsOrDoubleBlending) {
  // a right-angle path at half opacity: the corner matches the straight parts
  Canvas c(50, 50);
  c.polyline({{10.5, 10.5}, {35.5, 10.5}, {35.5, 40.5}}, kBlack, 3.0, false, 0.5);
  const Rgb8 mid = c.at(20, 10);
  EXPECT_NEAR(mid.r, 128, 1);
  EXPECT_EQ(c.at(35, 10), mid);  // the join pixel
  EXPECT_EQ(c.at(35, 25), mid);
  // the outer corner is a round join: the diagonal pixel's centre is 1.41 px from the vertex,
  // so it has coverage 2 - 1.41 at half opacity
  EXPECT_EQ(c.at(36, 10), mid);
  EXPECT_NEAR(c.at(36, 9).r, 255 * (1 - 0.5 * (2 - std::sqrt(2.0))), 1);
  EXPECT_EQ(c.at(37, 8), kWhite);
  // closing a polygon outline adds the last edge
  Canvas closed(50, 50);
  closed.polyline({{10.5, 10.5}, {35.5, 10.5}, {35.5, 40.5}}, kBlack, 1.0, true);
  EXPECT_EQ(closed.at(15, 16), kBlack);  // centre on the diagonal from (35.5, 40.5) back to (10.5, 10.5)
}

TEST(CanvasShapes, BadCoordinatesDrawNothingAndHugeOnesClip) {
  Canvas c(20, 20);
  const double nan = std::nan("");
  c.line({nan, 1}, {5, 5}, kBlack);
  c.fill_polygon({{0, 0}, {nan, 3}, {5, 5}}, kBlack);
  c.fill_circle({5, 5}, nan, kBlack);
  c.circle({5, 5}, -3, kBlack);
  c.polyline({}, kBlack);
  EXPECT_EQ(darkness(c), 0.0);
  // a shape far larger than the canvas covers it exactly
  c.fill_polygon({{-1e12, -1e12}, {1e12, -1e12}, {1e12, 1e12}, {-1e12, 1e12}}, kBlack);
  EXPECT_DOUBLE_EQ(darkness(c), 400.0);
  Canvas d(20, 20);
  d.line({-1e9, 10.5}, {1e9, 10.5}, kBlack);
  EXPECT_NEAR(darkness(d), 20.0, 1e-9);
}

// -- text ------------------------------------------------------------------------------------

TEST(CanvasText, StaysInItsBoxAndReturnsItsWidth) {
  const std::string s = "Hello, World! 0123 {~}";
  for (int scale : {1, 2, 3}) {
    Canvas c(200, 40);
    const int x = 7, y = 9;
    const int w = c.text(x, y, s, kBlack, scale);
    EXPECT_EQ(w, (6 * static_cast<int>(s.size()) - 1) * scale);
    int drawn = 0;
    for (int py = 0; py < c.height(); ++py) {
      for (int px = 0; px < c.width(); ++px) {
        if (c.at(px, py) == kWhite) continue;
        ++drawn;
        EXPECT_TRUE(px >= x && px < x + w && py >= y && py < y + 7 * scale) << px << "," << py;
      }
    }
    EXPECT_GT(drawn, 0);
  }
  Canvas c(10, 10);
  EXPECT_EQ(c.text(0, 0, "", kBlack), 0);
  EXPECT_EQ(c.text(0, 0, "A", kBlack), 5);
}

TEST(CanvasText, EveryPrintableGlyphIsDistinct) {
  for (int a = 33; a <= 126; ++a) {
    const auto& ga = font::glyph(static_cast<char>(a));
    bool any = false;
    for (auto row : ga) any = any || row != 0;
    EXPECT_TRUE(any) << static_cast<char>(a);
    for (int b = a + 1; b <= 126; ++b) EXPECT_NE(ga, font::glyph(static_cast<char>(b))) << char(a) << char(b);
  }
  for (auto row : font::glyph(' ')) EXPECT_EQ(row, 0);
  // characters outside printable ASCII draw as '?'
  EXPECT_EQ(font::glyph('\n'), font::glyph('?'));
  EXPECT_EQ(font::glyph(static_cast<char>(0xC3)), font::glyph('?'));
}

// -- PNG -------------------------------------------------------------------------------------

TEST(CanvasPng, RoundTripIsPixelIdentical) {
  const Canvas c = pattern(37, 23);
  const std::string png = c.encode_png();
  ASSERT_GE(png.size(), 8u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  const Canvas back = decode_png(png);
  EXPECT_EQ(back.width(), 37);
  EXPECT_EQ(back.height(), 23);
  EXPECT_EQ(back.pixels(), c.pixels());
}

TEST(CanvasPng, DecodesRgbaByDroppingAlpha) {
  // a 2 x 1 RGBA image: opaque red, half-transparent green
  const unsigned char rgba[] = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
      0x00, 0x02, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0xf4, 0x22, 0x7f, 0x8a, 0x00, 0x00, 0x00,
      0x0f, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0xf8, 0xcf, 0xc0, 0xf0, 0x1f, 0x08, 0x1b, 0x00, 0x10, 0x79,
      0x03, 0x7e, 0x7d, 0x63, 0xce, 0xd7, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  const Canvas c = decode_png(std::string_view(reinterpret_cast<const char*>(rgba), sizeof rgba));
  ASSERT_EQ(c.width(), 2);
  ASSERT_EQ(c.height(), 1);
  EXPECT_EQ(c.at(0, 0), (Rgb8{255, 0, 0}));
  EXPECT_EQ(c.at(1, 0), (Rgb8{0, 255, 0}));
}

TEST(CanvasPng, RejectsOtherFormats) {
  // a valid 1 x 1 16-bit grey PNG
  const unsigned char grey16[] = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00,
      0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x10, 0x00, 0x00, 0x00, 0x00, 0x6a, 0xee, 0x47, 0x16, 0x00,
      0x00, 0x00, 0x0b, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x10, 0x32, 0x01, 0x00, 0x00, 0x5b, 0x00,
      0x47, 0x96, 0xfb, 0x1b, 0x65, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  try {
    decode_png(std::string_view(reinterpret_cast<const char*>(grey16), sizeof grey16));
    FAIL() << "16-bit grey accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("16-bit grey"), std::string::npos) << e.what();
  }
}

TEST(CanvasPng, GarbageThrows) {
  EXPECT_THROW(decode_png(""), Error);
  EXPECT_THROW(decode_png("hello, this is not an image at all"), Error);
  // a PNG signature followed by junk
  EXPECT_THROW(decode_png(std::string("\x89PNG\r\n\x1a\n", 8) + std::string(100, 'x')), Error);
  try {
    decode_png("GIF89a....");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a PNG"), std::string::npos) << e.what();
  }
}

TEST(CanvasPng, TruncatedAndCorruptedThrow) {
  const std::string png = pattern(64, 48).encode_png();
  for (std::size_t len : {std::size_t(8), std::size_t(20), std::size_t(40), png.size() / 2, png.size() - 13,
                          png.size() - 1}) {
    EXPECT_THROW(decode_png(std::string_view(png).substr(0, len)), Error) << len;
  }
  // one flipped byte inside the image data breaks its checksum
  std::string bad = png;
  bad[bad.size() / 2] = static_cast<char>(bad[bad.size() / 2] ^ 0x40);
  EXPECT_THROW(decode_png(bad), Error);
}

TEST(CanvasPng, WritePngIsReadable) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "rescuesim_canvas_test";
  const auto path = dir / "sub" / "image.png";
  const Canvas c = pattern(16, 9);
  c.write_png(path);
  EXPECT_EQ(decode_png(read_file(path)).pixels(), c.pixels());
  std::filesystem::remove_all(dir);
}

TEST(CanvasPng, WriteFailuresNameThePath) {
  const Canvas c = pattern(4, 4);
  try {
    c.write_png("/proc/rescuesim_no_such_dir/x.png");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/rescuesim_no_such_dir/x.png"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Canvas(0, 5).encode_png(), Error);
}

// -- plot frame ------------------------------------------------------------------------------

TEST(PlotFrame, MapsCornersToTheMarginsNorthUp) {
  PlotFrame f;
  f.world.min = {-2, 1};
  f.world.max = {8, 6};
  f.px_per_m = 10;
  f.margin = 20;
  EXPECT_EQ(f.width(), 140);
  EXPECT_EQ(f.height(), 90);
  // north-west corner at the top-left margin, south-east at the bottom-right one
  EXPECT_TRUE(f.to_px({-2, 6}).isApprox(Vec2(20, 20)));
  EXPECT_TRUE(f.to_px({8, 1}).isApprox(Vec2(120, 70)));
  EXPECT_LT(f.to_px({0, 5}).y(), f.to_px({0, 2}).y());
  EXPECT_LT(f.to_px({0, 3}).x(), f.to_px({1, 3}).x());
}

TEST(PlotFrame, SizesRoundUp) {
  PlotFrame f;
  f.world.min = {0, 0};
  f.world.max = {10.01, 3.3};
  f.px_per_m = 10;
  f.margin = 5;
  EXPECT_EQ(f.width(), 101 + 10);
  EXPECT_EQ(f.height(), 33 + 10);  // 3.3 x 10 is 33 up to rounding noise, not 34
}

}  // namespace
}  // namespace rescuesim
