// Bullet's convex hull computer and HACD behind plain types (see hull.h). What the
// results are used for, and why these tools, is in import/mesh (mesh_hull.cpp, mesh_decompose.cpp).

#include "hull/hull.h"

#include <HACD/hacdHACD.h>
#include <LinearMath/btConvexHullComputer.h>

#include <mutex>

namespace rescuesim::hull {

Hull exact_hull(const std::vector<Vec3>& points) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles for Bullet");
  btConvexHullComputer computer;
  computer.compute(points.front().data(), static_cast<int>(sizeof(Vec3)), static_cast<int>(points.size()), 0, 0);

  Hull hull;
  hull.vertices.reserve(static_cast<std::size_t>(computer.vertices.size()));
  for (int i = 0; i < computer.vertices.size(); ++i) hull.vertices.push_back(computer.original_vertex_index[i]);

  // each face is a planar convex polygon given by a counter-clockwise edge loop: fan it from its
  // first vertex (the guard stops a malformed loop)
  for (int f = 0; f < computer.faces.size(); ++f) {
    const btConvexHullComputer::Edge* first = &computer.edges[computer.faces[f]];
    const int apex = first->getSourceVertex();
    const btConvexHullComputer::Edge* e = first->getNextEdgeOfFace();
    for (int guard = 0; e->getTargetVertex() != apex && guard < computer.edges.size(); ++guard, e = e->getNextEdgeOfFace()) {
      hull.triangles.push_back({apex, e->getSourceVertex(), e->getTargetVertex()});
    }
  }
  return hull;
}

std::vector<long> hacd_partition(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& mesh_triangles, double concavity,
                                 int max_vertices_per_hull, std::size_t& clusters) {
  static std::mutex hacd_mutex;
  // HACD scales and shifts the points it is given in place, so it gets copies
  std::vector<HACD::Vec3<HACD::Real>> points;
  Vec3 lo = vertices.front(), hi = vertices.front();
  for (const Vec3& v : vertices) {
    points.emplace_back(v.x(), v.y(), v.z());
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  std::vector<HACD::Vec3<long>> triangles;
  for (const auto& t : mesh_triangles) triangles.emplace_back(t[0], t[1], t[2]);

  HACD::HACD hacd;
  hacd.SetPoints(points.data());
  hacd.SetNPoints(points.size());
  hacd.SetTriangles(triangles.data());
  hacd.SetNTriangles(triangles.size());
  // HACD measures concavity after scaling the bounding-box diagonal to 2 * its scale factor
  hacd.SetConcavity(concavity * 2.0 * hacd.GetScaleFactor() / (hi - lo).norm());
  // merge as far as the concavity allows; too many pieces are merged afterwards, by volume
  hacd.SetNClusters(1);
  hacd.SetNVerticesPerCH(static_cast<std::size_t>(max_vertices_per_hull));
  // probes for concavity: triangle centres (concavity inside large faces) and the neighbouring
  // clusters' points (a merge that would swallow a notch); without the second, the flat top and
  // bottom of a finely meshed L merge into one piece. The ray-cast "extra distance points" cost
  // a pass over all triangles per triangle and helped no test shape.
  hacd.SetAddFacesPoints(true);
  hacd.SetAddNeighboursDistPoints(true);
  hacd.SetAddExtraDistPoints(false);

  const std::lock_guard<std::mutex> lock(hacd_mutex);
  if (!hacd.Compute(false)) return {};
  clusters = hacd.GetNClusters();
  std::vector<long> partition(hacd.GetPartition(), hacd.GetPartition() + triangles.size());
  for (long& p : partition) {
    if (p < 0 || static_cast<std::size_t>(p) >= clusters) p = -1;
  }
  return partition;
}

}  // namespace rescuesim::hull
