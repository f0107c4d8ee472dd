#include "core/polygon.h"

#include <algorithm>
#include <cmath>

namespace rescuesim {

namespace {
double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
double orient(const Vec2& a, const Vec2& b, const Vec2& c) { return cross(b - a, c - a); }

bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c), d4 = orient(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return false;
}
}  // namespace

double signed_area(const Polygon2& poly) {
  double a = 0;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) a += cross(poly[i], poly[(i + 1) % n]);
  return 0.5 * a;
}

Vec2 centroid(const Polygon2& poly) {
  if (poly.empty()) return Vec2::Zero();
  const double a = signed_area(poly);
  if (std::abs(a) < 1e-12) {
    Vec2 m = Vec2::Zero();
    for (const auto& p : poly) m += p;
    return m / static_cast<double>(poly.size());
  }
  // shift to the first vertex to keep the sums well conditioned far from the origin
  const Vec2 o = poly[0];
  Vec2 c = Vec2::Zero();
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 p = poly[i] - o, q = poly[(i + 1) % n] - o;
    c += (p + q) * cross(p, q);
  }
  return o + c / (6.0 * a);
}

Box2 bounds(const Polygon2& poly) {
  Box2 b;
  for (const auto& p : poly) b.extend(p);
  return b;
}

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

bool contains(const Polygon2& poly, const Vec2& p, double eps) {
  const std::size_t n = poly.size();
  if (n < 3) return false;
  bool inside = false;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if (distance_to_segment(p, a, b) <= eps) return true;
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

double distance_to_polygon(const Polygon2& poly, const Vec2& p) {
  if (contains(poly, p)) return 0.0;
  double d = 1e300;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) d = std::min(d, distance_to_segment(p, poly[i], poly[(i + 1) % n]));
  return d;
}

bool is_simple(const Polygon2& poly) {
  const std::size_t n = poly.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;
      if (segments_cross(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n])) return false;
    }
  }
  return true;
}

Polygon2 normalized(const Polygon2& poly, double eps) {
  Polygon2 out;
  for (const auto& p : poly) {
    if (out.empty() || (p - out.back()).norm() > eps) out.push_back(p);
  }
  while (out.size() > 1 && (out.front() - out.back()).norm() <= eps) out.pop_back();
  // drop vertices on a straight line between their neighbours
  bool changed = true;
  while (changed && out.size() > 3) {
    changed = false;
    for (std::size_t i = 0; i < out.size(); ++i) {
      const Vec2& a = out[(i + out.size() - 1) % out.size()];
      const Vec2& b = out[i];
      const Vec2& c = out[(i + 1) % out.size()];
      if (std::abs(orient(a, b, c)) <= eps * std::max(1.0, (c - a).norm()) && (b - a).dot(c - b) >= 0) {
        out.erase(out.begin() + static_cast<long>(i));
        changed = true;
        break;
      }
    }
  }
  if (signed_area(out) < 0) std::reverse(out.begin(), out.end());
  return out;
}

std::vector<std::array<int, 3>> triangulate(const Polygon2& poly_in) {
  std::vector<std::array<int, 3>> tris;
  const int n = static_cast<int>(poly_in.size());
  if (n < 3) return tris;
  std::vector<int> idx(n);
  for (int i = 0; i < n; ++i) idx[i] = i;
  if (signed_area(poly_in) < 0) std::reverse(idx.begin(), idx.end());
  const auto& P = poly_in;
  // ear clipping: O(n^2) per ear in the worst case, fine for hand-drawn shapes
  int guard = 0;
  while (idx.size() > 3 && guard < 10 * n * n) {
    ++guard;
    bool clipped = false;
    const int m = static_cast<int>(idx.size());
    for (int i = 0; i < m; ++i) {
      const int ia = idx[(i + m - 1) % m], ib = idx[i], ic = idx[(i + 1) % m];
      if (orient(P[ia], P[ib], P[ic]) <= 1e-15) continue;  // reflex or degenerate corner
      bool ear = true;
      for (int k = 0; k < m && ear; ++k) {
        const int ip = idx[k];
        if (ip == ia || ip == ib || ip == ic) continue;
        if (orient(P[ia], P[ib], P[ip]) >= 0 && orient(P[ib], P[ic], P[ip]) >= 0 && orient(P[ic], P[ia], P[ip]) >= 0) {
          ear = false;
        }
      }
      if (!ear) continue;
      tris.push_back({ia, ib, ic});
      idx.erase(idx.begin() + i);
      clipped = true;
      break;
    }
    if (!clipped) {
      // numerically stuck (nearly degenerate input): clip the most convex corner anyway
      tris.push_back({idx[m - 1], idx[0], idx[1]});
      idx.erase(idx.begin());
    }
  }
  if (idx.size() == 3) tris.push_back({idx[0], idx[1], idx[2]});
  return tris;
}

