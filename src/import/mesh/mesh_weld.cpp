#include "import/mesh/mesh_detail.h"

#include <algorithm>
#include <numeric>

namespace rescuesim::mesh_detail {

TriangleMesh weld(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles, std::vector<int>* kept) {
  const std::size_t n = vertices.size();

  // sort vertex indices by coordinates; equal coordinates end up side by side, lowest index first
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](int a, int b) {
    const Vec3& p = vertices[a];
    const Vec3& q = vertices[b];
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);

  // every vertex points at the first (lowest-index) vertex with the same coordinates
  std::vector<int> representative(n);
  for (std::size_t i = 0; i < n; ++i) {
    const int v = order[i];
    const bool same = i > 0 && vertices[order[i - 1]] == vertices[v];
    representative[v] = same ? representative[order[i - 1]] : v;
  }

  // keep the triangles with three distinct vertices, numbering vertices in order of first use
  TriangleMesh out;
  std::vector<int> new_index(n, -1);
  out.triangles.reserve(triangles.size());
  if (kept) kept->clear();
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    std::array<int, 3> r{representative[t[0]], representative[t[1]], representative[t[2]]};
    if (r[0] == r[1] || r[1] == r[2] || r[0] == r[2]) continue;
    if (kept) kept->push_back(static_cast<int>(i));
    for (int& v : r) {
      int& slot = new_index[v];
      if (slot < 0) {
        slot = static_cast<int>(out.vertices.size());
        out.vertices.push_back(vertices[v]);
      }
      v = slot;
    }
    out.triangles.push_back(r);
  }
  return out;
}

}  // namespace rescuesim::mesh_detail
