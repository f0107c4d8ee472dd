#include "render/fog_volumes.h"

#include <algorithm>
#include <cmath>

#include "core/polygon.h"
#include "world/geometry.h"
#include "world/media.h"

namespace rescuesim {

namespace {

/// The half-planes of a counter-clockwise convex polygon: outward normal (dy, -dx) of each edge.
std::vector<Vec3> half_planes_of(const Polygon2& convex) {
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < convex.size(); ++i) {
    const Vec2& a = convex[i];
    const Vec2& b = convex[(i + 1) % convex.size()];
    const Vec2 e = b - a;
    if (e.norm() < 1e-12) continue;
    const Vec2 n = Vec2(e.y(), -e.x()).normalized();
    out.emplace_back(n.x(), n.y(), n.dot(a));
  }
  return out;
}

}  // namespace

std::vector<FogPiece> fog_pieces(std::span<const MediumSpec> media, double t) {
  std::vector<FogPiece> out;
  for (const MediumSpec& m : media) {
    if (m.density <= 0) continue;
    FogPiece base;
    base.bottom = m.bottom;
    base.top = m.bottom + m.height;
    base.sigma_visible = extinction(m, SensingBand::visible);
    base.sigma_near_infrared = extinction(m, SensingBand::near_infrared);
    base.sigma_long_wave = extinction(m, SensingBand::long_wave_infrared);
    base.albedo = scattering_albedo(m.kind);
    const Polygon2 outline = normalized(medium_outline(m, t));
    if (outline.size() < 3) continue;
    std::vector<Polygon2> convex;
    if (is_convex(outline)) {
      convex.push_back(outline);
    } else if (!is_simple(outline)) {
      convex.push_back(convex_hull(outline));
    } else {
      for (const auto& tri : triangulate(outline)) {
        convex.push_back({outline[static_cast<std::size_t>(tri[0])], outline[static_cast<std::size_t>(tri[1])],
                          outline[static_cast<std::size_t>(tri[2])]});
      }
    }
    for (const Polygon2& c : convex) {
      FogPiece p = base;
      p.half_planes = half_planes_of(c);
      p.corners = c;
      if (p.half_planes.size() >= 3) out.push_back(std::move(p));
    }
  }
  return out;
}

Vec3 fog_optical_depth(std::span<const FogPiece> pieces, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double length = d.norm();
  Vec3 tau = Vec3::Zero();
  for (const FogPiece& p : pieces) {
    double t0 = 0, t1 = 1;
    if (std::abs(d.z()) > 1e-12) {
      const double ta = (p.bottom - a.z()) / d.z(), tb = (p.top - a.z()) / d.z();
      t0 = std::max(t0, std::min(ta, tb));
      t1 = std::min(t1, std::max(ta, tb));
    } else if (a.z() < p.bottom || a.z() > p.top) {
      continue;
    }
    for (const Vec3& h : p.half_planes) {
      const double s0 = h.x() * a.x() + h.y() * a.y() - h.z();  // > 0 outside
      const double ds = h.x() * d.x() + h.y() * d.y();
      if (std::abs(ds) < 1e-12) {
        if (s0 > 0) t1 = -1;
      } else if (ds > 0) {
        t1 = std::min(t1, -s0 / ds);
      } else {
        t0 = std::max(t0, -s0 / ds);
      }
    }
    const double inside = std::max(t1 - t0, 0.0) * length;
    tau += inside * Vec3(p.sigma_visible, p.sigma_near_infrared, p.sigma_long_wave);
  }
  return tau;
}

}  // namespace rescuesim