Polygon2 convex_hull(std::vector<Vec2> pts) {
  std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() < 3) return pts;
  Polygon2 h(2 * pts.size());
  std::size_t k = 0;
  for (const auto& p : pts) {
    while (k >= 2 && orient(h[k - 2], h[k - 1], p) <= 0) --k;
    h[k++] = p;
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && orient(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  h.resize(k - 1);
  return h;
}

OrientedExtent oriented_extent(const Polygon2& poly) {
  OrientedExtent best;
  const Polygon2 hull = convex_hull(poly);
  if (hull.size() < 3) {
    const Box2 b = bounds(poly);
    best.center = b.empty() ? Vec2::Zero() : Vec2(0.5 * (b.min + b.max));
    if (hull.size() == 2) {
      const Vec2 d = hull[1] - hull[0];
      best.angle = std::atan2(d.y(), d.x());
      if (best.angle < 0) best.angle += M_PI;
      best.length = d.norm();
    }
    return best;
  }
  // rotating calipers, simplified: try each hull edge direction
  double best_area = 1e300;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec2 e = hull[(i + 1) % hull.size()] - hull[i];
    const double yaw = std::atan2(e.y(), e.x());
    const AxisExtent x = extent_along(hull, yaw);
    const double area = x.along * x.across;
    if (area < best_area - 1e-12) {
      best_area = area;
      best.center = x.centre;
      best.length = std::max(x.along, x.across);
      best.width = std::min(x.along, x.across);
      double a = x.along >= x.across ? yaw : yaw + M_PI / 2;
      a = std::fmod(a + 2 * M_PI, M_PI);
      best.angle = a;
    }
  }
  return best;
}

AxisExtent extent_along(const std::vector<Vec2>& pts, double yaw) {
  const Vec2 u(std::cos(yaw), std::sin(yaw)), v(-std::sin(yaw), std::cos(yaw));
  double lo_u = 1e300, hi_u = -1e300, lo_v = 1e300, hi_v = -1e300;
  for (const auto& p : pts) {
    lo_u = std::min(lo_u, p.dot(u));
    hi_u = std::max(hi_u, p.dot(u));
    lo_v = std::min(lo_v, p.dot(v));
    hi_v = std::max(hi_v, p.dot(v));
  }
  return {u * 0.5 * (lo_u + hi_u) + v * 0.5 * (lo_v + hi_v), hi_u - lo_u, hi_v - lo_v};
}

Polygon2 rectangle(const Pose2& c, double length, double width) {
  const double hl = 0.5 * length, hw = 0.5 * width;
  return {c.transform({-hl, -hw}), c.transform({hl, -hw}), c.transform({hl, hw}), c.transform({-hl, hw})};
}

bool polygons_overlap(const Polygon2& a, const Polygon2& b) {
  if (a.size() < 3 || b.size() < 3) return false;
  if (!bounds(a).overlaps(bounds(b))) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (segments_cross(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()])) return true;
    }
  }
  // no crossing edges: one contains the other, or they are apart
  return contains(a, centroid(b), 0) || contains(b, centroid(a), 0) || contains(a, b[0], 0) || contains(b, a[0], 0);
}

}  // namespace rescuesim
