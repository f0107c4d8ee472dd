#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "import/svg/svg_parse.h"

namespace rescuesim::svg {
namespace {

const Eigen::Affine2d kIdentity = Eigen::Affine2d::Identity();

using Points = std::vector<Vec2>;

/// Parses with the identity map.
std::vector<Subpath> parse(std::string_view d, double tolerance = 0.01) { return parse_path(d, kIdentity, tolerance); }

/// The single subpath of `d` (fails the test if there is not exactly one).
Points only(std::string_view d, double tolerance = 0.01) {
  const auto subpaths = parse(d, tolerance);
  EXPECT_EQ(subpaths.size(), 1u) << d;
  return subpaths.empty() ? Points{} : subpaths[0].points;
}

void expect_points(const Points& got, const Points& want, double eps = 1e-12) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_NEAR(got[i].x(), want[i].x(), eps) << "point " << i;
    EXPECT_NEAR(got[i].y(), want[i].y(), eps) << "point " << i;
  }
}

/// The ParseError path data throws (fails the test if none).
ParseError path_error(std::string_view d) {
  try {
    parse(d);
  } catch (const ParseError& e) {
    return e;
  }
  ADD_FAILURE() << "no ParseError for '" << d << "'";
  return ParseError("", 0);
}

/// Shoelace area of a closed polygon.
double area(const Points& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& q = p[(i + 1) % p.size()];
    a += p[i].x() * q.y() - q.x() * p[i].y();
  }
  return 0.5 * a;
}

/// Distance from a point to a polyline.
double distance_to(const Points& line, const Vec2& p) {
  double best = 1e300;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec2 d = line[i + 1] - line[i];
    const double t = std::clamp((p - line[i]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (line[i] + t * d - p).norm());
  }
  return best;
}

TEST(SvgPath, EmptyDataHasNoSubpaths) {
  EXPECT_TRUE(parse("").empty());
  EXPECT_TRUE(parse(" \n ").empty());
}

TEST(SvgPath, MovetoAndLineto) {
  expect_points(only("M 10 20 L 30 40"), {{10, 20}, {30, 40}});
  // relative: (10,20) then +(5,5)
  expect_points(only("m 10 20 l 5 5"), {{10, 20}, {15, 25}});
  expect_points(only("M10,20L30,40"), {{10, 20}, {30, 40}});
  EXPECT_FALSE(parse("M 10 20 L 30 40")[0].closed);
}

TEST(SvgPath, ExtraPairsAfterMovetoAreLinetos) {
  expect_points(only("M0 0 10 0 10 10"), {{0, 0}, {10, 0}, {10, 10}});
  // after m they are relative: (1,1) → (3,1) → (3,3)
  expect_points(only("m1 1 2 0 0 2"), {{1, 1}, {3, 1}, {3, 3}});
  expect_points(only("M0 0 L 1 1 2 2, 3 3"), {{0, 0}, {1, 1}, {2, 2}, {3, 3}});
}

TEST(SvgPath, HorizontalAndVertical) {
  // (1,2) H5 → (5,2), V7 → (5,7), h-2 → (3,7), v-3 → (3,4)
  expect_points(only("M1 2 H5 V7 h-2 v-3"), {{1, 2}, {5, 2}, {5, 7}, {3, 7}, {3, 4}});
  expect_points(only("M0 0 H 1 2 3"), {{0, 0}, {1, 0}, {2, 0}, {3, 0}});
}

TEST(SvgPath, CloseDoesNotRepeatTheStart) {
  const auto square = parse("M0 0 L10 0 L10 10 Z");
  ASSERT_EQ(square.size(), 1u);
  EXPECT_TRUE(square[0].closed);
  expect_points(square[0].points, {{0, 0}, {10, 0}, {10, 10}});
  // drawn back to the start explicitly: still one copy
  expect_points(only("M0 0 L10 0 L10 10 L0 0 z"), {{0, 0}, {10, 0}, {10, 10}});
}

TEST(SvgPath, DrawingAfterCloseStartsANewSubpathAtTheStart) {
  const auto two = parse("M0 0 L10 0 L10 10 Z L 0 10");
  ASSERT_EQ(two.size(), 2u);
  EXPECT_TRUE(two[0].closed);
  EXPECT_FALSE(two[1].closed);
  expect_points(two[1].points, {{0, 0}, {0, 10}});
  // relative after z is relative to the subpath start (5,5): (5,5) + (0,-5)
  const auto rel = parse("M5 5 l10 0 l0 10 z l 0 -5");
  ASSERT_EQ(rel.size(), 2u);
  expect_points(rel[1].points, {{5, 5}, {5, 0}});
}

