// Vertex clustering (Rossignac and Borrel's grid simplification): the cheapest way to bound the
// size of the mesh handed to HACD, whose run time grows faster than quadratically with the
// triangle count. Its error is bounded by the cell size.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "import/mesh/mesh_detail.h"

namespace rescuesim::mesh_detail {

ClusteredMesh cluster_vertices(const TriangleMesh& mesh, double cell) {
  const std::size_t n = mesh.vertices.size();
  ClusteredMesh out;
  out.vertex_of.assign(n, -1);
  if (n == 0) return out;

  // each vertex's grid cell, counted from the bounding box's low corner
  Vec3 lo = mesh.vertices.front();
  for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v);
  std::vector<std::array<std::int64_t, 3>> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 q = (mesh.vertices[i] - lo) / cell;
    key[i] = {static_cast<std::int64_t>(std::floor(q.x())), static_cast<std::int64_t>(std::floor(q.y())),
              static_cast<std::int64_t>(std::floor(q.z()))};
  }

  // vertices sorted by cell: each run of equal cells is one cluster, placed at its mean
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key[a] != key[b] ? key[a] < key[b] : a < b; });
  std::vector<int> cluster(n);
  std::vector<Vec3> sum;
  std::vector<int> count;
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 0 || key[order[i]] != key[order[i - 1]]) {
      sum.push_back(Vec3::Zero());
      count.push_back(0);
    }
    cluster[order[i]] = static_cast<int>(sum.size()) - 1;
    sum.back() += mesh.vertices[order[i]];
    ++count.back();
  }

  // triangles between three different clusters, each corner set once
  std::vector<std::array<int, 3>> triangles, seen;
  for (const auto& t : mesh.triangles) {
    const std::array<int, 3> c{cluster[t[0]], cluster[t[1]], cluster[t[2]]};
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
    std::array<int, 3> sorted = c;
    std::sort(sorted.begin(), sorted.end());
    seen.push_back(sorted);
    triangles.push_back(c);
  }
  std::vector<std::size_t> first(triangles.size());
  std::iota(first.begin(), first.end(), std::size_t{0});
  std::stable_sort(first.begin(), first.end(), [&](std::size_t a, std::size_t b) { return seen[a] < seen[b]; });
  std::vector<bool> keep(triangles.size(), false);
  for (std::size_t i = 0; i < first.size(); ++i) keep[first[i]] = i == 0 || seen[first[i]] != seen[first[i - 1]];

  // the kept triangles, with clusters numbered in order of first use
  std::vector<int> index_of(sum.size(), -1);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    if (!keep[i]) continue;
    std::array<int, 3> t = triangles[i];
    for (int& c : t) {
      if (index_of[c] < 0) {
        index_of[c] = static_cast<int>(out.mesh.vertices.size());
        out.mesh.vertices.push_back(sum[c] / count[c]);
      }
      c = index_of[c];
    }
    out.mesh.triangles.push_back(t);
  }
  for (std::size_t i = 0; i < n; ++i) out.vertex_of[i] = index_of[cluster[i]];
  return out;
}

ClusteredMesh coarsen(const TriangleMesh& mesh, std::size_t max_triangles) {
  if (mesh.triangles.size() <= max_triangles) {
    ClusteredMesh same{mesh, std::vector<int>(mesh.vertices.size())};
    std::iota(same.vertex_of.begin(), same.vertex_of.end(), 0);
    return same;
  }
  // first guess: a closed surface of area A in cells of side h has about A / h^2 vertices and
  // twice as many triangles
  double area = 0;
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    area += 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
  }
  double cell = std::sqrt(2.0 * area / static_cast<double>(max_triangles));
  if (!(cell > 0)) {
    Vec3 lo = mesh.vertices.front(), hi = lo;
    for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    cell = std::max((hi - lo).norm(), 1e-12) / std::sqrt(static_cast<double>(max_triangles));
  }
  for (;;) {
    ClusteredMesh c = cluster_vertices(mesh, cell);
    if (c.mesh.triangles.size() <= max_triangles) return c;
    cell *= 1.25;
  }
}

}  // namespace rescuesim::mesh_detail
