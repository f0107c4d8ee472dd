#include "core/polygon.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rescuesim {
namespace {

const Polygon2 kSquare = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};

TEST(Polygon, AreaAndCentroidOfASquare) {
  EXPECT_DOUBLE_EQ(signed_area(kSquare), 4.0);
  Polygon2 cw(kSquare.rbegin(), kSquare.rend());
  EXPECT_DOUBLE_EQ(signed_area(cw), -4.0);
  EXPECT_TRUE(centroid(kSquare).isApprox(Vec2(1, 1)));
}

TEST(Polygon, CentroidOfAnLShape) {
  // 2x2 square plus a 2x1 strip on top-left: centroid by composite areas
  const Polygon2 l = {{0, 0}, {2, 0}, {2, 2}, {1, 2}, {1, 3}, {0, 3}};
  // areas: 4 at (1,1), 1 at (0.5,2.5) -> (4.5/5, 6.5/5)
  EXPECT_NEAR(signed_area(l), 5.0, 1e-12);
  EXPECT_TRUE(centroid(l).isApprox(Vec2(0.9, 1.3)));
}

TEST(Polygon, ContainsAndDistance) {
  EXPECT_TRUE(contains(kSquare, {1, 1}));
  EXPECT_FALSE(contains(kSquare, {3, 1}));
  EXPECT_DOUBLE_EQ(distance_to_polygon(kSquare, {3, 1}), 1.0);
  EXPECT_DOUBLE_EQ(distance_to_polygon(kSquare, {1, 1}), 0.0);
  EXPECT_NEAR(distance_to_polygon(kSquare, {3, 3}), std::sqrt(2.0), 1e-12);
}

TEST(Polygon, TriangulationCoversTheArea) {
  const Polygon2 l = {{0, 0}, {2, 0}, {2, 2}, {1, 2}, {1, 3}, {0, 3}};
  const auto tris = triangulate(l);
  ASSERT_EQ(tris.size(), l.size() - 2);
  double area = 0;
  for (const auto& t : tris) area += signed_area({l[t[0]], l[t[1]], l[t[2]]});
  EXPECT_NEAR(area, 5.0, 1e-12);
}

TEST(Polygon, SelfCrossingIsNotSimple) {
  const Polygon2 bowtie = {{0, 0}, {2, 2}, {2, 0}, {0, 2}};
  EXPECT_FALSE(is_simple(bowtie));
  EXPECT_TRUE(is_simple(kSquare));
}

TEST(Polygon, OrientedExtentOfARotatedRectangle) {
  const Polygon2 r = rectangle({5, 3, M_PI / 6}, 1.6, 0.4);
  const auto e = oriented_extent(r);
  EXPECT_NEAR(e.length, 1.6, 1e-9);
  EXPECT_NEAR(e.width, 0.4, 1e-9);
  EXPECT_NEAR(e.angle, M_PI / 6, 1e-9);
  EXPECT_TRUE(e.center.isApprox(Vec2(5, 3)));
}

TEST(Polygon, NormalizedIsCounterClockwiseWithoutCollinearPoints) {
  const Polygon2 p = {{0, 2}, {1, 2}, {2, 2}, {2, 0}, {0, 0}, {0, 0}};
  const Polygon2 n = normalized(p);
  EXPECT_EQ(n.size(), 4u);
  EXPECT_GT(signed_area(n), 0);
}

TEST(Polygon, OverlapDetection) {
  const Polygon2 far = {{5, 5}, {6, 5}, {6, 6}};
  const Polygon2 crossing = {{1, 1}, {3, 1}, {3, 3}, {1, 3}};
  const Polygon2 inside = {{0.5, 0.5}, {1, 0.5}, {1, 1}};
  EXPECT_FALSE(polygons_overlap(kSquare, far));
  EXPECT_TRUE(polygons_overlap(kSquare, crossing));
  EXPECT_TRUE(polygons_overlap(kSquare, inside));
}

}  // namespace
}  // namespace rescuesim