TEST(SvgPath, SeveralSubpathsAndBareMovetos) {
  const auto two = parse("M0 0 L1 0 M5 5 L6 5");
  ASSERT_EQ(two.size(), 2u);
  expect_points(two[1].points, {{5, 5}, {6, 5}});
  // a moveto alone draws nothing
  expect_points(only("M0 0 M1 1 L2 2"), {{1, 1}, {2, 2}});
  EXPECT_TRUE(parse("M 5 5").empty());
  EXPECT_TRUE(parse("M 5 5 Z").empty());
  EXPECT_TRUE(parse("M 5 5 L 5 5").empty());
  // a second m is relative to the end of the first subpath: (1,0) + (4,0)
  const auto rel = parse("m0 0 l1 0 m4 0 l1 0");
  ASSERT_EQ(rel.size(), 2u);
  expect_points(rel[1].points, {{5, 0}, {6, 0}});
}

TEST(SvgPath, ConsecutiveDuplicatesAreDropped) {
  expect_points(only("M0 0 L0 0 L1 0 L1 0 l0 0"), {{0, 0}, {1, 0}});
}

TEST(SvgPath, PointsAreMappedToWorld) {
  // world = (0.01 x, 8 - 0.01 y): (100,100) → (1,7), (200,100) → (2,7)
  Eigen::Affine2d w = Eigen::Affine2d::Identity();
  w.linear() << 0.01, 0, 0, -0.01;
  w.translation() << 0, 8;
  const auto sub = parse_path("M 100 100 L 200 100", w, 0.005);
  ASSERT_EQ(sub.size(), 1u);
  expect_points(sub[0].points, {{1, 7}, {2, 7}});
}

TEST(SvgPath, CubicAbsoluteAndRelative) {
  // P = (0,0) (0,10) (10,10) (10,0): second differences (10,-10) and (-10,-10), |.| = 14.14;
  // tolerance 5 → n = ceil(sqrt(0.75 * 14.14 / 5)) = ceil(1.46) = 2; B(1/2) = (P0 + 3P1 + 3P2 + P3) / 8
  // = (40, 60) / 8 = (5, 7.5)
  expect_points(only("M0 0 C 0 10 10 10 10 0", 5), {{0, 0}, {5, 7.5}, {10, 0}});
  expect_points(only("M10 10 c 0 10 10 10 10 0", 5), {{10, 10}, {15, 17.5}, {20, 10}});
}

TEST(SvgPath, CubicStaysWithinTolerance) {
  // sample the true curve densely: every sample is within the tolerance of the polyline
  const double tol = 0.01;
  const Points line = only("M0 0 C 0 100 100 -50 100 50", tol);
  EXPECT_GT(line.size(), 10u);
  const Vec2 p0(0, 0), p1(0, 100), p2(100, -50), p3(100, 50);
  for (int i = 0; i <= 2000; ++i) {
    const double t = i / 2000.0, u = 1 - t;
    const Vec2 b = u * u * u * p0 + 3 * u * u * t * p1 + 3 * u * t * t * p2 + t * t * t * p3;
    EXPECT_LE(distance_to(line, b), tol) << "t = " << t;
  }
}

TEST(SvgPath, ToleranceIsMeasuredInWorldUnits) {
  // scaling by 100 multiplies the second differences by 100, so ~10 times as many chords
  Eigen::Affine2d big = Eigen::Affine2d::Identity();
  big.linear() *= 100;
  const std::string d = "M0 0 C 0 10 10 10 10 0";
  const std::size_t small_n = parse_path(d, kIdentity, 0.01)[0].points.size();
  const std::size_t big_n = parse_path(d, big, 0.01)[0].points.size();
  EXPECT_GT(big_n, 8 * small_n);
}

