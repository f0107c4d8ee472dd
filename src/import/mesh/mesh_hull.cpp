// convex_hull: Bullet's exact hull (btConvexHullComputer, through hull/hull.h), its faces fanned
// into triangles, then reduced to the vertex budget.
//
// How the reduction works and what it costs: the reduced hull is the hull of a subset of the exact
// hull's vertices, chosen greedily "farthest outside first" (the incremental step of quickhull,
// stopped at the budget). It starts from a large tetrahedron of exact-hull vertices; each round adds
// the exact-hull vertex that lies farthest outside the current reduced hull (distance to its face
// planes) and re-hulls. So the reduced hull always lies inside the exact one (a collision shape
// that is a little too small, never too big), and the error left is the largest outside distance
// of a vertex not taken; each round removes the current worst, which puts the kept vertices where
// the shape bulges most. Support points along a fixed set of directions (a Fibonacci sphere) were
// the alternative: as good on a sphere, poor on elongated shapes. Measured with 64 vertices, as a
// fraction of the exact hull's volume: 2000 points on a sphere, greedy 0.908, directions 0.912
// (64 vertices evenly on a sphere cannot do much better); the same points on a 10 : 1 : 0.3
// ellipsoid, greedy 0.867, directions 0.259. Cost: about (budget x exact vertices x faces); a
// 30 000-triangle sphere mesh (14 400 hull vertices) takes 25 ms for the exact hull and 100 ms
// more to reduce it to 64 vertices.

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <string>

#include "hull/hull.h"
#include "import/mesh/mesh.h"

namespace rescuesim {

namespace {

/// Throws when the points cannot enclose a volume: fewer than 4, not finite, all equal, all on a
/// line or all in a plane. A spread below 1e-9 of the largest counts as none.
void check_spread(const std::vector<Vec3>& points) {
  if (points.size() < 4) {
    throw Error("convex_hull: needs at least 4 points, got " + std::to_string(points.size()));
  }
  Vec3 mean = Vec3::Zero();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw Error("convex_hull: point " + std::to_string(i) + " is not finite");
    mean += points[i];
  }
  mean /= static_cast<double>(points.size());
  // the covariance's eigenvectors are the principal axes, least spread first; the spreads are
  // measured along them directly (tiny eigenvalues themselves are only accurate to ~1e-16 of
  // the largest, too coarse to tell a plane from a thin slab)
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Vec3& p : points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::Matrix3d axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors();
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& p : points) {
    const Vec3 q = axes.transpose() * (p - mean);
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const Vec3 spread = hi - lo;
  const double tolerance = 1e-9 * spread.maxCoeff();
  if (spread.maxCoeff() <= 0) throw Error("convex_hull: all " + std::to_string(points.size()) + " points are the same point");
  if (spread[1] <= tolerance) throw Error("convex_hull: the points all lie on a line, so they enclose no volume");
  if (spread[0] <= tolerance) throw Error("convex_hull: the points all lie in a plane, so they enclose no volume");
}

/// The exact hull of `points` by Bullet, with the input's own coordinates and outward triangles.
TriangleMesh exact_hull(const std::vector<Vec3>& points) {
  const hull::Hull h = hull::exact_hull(points);
  TriangleMesh hull;
  hull.vertices.reserve(h.vertices.size());
  for (int i : h.vertices) hull.vertices.push_back(points[static_cast<std::size_t>(i)]);
  hull.triangles = h.triangles;
  orient_outward(hull);
  return hull;
}

/// Index of the point farthest by `distance` (ties: the lowest index), skipping those in `skip`.
template <typename Distance>
int farthest(const std::vector<Vec3>& points, const std::vector<int>& skip, Distance&& distance) {
  int best = -1;
  double best_d = -1;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    if (std::find(skip.begin(), skip.end(), i) != skip.end()) continue;
    const double d = distance(points[i]);
    if (d > best_d) best = i, best_d = d;
  }
  return best;
}

/// Four of the points spanning a large tetrahedron: the lowest in x, the farthest from it, the
/// farthest from their line, the farthest from their plane.
std::vector<int> seed_tetrahedron(const std::vector<Vec3>& P) {
  std::vector<int> seed{farthest(P, {}, [](const Vec3& p) { return -p.x(); })};
  const Vec3 a = P[seed[0]];
  seed.push_back(farthest(P, seed, [&](const Vec3& p) { return (p - a).squaredNorm(); }));
  const Vec3 ab = (P[seed[1]] - a).normalized();
  seed.push_back(farthest(P, seed, [&](const Vec3& p) { return (p - a).cross(ab).squaredNorm(); }));
  const Vec3 n = ab.cross(P[seed[2]] - a).normalized();
  seed.push_back(farthest(P, seed, [&](const Vec3& p) { return std::abs(n.dot(p - a)); }));
  return seed;
}

/// The hull of at most `max_vertices` of the exact hull's vertices, chosen farthest outside first.
TriangleMesh reduce(const TriangleMesh& exact, int max_vertices) {
  const std::vector<Vec3>& P = exact.vertices;
  std::vector<int> chosen = seed_tetrahedron(P);
  std::vector<Vec3> kept;
  for (int i : chosen) kept.push_back(P[i]);
  TriangleMesh current = exact_hull(kept);

  while (static_cast<int>(chosen.size()) < max_vertices) {
    // the current hull's face planes, unit normals pointing out
    std::vector<std::pair<Vec3, double>> planes;
    for (const auto& t : current.triangles) {
      const Vec3& a = current.vertices[t[0]];
      const Vec3 n = (current.vertices[t[1]] - a).cross(current.vertices[t[2]] - a);
      if (n.norm() > 0) planes.emplace_back(n.normalized(), n.normalized().dot(a));
    }
    // the vertex farthest outside; none outside means the budget is not needed
    auto outside = [&](const Vec3& p) {
      double d = -1e300;
      for (const auto& [n, offset] : planes) d = std::max(d, n.dot(p) - offset);
      return d;
    };
    const int next = farthest(P, chosen, outside);
    if (next < 0 || outside(P[next]) <= 0) break;
    chosen.push_back(next);
    kept.push_back(P[next]);
    current = exact_hull(kept);
  }
  return current;
}

}  // namespace

TriangleMesh convex_hull(const std::vector<Vec3>& points, int max_vertices) {
  if (max_vertices < 4) throw Error("convex_hull: max_vertices must be at least 4, got " + std::to_string(max_vertices));
  check_spread(points);

  // the exact hull; Bullet's float rounding can still flatten a sliver, so check what came back
  TriangleMesh hull = exact_hull(points);
  if (hull.vertices.size() < 4 || mass_properties(hull).volume <= 0) {
    throw Error("convex_hull: the points are too close to a plane to enclose a volume");
  }
  if (static_cast<int>(hull.vertices.size()) <= max_vertices) return hull;
  return reduce(hull, max_vertices);
}

}  // namespace rescuesim
