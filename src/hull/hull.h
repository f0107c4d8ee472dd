#pragma once
/// Bullet's geometry tools, on plain points and triangles: the exact convex hull of a point set
/// (LinearMath's btConvexHullComputer) and the clusters of Khaled Mamou's HACD (hierarchical
/// approximate convex decomposition, Bullet's extras). Its own module below `world`, outside
/// `physics`, so that `import/mesh` can hull and decompose meshes for importers without linking
/// the physics engine; no Bullet type leaves the .cpp file.

#include <array>
#include <cstddef>
#include <vector>

#include "core/pose.h"

namespace rescuesim::hull {

/// An exact hull: `vertices` index the input points; triangles index `vertices` and fan each
/// hull face from its first corner (their winding is Bullet's; callers orient them).
struct Hull {
  std::vector<int> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// The exact convex hull of `points` (at least 4, spanning a volume: the caller checks).
/// Bullet works in float internally; the indices give back the input's own doubles.
Hull exact_hull(const std::vector<Vec3>& points);

/// HACD's clusters of an outward triangle mesh, merged as far as `concavity` (m, as the mesh's
/// units) allows, with `max_vertices_per_hull` for HACD's own hulls. Returns, per triangle, its
/// cluster in [0, clusters) or -1; empty when HACD fails. Calls are serialised by a lock.
std::vector<long> hacd_partition(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles, double concavity,
                                 int max_vertices_per_hull, std::size_t& clusters);

}  // namespace rescuesim::hull