TEST(SvgPath, SmoothCubicReflectsAfterCubic) {
  // S after C: first control = reflection of (10,10) about (10,0) = (10,-10)
  const Points s = only("M0 0 C 0 10 10 10 10 0 S 20 -10 20 0", 5);
  expect_points(s, only("M0 0 C 0 10 10 10 10 0 C 10 -10 20 -10 20 0", 5));
  // hand check of the second half's midpoint: (10 + 30 + 60 + 20, 0 - 30 - 30 + 0) / 8 = (15, -7.5)
  expect_points(s, {{0, 0}, {5, 7.5}, {10, 0}, {15, -7.5}, {20, 0}});
  expect_points(only("M0 0 c 0 10 10 10 10 0 s 10 -10 10 0", 5), s);
  // repeated S reflects the previous S's control: (20,-10) about (20,0) → (20,10)
  expect_points(only("M0 0 C 0 10 10 10 10 0 S 20 -10 20 0 30 10 40 0", 5),
                only("M0 0 C 0 10 10 10 10 0 C 10 -10 20 -10 20 0 C 20 10 30 10 40 0", 5));
}

TEST(SvgPath, SmoothCubicWithoutCubicUsesTheCurrentPoint) {
  // controls (0,0) (10,10): B(1/2) = (0 + 0 + 30 + 10, 0 + 0 + 30 + 0) / 8 = (5, 3.75)
  expect_points(only("M0 0 S 10 10 10 0", 5), {{0, 0}, {5, 3.75}, {10, 0}});
  // after a quadratic there is nothing to reflect either
  expect_points(only("M0 0 Q 5 5 10 0 S 20 10 20 0"), only("M0 0 Q 5 5 10 0 C 10 0 20 10 20 0"));
}

TEST(SvgPath, QuadraticAbsoluteAndRelative) {
  // P0 - 2C + P1 = (0,-20); tolerance 2 → n = ceil(sqrt(0.25 * 20 / 2)) = 2;
  // B(1/2) = (P0 + 2C + P1) / 4 = (20, 20) / 4 = (5, 5)
  expect_points(only("M0 0 Q 5 10 10 0", 2), {{0, 0}, {5, 5}, {10, 0}});
  expect_points(only("M10 10 q 5 10 10 0", 2), {{10, 10}, {15, 15}, {20, 10}});
}

TEST(SvgPath, SmoothQuadraticReflects) {
  // T after Q: control (5,10) reflected about (10,0) = (15,-10); B(1/2) = (10 + 30 + 20, -20) / 4
  const Points t = only("M0 0 Q 5 10 10 0 T 20 0", 2);
  expect_points(t, {{0, 0}, {5, 5}, {10, 0}, {15, -5}, {20, 0}});
  expect_points(only("M0 0 q 5 10 10 0 t 10 0", 2), t);
  // a second T reflects (15,-10) about (20,0) → (25,10); midpoint (20 + 50 + 30, 20) / 4 = (25, 5)
  const Points tt = only("M0 0 Q 5 10 10 0 T 20 0 T 30 0", 2);
  ASSERT_EQ(tt.size(), 7u);
  EXPECT_NEAR(tt[5].x(), 25, 1e-12);
  EXPECT_NEAR(tt[5].y(), 5, 1e-12);
  // without a quadratic before, T's control is the current point: a straight line
  for (const Vec2& p : only("M0 0 T 10 0", 2)) EXPECT_EQ(p.y(), 0.0);
  expect_points(only("M0 0 C 1 1 2 2 3 0 T 6 0"), only("M0 0 C 1 1 2 2 3 0 Q 3 0 6 0"));
}

TEST(SvgPath, HalfCircleArcs) {
  // r = 10 between (0,0) and (20,0): centre (10,0); sweep 1 turns towards +angle, through (10,-10)
  for (const char* d : {"M 0 0 A 10 10 0 0 1 20 0", "M 0 0 a 10 10 0 0 1 20 0", "M0,0A10,10,0,0,1,20,0"}) {
    const Points p = only(d, 0.1);
    ASSERT_GE(p.size(), 3u);
    EXPECT_EQ(p.back(), Vec2(20, 0));
    double lowest = 0;
    for (const Vec2& q : p) {
      EXPECT_NEAR((q - Vec2(10, 0)).norm(), 10, 1e-9);
      EXPECT_LE(q.y(), 1e-9);
      lowest = std::min(lowest, q.y());
    }
    EXPECT_LT(lowest, -9.9);
  }
  // sweep 0 goes the other way, through (10,10)
  for (const Vec2& q : only("M 0 0 A 10 10 0 0 0 20 0", 0.1)) EXPECT_GE(q.y(), -1e-9);
}

