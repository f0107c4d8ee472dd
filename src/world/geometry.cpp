#include "world/geometry.h"

#include <algorithm>
#include <cmath>

#include "core/polygon.h"

namespace rescuesim {

namespace {
Vec3 mesh_extent(const TriangleMesh& m) {
  if (m.vertices.empty()) return Vec3::Zero();
  Vec3 lo = m.vertices[0], hi = m.vertices[0];
  for (const auto& v : m.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return hi - lo;
}
}  // namespace

Geometry Geometry::box(const Vec3& full_extents) {
  Geometry g;
  g.type = Type::box;
  g.size = full_extents;
  return g;
}

Geometry Geometry::cylinder(double radius, double length) {
  Geometry g;
  g.type = Type::cylinder;
  g.size = {2 * radius, 2 * radius, length};
  return g;
}

Geometry Geometry::sphere(double radius) {
  Geometry g;
  g.type = Type::sphere;
  g.size = {2 * radius, 2 * radius, 2 * radius};
  return g;
}

Geometry Geometry::convex(TriangleMesh hull) {
  Geometry g;
  g.type = Type::convex;
  g.size = mesh_extent(hull);
  g.mesh = std::move(hull);
  return g;
}

Geometry Geometry::triangles(TriangleMesh mesh) {
  Geometry g;
  g.type = Type::mesh;
  g.size = mesh_extent(mesh);
  g.mesh = std::move(mesh);
  return g;
}

Vec3 solid_inertia(const Geometry& g, double mass) {
  const double x = g.size.x(), y = g.size.y(), z = g.size.z();
  switch (g.type) {
    case Geometry::Type::cylinder: {
      const double rad = 0.5 * x;
      return Vec3(mass * (3 * rad * rad + z * z) / 12, mass * (3 * rad * rad + z * z) / 12, mass * rad * rad / 2);
    }
    case Geometry::Type::sphere: {
      const double rad = 0.5 * x;
      return Vec3::Constant(0.4 * mass * rad * rad);
    }
    default:
      return mass / 12.0 * Vec3(y * y + z * z, x * x + z * z, x * x + y * y);
  }
}

TriangleMesh mesh_of(const Geometry& g, int segments) {
  TriangleMesh m;
  switch (g.type) {
    case Geometry::Type::box: {
      const Vec3 h = 0.5 * g.size;
      for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z());
      // two triangles per face, counter-clockwise seen from outside
      const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
      for (const auto& f : faces) {
        m.triangles.push_back({f[0], f[1], f[2]});
        m.triangles.push_back({f[0], f[2], f[3]});
      }
      return m;
    }
    case Geometry::Type::cylinder: {
      const double r = 0.5 * g.size.x(), hz = 0.5 * g.size.z();
      Polygon2 circle;
      for (int i = 0; i < segments; ++i) {
        const double a = 2 * M_PI * i / segments;
        circle.emplace_back(r * std::cos(a), r * std::sin(a));
      }
      return extrude(circle, -hz, hz);
    }
    case Geometry::Type::sphere: {
      const double r = 0.5 * g.size.x();
      const int rings = std::max(4, segments / 2);
      m.vertices.emplace_back(0, 0, -r);
      for (int i = 1; i < rings; ++i) {
        const double phi = -M_PI / 2 + M_PI * i / rings;
        for (int j = 0; j < segments; ++j) {
          const double th = 2 * M_PI * j / segments;
          m.vertices.emplace_back(r * std::cos(phi) * std::cos(th), r * std::cos(phi) * std::sin(th), r * std::sin(phi));
        }
      }
      m.vertices.emplace_back(0, 0, r);
      const int top = static_cast<int>(m.vertices.size()) - 1;
      auto at = [&](int ring, int j) { return 1 + (ring - 1) * segments + (j % segments); };
      for (int j = 0; j < segments; ++j) m.triangles.push_back({0, at(1, j + 1), at(1, j)});
      for (int i = 1; i + 1 < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
          m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
          m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
      }
      for (int j = 0; j < segments; ++j) m.triangles.push_back({top, at(rings - 1, j), at(rings - 1, j + 1)});
      return m;
    }
    case Geometry::Type::convex:
    case Geometry::Type::mesh: return g.mesh;
  }
  return m;
}

TriangleMesh extrude(const std::vector<Vec2>& polygon, double z0, double z1) {
  TriangleMesh m;
  const int n = static_cast<int>(polygon.size());
  for (const auto& p : polygon) m.vertices.emplace_back(p.x(), p.y(), z0);
  for (const auto& p : polygon) m.vertices.emplace_back(p.x(), p.y(), z1);
  // caps from the 2D triangulation: the top keeps its winding, the bottom is reversed
  for (const auto& t : triangulate(polygon)) {
    m.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});
    m.triangles.push_back({t[0], t[2], t[1]});
  }
  // sides: counter-clockwise outline, so (i, i+1) with up is outward-facing
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.push_back({i, j, j + n});
    m.triangles.push_back({i, j + n, i + n});
  }
  return m;
}

void orient_outward(TriangleMesh& m) {
  if (m.vertices.empty()) return;
  Vec3 c = Vec3::Zero();
  for (const auto& v : m.vertices) c += v;
  c /= static_cast<double>(m.vertices.size());
  for (auto& t : m.triangles) {
    const Vec3& a = m.vertices[static_cast<std::size_t>(t[0])];
    const Vec3 n = (m.vertices[static_cast<std::size_t>(t[1])] - a).cross(m.vertices[static_cast<std::size_t>(t[2])] - a);
    if (n.dot(a - c) < 0) std::swap(t[1], t[2]);
  }
}

bool is_convex(const std::vector<Vec2>& poly) {
  const std::size_t n = poly.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % n], c = poly[(i + 2) % n];
    const Vec2 u = b - a, v = c - b;
    if (u.x() * v.y() - u.y() * v.x() < -1e-12) return false;
  }
  return true;
}

}  // namespace rescuesim
