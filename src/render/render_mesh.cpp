// Render meshes of the World's shapes: per-face vertices for boxes and polyhedra, smooth normals
// for cylinders and spheres, and texture coordinates in metres along each surface.

#include <algorithm>
#include <cmath>

#include "render/render_scene.h"

namespace rescuesim {

namespace {

constexpr int kRoundSegments = 32;

/// Appends a vertex and returns its index.
std::uint32_t add_vertex(RenderMesh& m, const Vec3& p, const Vec3& n, double u, double v) {
  m.positions.push_back(p.cast<float>());
  m.normals.push_back(n.cast<float>());
  m.uvs.emplace_back(static_cast<float>(u), static_cast<float>(v));
  return static_cast<std::uint32_t>(m.positions.size() - 1);
}

void add_triangle(RenderMesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  m.indices.insert(m.indices.end(), {a, b, c});
}

RenderMesh box_mesh(const Vec3& size) {
  RenderMesh m;
  const Vec3 h = 0.5 * size;
  // face with outward axis a and sign s: u runs along s·e_b, v along e_c (b, c cyclic after a),
  // so (u, v, normal) is right-handed and the quad is counter-clockwise seen from outside
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (double s : {1.0, -1.0}) {
      Vec3 n = Vec3::Zero();
      n[a] = s;
      std::uint32_t corner[4];
      const double us[4] = {-1, 1, 1, -1}, vs[4] = {-1, -1, 1, 1};
      for (int k = 0; k < 4; ++k) {
        Vec3 p;
        p[a] = s * h[a];
        p[b] = s * us[k] * h[b];
        p[c] = vs[k] * h[c];
        corner[k] = add_vertex(m, p, n, s * p[b], p[c]);
      }
      add_triangle(m, corner[0], corner[1], corner[2]);
      add_triangle(m, corner[0], corner[2], corner[3]);
    }
  }
  return m;
}

RenderMesh cylinder_mesh(double r, double length) {
  RenderMesh m;
  const double hz = 0.5 * length;
  // side: a seam column repeated so u (arc length) runs 0 .. 2πr without wrapping
  for (int i = 0; i <= kRoundSegments; ++i) {
    const double a = 2 * M_PI * i / kRoundSegments;
    const Vec3 n(std::cos(a), std::sin(a), 0);
    add_vertex(m, Vec3(r * n.x(), r * n.y(), -hz), n, a * r, -hz);
    add_vertex(m, Vec3(r * n.x(), r * n.y(), hz), n, a * r, hz);
  }
  for (std::uint32_t i = 0; i < kRoundSegments; ++i) {
    const std::uint32_t b0 = 2 * i, t0 = b0 + 1, b1 = b0 + 2, t1 = b0 + 3;
    add_triangle(m, b0, b1, t1);
    add_triangle(m, b0, t1, t0);
  }
  // caps: fans around a centre vertex, planar texture coordinates
  for (double s : {1.0, -1.0}) {
    const Vec3 n(0, 0, s);
    const std::uint32_t centre = add_vertex(m, Vec3(0, 0, s * hz), n, 0, 0);
    for (int i = 0; i < kRoundSegments; ++i) {
      const double a = 2 * M_PI * i / kRoundSegments;
      add_vertex(m, Vec3(r * std::cos(a), r * std::sin(a), s * hz), n, r * std::cos(a), r * std::sin(a));
    }
    for (std::uint32_t i = 0; i < kRoundSegments; ++i) {
      const std::uint32_t p = centre + 1 + i, q = centre + 1 + (i + 1) % kRoundSegments;
      if (s > 0) add_triangle(m, centre, p, q);
      else add_triangle(m, centre, q, p);
    }
  }
  return m;
}

RenderMesh sphere_mesh(double r) {
  RenderMesh m;
  const int rings = kRoundSegments / 2;
  // latitude-longitude grid with a repeated seam; u is arc length along the equator, v along a meridian
  for (int i = 0; i <= rings; ++i) {
    const double phi = -M_PI / 2 + M_PI * i / rings;
    for (int j = 0; j <= kRoundSegments; ++j) {
      const double th = 2 * M_PI * j / kRoundSegments;
      const Vec3 n(std::cos(phi) * std::cos(th), std::cos(phi) * std::sin(th), std::sin(phi));
      add_vertex(m, r * n, n, th * r, phi * r);
    }
  }
  const auto at = [](int i, int j) { return static_cast<std::uint32_t>(i * (kRoundSegments + 1) + j); };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < kRoundSegments; ++j) {
      if (i > 0) add_triangle(m, at(i, j), at(i, j + 1), at(i + 1, j + 1));
      if (i + 1 < rings) add_triangle(m, at(i, j), at(i + 1, j + 1), at(i + 1, j));
    }
  }
  return m;
}

/// Flat-shaded copy of a triangle mesh; texture coordinates are the image's (`image`, when it
/// has one per triangle), else they project each face on the plane of the two axes its normal
/// is least aligned with.
RenderMesh flat_mesh(const TriangleMesh& t, const SurfaceImage* image = nullptr) {
  RenderMesh m;
  const bool image_uvs = image && image->corner_uvs.size() == t.triangles.size();
  for (std::size_t f = 0; f < t.triangles.size(); ++f) {
    const auto& tri = t.triangles[f];
    const Vec3& a = t.vertices[static_cast<std::size_t>(tri[0])];
    const Vec3& b = t.vertices[static_cast<std::size_t>(tri[1])];
    const Vec3& c = t.vertices[static_cast<std::size_t>(tri[2])];
    const Vec3 cross = (b - a).cross(c - a);
    if (cross.norm() < 1e-12) continue;
    const Vec3 n = cross.normalized();
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    const int iu = axis == 0 ? 1 : 0, iv = axis == 2 ? 1 : 2;
    std::uint32_t k[3];
    const Vec3* ps[3] = {&a, &b, &c};
    for (int i = 0; i < 3; ++i) {
      const Vec2 uv = image_uvs ? image->corner_uvs[f][static_cast<std::size_t>(i)] : Vec2((*ps[i])[iu], (*ps[i])[iv]);
      k[i] = add_vertex(m, *ps[i], n, uv.x(), uv.y());
    }
    add_triangle(m, k[0], k[1], k[2]);
  }
  return m;
}

}  // namespace

RenderMesh render_mesh_of(const Geometry& g) {
  switch (g.type) {
    case Geometry::Type::box: return box_mesh(g.size);
    case Geometry::Type::cylinder: return cylinder_mesh(0.5 * g.size.x(), g.size.z());
    case Geometry::Type::sphere: return sphere_mesh(0.5 * g.size.x());
    case Geometry::Type::convex: return flat_mesh(mesh_of(g));
    case Geometry::Type::mesh: return flat_mesh(g.mesh, g.image.get());
  }
  return {};
}

}  // namespace rescuesim