TEST(SvgPath, QuarterCircleWithinTolerance) {
  // from (10,0) to (0,10), small arc, sweep 1: the centre is the origin (the other candidate,
  // (10,10), would need a 270° sweep)
  for (const double tol : {1.0, 0.1, 0.01, 0.001}) {
    const Points p = only("M 10 0 A 10 10 0 0 1 0 10", tol);
    ASSERT_GE(p.size(), 2u);
    EXPECT_EQ(p.front(), Vec2(10, 0));
    EXPECT_EQ(p.back(), Vec2(0, 10));
    for (std::size_t i = 0; i < p.size(); ++i) {
      EXPECT_NEAR(p[i].norm(), 10, 1e-9);
      if (i + 1 < p.size()) {
        EXPECT_LE(10 - (0.5 * (p[i] + p[i + 1])).norm(), tol);
      }
    }
  }
}

TEST(SvgPath, QuarterCircleToleranceHoldsAfterATransform) {
  // world = 0.01 × user with a y flip: the circle has radius 0.1 m about (1, 2)
  Eigen::Affine2d w = Eigen::Affine2d::Identity();
  w.linear() << 0.01, 0, 0, -0.01;
  w.translation() << 1, 2;
  const double tol = 0.0005;
  const auto sub = parse_path("M 10 0 A 10 10 0 0 1 0 10", w, tol);
  ASSERT_EQ(sub.size(), 1u);
  const Points& p = sub[0].points;
  EXPECT_GT(p.size(), 3u);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_NEAR((p[i] - Vec2(1, 2)).norm(), 0.1, 1e-9);
    if (i + 1 < p.size()) {
      EXPECT_LE(0.1 - (0.5 * (p[i] + p[i + 1]) - Vec2(1, 2)).norm(), tol);
    }
  }
}

TEST(SvgPath, FullCircleArea) {
  // two half arcs of r = 50: the inscribed polygon's area falls short of πr² by at most
  // perimeter × tolerance = 2πr t
  const double r = 50, tol = 0.05;
  const auto sub = parse("M150 100 A50 50 0 0 1 50 100 A50 50 0 0 1 150 100 Z", tol);
  ASSERT_EQ(sub.size(), 1u);
  EXPECT_TRUE(sub[0].closed);
  const double a = std::abs(area(sub[0].points));
  EXPECT_LE(a, M_PI * r * r);
  EXPECT_GE(a, M_PI * r * r - 2 * M_PI * r * tol);
}

TEST(SvgPath, TooSmallRadiiAreScaledUp) {
  // r = 1 cannot span 20 units: scaled by sqrt(Λ) = 10 to r = 10, centre at the midpoint (10,0)
  const Points circle = only("M0 0 A 1 1 0 0 1 20 0", 0.1);
  for (const Vec2& q : circle) EXPECT_NEAR((q - Vec2(10, 0)).norm(), 10, 1e-9);
  // radii (1,2): Λ = (10/1)² = 100, so (10,20): a half ellipse ((x-10)/10)² + (y/20)² = 1
  const Points ellipse = only("M0 0 A 1 2 0 1 0 20 0", 0.1);
  double highest = 0;
  for (const Vec2& q : ellipse) {
    EXPECT_NEAR(std::pow((q.x() - 10) / 10, 2) + std::pow(q.y() / 20, 2), 1, 1e-9);
    highest = std::max(highest, q.y());
  }
  EXPECT_GT(highest, 19.9);
}

TEST(SvgPath, RotatedEllipticArc) {
  // radii (20,10) turned 90°: the ellipse's long axis is vertical; from (0,0) to (0,40) with
  // Λ = (−20/20)² = 1 exactly the half ellipse around (0,20); sweep 1 turns from -90° towards
  // 0°, through (10,20)
  const Points p = only("M0 0 A 20 10 90 0 1 0 40", 0.01);
  for (const Vec2& q : p) EXPECT_NEAR(std::pow(q.x() / 10, 2) + std::pow((q.y() - 20) / 20, 2), 1, 1e-9);
  EXPECT_GT(std::max_element(p.begin(), p.end(), [](auto& a, auto& b) { return a.x() < b.x(); })->x(), 9.99);
}

