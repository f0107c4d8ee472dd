// convex_decomposition of a concave L-shaped block (volume 5, convex hull 7) and of a cube.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>

#include "import/mesh/mesh.h"

namespace rescuesim {
namespace {

using ::testing::HasSubstr;

/// An L of two 1 m wide arms, 3 m long, 1 m tall: area 3 + 2 = 5, so volume 5; its hull's
/// footprint is the 3 x 3 square less the triangle (3,1), (3,3), (1,3): volume 9 - 2 = 7.
TriangleMesh l_block() { return extrude({{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}}, 0, 1); }

/// True when p is inside (or on) the convex, outward-facing piece.
bool inside(const TriangleMesh& piece, const Vec3& p) {
  for (const auto& t : piece.triangles) {
    const Vec3& a = piece.vertices[t[0]];
    const Vec3 n = (piece.vertices[t[1]] - a).cross(piece.vertices[t[2]] - a);
    if (n.dot(p - a) > 1e-9) return false;
  }
  return true;
}

/// Volume of the union of the pieces, counted on a grid of cell centres over [lo, hi].
double union_volume(const std::vector<TriangleMesh>& pieces, const Vec3& lo, const Vec3& hi, int cells) {
  const Vec3 step = (hi - lo) / cells;
  int hits = 0;
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      for (int k = 0; k < cells; ++k) {
        const Vec3 p = lo + step.cwiseProduct(Vec3(i + 0.5, j + 0.5, k + 0.5));
        for (const auto& piece : pieces) {
          if (inside(piece, p)) {
            ++hits;
            break;
          }
        }
      }
    }
  }
  return hits * step.prod();
}

TEST(ConvexDecomposition, LShapeSplitsIntoConvexPieces) {
  const TriangleMesh l = l_block();
  ASSERT_NEAR(mass_properties(l).volume, 5.0, 1e-12);
  const double hull_volume = mass_properties(convex_hull(l.vertices)).volume;
  EXPECT_NEAR(hull_volume, 7.0, 1e-12);  // the single hull is 40% too big

  const auto pieces = convex_decomposition(l);
  ASSERT_GE(pieces.size(), 2u);
  double sum = 0;
  for (const auto& piece : pieces) {
    EXPECT_LE(piece.vertices.size(), 32u);
    sum += mass_properties(piece).volume;
  }
  EXPECT_NEAR(sum, 5.0, 0.75);
  EXPECT_NEAR(union_volume(pieces, {-0.5, -0.5, -0.5}, {3.5, 3.5, 1.5}, 60), 5.0, 0.75);
  // the L's far corners are covered and the notch is left open
  auto covered = [&](const Vec3& p) {
    for (const auto& piece : pieces) {
      if (inside(piece, p)) return true;
    }
    return false;
  };
  EXPECT_TRUE(covered({2.9, 0.1, 0.5}));
  EXPECT_TRUE(covered({0.1, 2.9, 0.5}));
  EXPECT_FALSE(covered({2.0, 2.0, 0.5}));
}

/// Each triangle split into four at its edge midpoints, `levels` times (shared edges get one
/// midpoint, so the mesh stays closed).
TriangleMesh subdivided(TriangleMesh m, int levels) {
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      m.vertices.push_back(0.5 * (m.vertices[a] + m.vertices[b]));
      return midpoint[key] = static_cast<int>(m.vertices.size()) - 1;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& t : m.triangles) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({ab, t[1], bc});
      finer.push_back({ca, bc, t[2]});
      finer.push_back({ab, bc, ca});
    }
    m.triangles = std::move(finer);
  }
  return m;
}

TEST(ConvexDecomposition, LargeMeshesAreCoarsenedForHacd) {
  // 5120 triangles, more than HACD is given at once: it sees a coarsened copy, and the pieces
  // are hulls of the L's own vertices. Coarsening makes the result rougher than for the plain L
  // (more, overlapping pieces), but the union still follows the L and leaves the notch open.
  const TriangleMesh fine = subdivided(l_block(), 4);
  ASSERT_EQ(fine.triangles.size(), 5120u);
  ASSERT_NEAR(mass_properties(fine).volume, 5.0, 1e-9);
  const auto pieces = convex_decomposition(fine);
  ASSERT_GE(pieces.size(), 2u);
  EXPECT_LE(pieces.size(), 16u);
  double sum = 0;
  for (const auto& piece : pieces) {
    EXPECT_LE(piece.vertices.size(), 32u);
    sum += mass_properties(piece).volume;
  }
  EXPECT_LT(sum, 7.0);  // tighter than the single hull
  EXPECT_NEAR(union_volume(pieces, {-0.5, -0.5, -0.5}, {3.5, 3.5, 1.5}, 60), 5.0, 0.75);
}

TEST(ConvexDecomposition, SameInputGivesTheSamePieces) {
  const auto a = convex_decomposition(l_block()), b = convex_decomposition(l_block());
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].vertices, b[i].vertices);
    EXPECT_EQ(a[i].triangles, b[i].triangles);
  }
}

TEST(ConvexDecomposition, MaxHullsMergesTheCheapestPieces) {
  DecompositionOptions o;
  o.max_hulls = 1;
  const auto pieces = convex_decomposition(l_block(), o);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_NEAR(mass_properties(pieces[0]).volume, 7.0, 1e-9);
}

TEST(ConvexDecomposition, CubeIsOnePiece) {
  const auto pieces = convex_decomposition(mesh_of(Geometry::box({1, 1, 1})));
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].vertices.size(), 8u);
  EXPECT_NEAR(mass_properties(pieces[0]).volume, 1.0, 1e-12);
}

TEST(ConvexDecomposition, BadOptionsAreRefused) {
  DecompositionOptions o;
  o.max_hulls = 0;
  EXPECT_THAT([&] { convex_decomposition(l_block(), o); }, ::testing::ThrowsMessage<Error>(HasSubstr("max_hulls")));
  o = {};
  o.concavity = -1;
  EXPECT_THAT([&] { convex_decomposition(l_block(), o); }, ::testing::ThrowsMessage<Error>(HasSubstr("concavity")));
}

}  // namespace
}  // namespace rescuesim
