// convex_hull against shapes with known hulls: a cube with points inside and on its faces, a
// sampled sphere reduced to the vertex budget, and degenerate inputs that must be refused.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "import/mesh/mesh.h"

namespace rescuesim {
namespace {

using ::testing::HasSubstr;

/// Every triangle's normal points away from the hull's centroid (and none is degenerate).
void expect_outward(const TriangleMesh& hull) {
  const Vec3 c = mass_properties(hull).centroid;
  for (const auto& t : hull.triangles) {
    const Vec3 &a = hull.vertices[t[0]], &b = hull.vertices[t[1]], &d = hull.vertices[t[2]];
    const Vec3 n = (b - a).cross(d - a);
    EXPECT_GT(n.norm(), 0);
    EXPECT_GT(n.dot((a + b + d) / 3.0 - c), 0);
  }
}

/// n points spread evenly over a sphere of radius r (a Fibonacci lattice).
std::vector<Vec3> sphere_points(int n, double r) {
  std::vector<Vec3> points;
  const double golden = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, rho = std::sqrt(1 - z * z), phi = golden * i;
    points.emplace_back(r * rho * std::cos(phi), r * rho * std::sin(phi), r * z);
  }
  return points;
}

std::vector<Vec3> unit_cube_corners() {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  return corners;
}

TEST(ConvexHull, CubeCornersWithInteriorPoints) {
  std::vector<Vec3> points = unit_cube_corners();
  for (double x : {0.25, 0.5, 0.75}) {
    for (double y : {0.25, 0.5, 0.75}) {
      for (double z : {0.25, 0.5, 0.75}) points.emplace_back(x, y, z);
    }
  }
  const TriangleMesh hull = convex_hull(points);
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.triangles.size(), 12u);
  // the hull's vertices are the input corners, exactly
  for (const Vec3& v : hull.vertices) EXPECT_NE(std::find(points.begin(), points.begin() + 8, v), points.begin() + 8);
  const MassProperties mp = mass_properties(hull);
  EXPECT_NEAR(mp.volume, 1.0, 1e-12);
  EXPECT_NEAR((mp.centroid - Vec3(0.5, 0.5, 0.5)).norm(), 0, 1e-12);
  expect_outward(hull);
}

TEST(ConvexHull, PointsOnFacesAndEdgesAddNoVertices) {
  std::vector<Vec3> points = unit_cube_corners();
  points.emplace_back(0.5, 0.5, 0);    // face centre
  points.emplace_back(1, 0.5, 0.5);    // face centre
  points.emplace_back(0.5, 0, 0);      // edge midpoint
  points.emplace_back(1, 1, 0.25);     // on an edge
  const TriangleMesh hull = convex_hull(points);
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.triangles.size(), 12u);
  EXPECT_NEAR(mass_properties(hull).volume, 1.0, 1e-12);
}

TEST(ConvexHull, SphereIsReducedToTheVertexBudget) {
  const double r = 0.5;
  const auto points = sphere_points(2000, r);
  // the exact hull of 2000 points on the sphere loses a fraction of a percent of its volume
  const TriangleMesh exact = convex_hull(points, 4000);
  EXPECT_EQ(exact.vertices.size(), 2000u);
  const double sphere = 4.0 / 3.0 * M_PI * r * r * r;
  const double exact_volume = mass_properties(exact).volume;
  EXPECT_NEAR(exact_volume / sphere, 1.0, 0.01);

  const TriangleMesh reduced = convex_hull(points, 64);
  EXPECT_LE(reduced.vertices.size(), 64u);
  EXPECT_GE(reduced.vertices.size(), 60u);
  const double reduced_volume = mass_properties(reduced).volume;
  // inside the exact hull (its vertices are input points) and within 10% of its volume
  EXPECT_LE(reduced_volume, exact_volume);
  EXPECT_GE(reduced_volume, 0.9 * exact_volume);
  for (const Vec3& v : reduced.vertices) EXPECT_NEAR(v.norm(), r, 1e-12);
  expect_outward(reduced);
  // a closed surface: every edge is shared by exactly two triangles (V - E + F = 2)
  EXPECT_EQ(reduced.triangles.size(), 2 * reduced.vertices.size() - 4);
}

TEST(ConvexHull, SameInputGivesTheSameHull) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> points;
  for (int i = 0; i < 500; ++i) points.emplace_back(u(rng), 2 * u(rng), 0.5 * u(rng));
  const TriangleMesh a = convex_hull(points, 16), b = convex_hull(points, 16);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_LE(a.vertices.size(), 16u);
  expect_outward(a);
}

TEST(ConvexHull, DegenerateInputsAreRefused) {
  EXPECT_THAT(
      [] {
        convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
      },
      ::testing::ThrowsMessage<Error>(HasSubstr("at least 4 points, got 3")));
  std::vector<Vec3> line, plane, same;
  for (int i = 0; i < 10; ++i) line.emplace_back(1 + i, 2 + 2 * i, 3 - i);
  // a tilted plane: z = 0.3 x - 0.2 y + 1
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 4; ++j) plane.emplace_back(i, j, 0.3 * i - 0.2 * j + 1);
  }
  for (int i = 0; i < 5; ++i) same.emplace_back(1, 1, 1);
  EXPECT_THAT([&] { convex_hull(line); }, ::testing::ThrowsMessage<Error>(HasSubstr("on a line")));
  EXPECT_THAT([&] { convex_hull(plane); }, ::testing::ThrowsMessage<Error>(HasSubstr("in a plane")));
  EXPECT_THAT([&] { convex_hull(same); }, ::testing::ThrowsMessage<Error>(HasSubstr("same point")));
  std::vector<Vec3> nan = unit_cube_corners();
  nan[3].y() = std::nan("");
  EXPECT_THAT([&] { convex_hull(nan); }, ::testing::ThrowsMessage<Error>(HasSubstr("point 3 is not finite")));
  EXPECT_THAT([] { convex_hull(unit_cube_corners(), 3); }, ::testing::ThrowsMessage<Error>(HasSubstr("max_vertices must be at least 4")));
}

}  // namespace
}  // namespace rescuesim