TEST(SvgPath, DegenerateArcs) {
  // a zero radius is a straight line; equal end points draw nothing
  expect_points(only("M0 0 A 0 5 0 0 1 10 0"), {{0, 0}, {10, 0}});
  expect_points(only("M0 0 A 5 0 0 0 1 10 0"), {{0, 0}, {10, 0}});
  expect_points(only("M0 0 A 5 5 0 0 1 0 0 L 1 0"), {{0, 0}, {1, 0}});
  // negative radii count as positive
  expect_points(only("M0 0 A -10 -10 0 0 1 20 0", 0.1), only("M0 0 A 10 10 0 0 1 20 0", 0.1));
}

TEST(SvgPath, ArcFlagsNeedNoSeparators) {
  // "a1 1 0 00 1 1": r = 1, flags 0 and 0, to (1,1); centre by F.6.5: x1' = y1' = -1/2,
  // coefficient -1 (fA = fS), centre' = (1/2, -1/2), centre = (1/2, -1/2) + (1/2, 1/2) = (1, 0)
  const Points p = only("M0 0 a1 1 0 00 1 1", 0.001);
  EXPECT_EQ(p.back(), Vec2(1, 1));
  for (const Vec2& q : p) EXPECT_NEAR((q - Vec2(1, 0)).norm(), 1, 1e-9);
  expect_points(only("M0 0 a1,1,0,0,0,1,1", 0.001), p);
  // "0110 0": flags 0 and 1, then x = 10, y = 0
  expect_points(only("M0 0 A 1 1 0 0110 0", 0.1), only("M0 0 A 1 1 0 0 1 10 0", 0.1));
}

TEST(SvgPath, DataMustStartWithMoveto) {
  const ParseError e = path_error("L 10 10");
  EXPECT_EQ(e.offset, 0u);
  EXPECT_NE(std::string(e.what()).find("moveto"), std::string::npos) << e.what();
  EXPECT_EQ(path_error("  10 10").offset, 2u);
}

TEST(SvgPath, TruncatedCommands) {
  const ParseError l = path_error("M 10 10 L");
  EXPECT_NE(std::string(l.what()).find("expected a number after 'L'"), std::string::npos) << l.what();
  EXPECT_EQ(l.offset, 9u);
  EXPECT_EQ(path_error("M 10").offset, 4u);
  EXPECT_EQ(path_error("M 10 10 C 1 2 3 4 5").offset, 19u);
  EXPECT_EQ(path_error("M 10 10 A 1 1 0 0 1 5").offset, 21u);
  EXPECT_EQ(path_error("M 10 10 L 5 5 6").offset, 15u);
  EXPECT_EQ(path_error("M 10 10 L 5 Z").offset, 12u);
  // a stray word gets the same message, naming the command
  EXPECT_NE(std::string(path_error("M 0 0 L 1 nope").what()).find("expected a number after 'L', found 'nope'"),
            std::string::npos);
}

TEST(SvgPath, UnknownCommandsAndStrayCharacters) {
  const ParseError x = path_error("M 10 10 X 5");
  EXPECT_EQ(x.offset, 8u);
  EXPECT_NE(std::string(x.what()).find("unknown path command 'X'"), std::string::npos) << x.what();
  EXPECT_EQ(path_error("M 0 0 # 1").offset, 6u);
  EXPECT_EQ(path_error("M 0 0 Z 5 5").offset, 8u);
  EXPECT_EQ(path_error("M 0 0 L 1,,2").offset, 10u);
  EXPECT_EQ(path_error("M 0 0, L 1 1").offset, 5u);
}

TEST(SvgPath, BadArcFlags) {
  for (const char* d : {"M0 0 A 1 1 0 2 1 5 5", "M0 0 A 1 1 0 0 .5 5 5", "M0 0 A 1 1 0 -1 1 5 5", "M0 0 A 1 1 0 x 1 5 5"}) {
    const ParseError e = path_error(d);
    EXPECT_EQ(e.offset, std::string(d).find_first_of("2.-x", 12)) << d;
    EXPECT_NE(std::string(e.what()).find("arc flag"), std::string::npos) << e.what();
  }
}

TEST(SvgPath, NonFiniteAndHugeNumbers) {
  EXPECT_NE(std::string(path_error("M 10 10 L 5 nan").what()).find("finite"), std::string::npos);
  EXPECT_EQ(path_error("M 10 10 L inf 0").offset, 10u);
  EXPECT_EQ(path_error("M 10 10 L -Infinity 0").offset, 10u);
  const ParseError big = path_error("M 10 10 L 1e400 0");
  EXPECT_STREQ(big.what(), "number 1e400 is out of range");
  EXPECT_EQ(big.offset, 10u);
  EXPECT_EQ(path_error("M 10 10 L 5e9 0").offset, 10u);
}

TEST(SvgEllipse, CircleWithinTolerance) {
  const double tol = 0.01;
  const Points p = ellipse_points(5, 5, 10, 10, kIdentity, tol);
  ASSERT_GE(p.size(), 8u);
  // starts at angle 0, (cx + r, cy); counter-clockwise in user coordinates (positive area)
  EXPECT_EQ(p.front(), Vec2(15, 5));
  EXPECT_GT(area(p), 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_NEAR((p[i] - Vec2(5, 5)).norm(), 10, 1e-9);
    const Vec2 mid = 0.5 * (p[i] + p[(i + 1) % p.size()]);
    EXPECT_LE(10 - (mid - Vec2(5, 5)).norm(), tol);
  }
  EXPECT_GE(area(p), M_PI * 100 - 2 * M_PI * 10 * tol);
}

TEST(SvgEllipse, DegenerateAndCoarse) {
  EXPECT_TRUE(ellipse_points(0, 0, 0, 5, kIdentity, 0.01).empty());
  EXPECT_TRUE(ellipse_points(0, 0, 5, -1, kIdentity, 0.01).empty());
  // a tolerance larger than the circle still gives eight sides
  EXPECT_EQ(ellipse_points(0, 0, 1, 1, kIdentity, 100).size(), 8u);
  // an ellipse (rx 20, ry 5): every point on it
  for (const Vec2& q : ellipse_points(0, 0, 20, 5, kIdentity, 0.01))
    EXPECT_NEAR(std::pow(q.x() / 20, 2) + std::pow(q.y() / 5, 2), 1, 1e-9);
}

TEST(SvgRect, SharpCorners) {
  expect_points(rect_points(0, 0, 4, 2, 0, 0, kIdentity, 0.01), {{0, 0}, {4, 0}, {4, 2}, {0, 2}});
  // mapped: translate(10, 0)
  Eigen::Affine2d w = Eigen::Affine2d::Identity();
  w.translation() << 10, 0;
  expect_points(rect_points(1, 1, 1, 1, 0, 0, w, 0.01), {{11, 1}, {12, 1}, {12, 2}, {11, 2}});
  EXPECT_TRUE(rect_points(0, 0, 0, 5, 0, 0, kIdentity, 0.01).empty());
  EXPECT_TRUE(rect_points(0, 0, 5, -1, 0, 0, kIdentity, 0.01).empty());
}

TEST(SvgRect, RoundedCorners) {
  // 10 x 6 with corner radii (2,1): area = 60 - (4 - π) rx ry = 60 - 2 (4 - π)
  const double tol = 0.001;
  const Points p = rect_points(0, 0, 10, 6, 2, 1, kIdentity, tol);
  EXPECT_EQ(p.front(), Vec2(2, 0));
  for (const Vec2& corner : {Vec2(8, 0), Vec2(10, 1), Vec2(10, 5), Vec2(8, 6), Vec2(2, 6), Vec2(0, 5), Vec2(0, 1)})
    EXPECT_NE(std::find(p.begin(), p.end(), corner), p.end()) << corner.transpose();
  for (const Vec2& q : p) {
    EXPECT_TRUE(q.x() >= 0 && q.x() <= 10 && q.y() >= 0 && q.y() <= 6) << q.transpose();
  }
  const double want = 60 - 2 * (4 - M_PI);
  EXPECT_LE(area(p), want);
  EXPECT_GE(area(p), want - 4 * (0.5 * M_PI * 2) * tol);
}

TEST(SvgRect, FullyRoundedHasNoDuplicatePoints) {
  // rx = w/2 and ry = h/2: the straight sides vanish; radii beyond that are clamped
  for (const Points& p : {rect_points(0, 0, 4, 2, 2, 1, kIdentity, 0.01), rect_points(0, 0, 4, 2, 9, 9, kIdentity, 0.01)}) {
    for (std::size_t i = 0; i < p.size(); ++i) EXPECT_NE(p[i], p[(i + 1) % p.size()]) << i;
    for (const Vec2& q : p) EXPECT_NEAR(std::pow((q.x() - 2) / 2, 2) + std::pow(q.y() - 1, 2), 1, 1e-9);
  }
}

}  // namespace
}  // namespace rescuesim::svg
