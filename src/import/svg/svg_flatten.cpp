/// Flattening of Béziers, elliptic arcs, ellipses and rounded rectangles into polylines in
/// world space. Segment counts come from the classic bound on linear interpolation: on a
/// parameter interval of length h, a curve P deviates from its chord by at most h²/8 · max|P''|.

#include <algorithm>
#include <cmath>

#include "import/svg/svg_detail.h"
#include "import/svg/svg_parse.h"

namespace rescuesim::svg {

namespace detail {

namespace {

/// Appends a world point unless it repeats the last one.
void push_world(std::vector<Vec2>& out, const Vec2& p) {
  if (out.empty() || !same_point(out.back(), p)) out.push_back(p);
}

/// The columns are the semi-axes of an ellipse with radii rx, ry turned by the angle whose
/// sine and cosine are s, c.
Eigen::Matrix2d ellipse_axes(double rx, double ry, double s, double c) {
  Eigen::Matrix2d axes;
  axes << c * rx, -s * ry, s * rx, c * ry;
  return axes;
}

}  // namespace

double largest_singular_value(const Eigen::Matrix2d& m) {
  const double a = m.col(0).squaredNorm(), c = m.col(1).squaredNorm(), b = m.col(0).dot(m.col(1));
  const double half_diff = 0.5 * (a - c);
  return std::sqrt(0.5 * (a + c) + std::sqrt(half_diff * half_diff + b * b));
}

bool same_point(const Vec2& a, const Vec2& b) {
  const double scale = std::max({1.0, std::abs(a.x()), std::abs(a.y()), std::abs(b.x()), std::abs(b.y())});
  return std::abs(a.x() - b.x()) <= 1e-12 * scale && std::abs(a.y() - b.y()) <= 1e-12 * scale;
}

int segment_count(double ideal) {
  if (!(ideal < 1000.0)) return 1000;
  if (!(ideal > 1.0)) return 1;
  return int(std::ceil(ideal));
}

void Flattener::point(std::vector<Vec2>& out, const Vec2& p_user) const { push_world(out, W * p_user); }

void Flattener::quad(std::vector<Vec2>& out, const Vec2& p0, const Vec2& c, const Vec2& p1) const {
  // B'' = 2 (P0 - 2C + P1) is constant, so n chords err by at most |P0 - 2C + P1| / (4 n²)
  const Vec2 a = W * p0, b = W * c, e = W * p1;
  const double d = (a - 2.0 * b + e).norm();
  const int n = segment_count(std::sqrt(0.25 * d / tolerance));
  for (int i = 1; i < n; ++i) {
    const double t = double(i) / n, u = 1.0 - t;
    push_world(out, u * u * a + 2.0 * u * t * b + t * t * e);
  }
  push_world(out, e);
}

void Flattener::cubic(std::vector<Vec2>& out, const Vec2& p0, const Vec2& c0, const Vec2& c1,
                      const Vec2& p1) const {
  // |B''| ≤ 6 max(|P0 - 2P1 + P2|, |P1 - 2P2 + P3|), so n chords err by at most 0.75 M / n²
  const Vec2 a = W * p0, b = W * c0, c = W * c1, e = W * p1;
  const double m = std::max((a - 2.0 * b + c).norm(), (b - 2.0 * c + e).norm());
  const int n = segment_count(std::sqrt(0.75 * m / tolerance));
  for (int i = 1; i < n; ++i) {
    const double t = double(i) / n, u = 1.0 - t;
    push_world(out, u * u * u * a + 3.0 * u * u * t * b + 3.0 * u * t * t * c + t * t * t * e);
  }
  push_world(out, e);
}

void Flattener::centre_arc(std::vector<Vec2>& out, const Vec2& c, const Eigen::Matrix2d& axes, double t0, double dt,
                           const Vec2* end) const {
  // |P''| ≤ σ_max of the mapped axes; chords of parameter length h err by at most h² σ / 8
  const double sigma = largest_singular_value(W.linear() * axes);
  const int n = segment_count(std::abs(dt) * std::sqrt(sigma / (8.0 * tolerance)));
  for (int i = 1; i <= n; ++i) {
    if (i == n && end) {
      point(out, *end);
    } else {
      const double t = t0 + dt * double(i) / n;
      point(out, c + axes * Vec2(std::cos(t), std::sin(t)));
    }
  }
}

void Flattener::arc(std::vector<Vec2>& out, const Vec2& p0, double rx, double ry, double phi_deg, bool large,
                    bool sweep, const Vec2& p1) const {
  // SVG implementation notes F.6: identical end points omit the arc, a zero radius makes a line
  if (p0 == p1) return;
  rx = std::abs(rx), ry = std::abs(ry);
  if (rx == 0.0 || ry == 0.0) {
    point(out, p1);
    return;
  }
  double s = 0, c = 1;
  sincos_degrees(phi_deg, s, c);

  // step 1: the half chord in the ellipse's own frame
  const Vec2 h = 0.5 * (p0 - p1);
  const double x1 = c * h.x() + s * h.y(), y1 = -s * h.x() + c * h.y();

  // radii too small to reach the end point grow uniformly until they just do (F.6.6); the
  // centre is then the chord's midpoint
  const double lambda = (x1 / rx) * (x1 / rx) + (y1 / ry) * (y1 / ry);
  double coef = 0;
  if (lambda > 1.0) {
    const double k = std::sqrt(lambda);
    rx *= k, ry *= k;
  } else {
    // step 2: the centre in the ellipse frame, on the side the flags ask for
    const double rx2 = rx * rx, ry2 = ry * ry;
    const double num = rx2 * ry2 - rx2 * y1 * y1 - ry2 * x1 * x1;
    const double den = rx2 * y1 * y1 + ry2 * x1 * x1;
    coef = std::sqrt(std::max(0.0, num / den));
    if (large == sweep) coef = -coef;
  }
  const double cx1 = coef * rx * y1 / ry, cy1 = -coef * ry * x1 / rx;

  // step 3: back to user space; step 4: start angle and sweep
  const Vec2 centre(c * cx1 - s * cy1 + 0.5 * (p0.x() + p1.x()), s * cx1 + c * cy1 + 0.5 * (p0.y() + p1.y()));
  const Vec2 u((x1 - cx1) / rx, (y1 - cy1) / ry), v((-x1 - cx1) / rx, (-y1 - cy1) / ry);
  const double t0 = std::atan2(u.y(), u.x());
  double dt = std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
  if (!sweep && dt > 0) dt -= 2.0 * M_PI;
  if (sweep && dt < 0) dt += 2.0 * M_PI;

  // degenerate numbers (radii many orders of magnitude apart) fall back to the chord
  if (!std::isfinite(centre.x()) || !std::isfinite(centre.y()) || !std::isfinite(rx) || !std::isfinite(ry) ||
      !std::isfinite(t0) || !std::isfinite(dt)) {
    point(out, p1);
    return;
  }
  centre_arc(out, centre, ellipse_axes(rx, ry, s, c), t0, dt, &p1);
}

}  // namespace detail

std::vector<Vec2> ellipse_points(double cx, double cy, double rx, double ry, const Eigen::Affine2d& to_world,
                                 double tolerance) {
  if (!(rx > 0 && ry > 0)) return {};
  // the arc bound over a full turn, with at least eight sides so that a coarse tolerance still
  // gives a recognisable round shape, and at most four times a single curve's limit
  const detail::Flattener f{to_world, tolerance};
  const Eigen::Matrix2d axes = Eigen::Vector2d(rx, ry).asDiagonal();
  const double sigma = detail::largest_singular_value(to_world.linear() * axes);
  const double ideal = 2.0 * M_PI * std::sqrt(sigma / (8.0 * tolerance));
  const int n = !(ideal < 4000.0) ? 4000 : std::max(8, int(std::ceil(ideal)));
  std::vector<Vec2> out;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * double(i) / n;
    f.point(out, Vec2(cx + rx * std::cos(t), cy + ry * std::sin(t)));
  }
  if (out.size() > 1 && detail::same_point(out.front(), out.back())) out.pop_back();
  return out;
}

std::vector<Vec2> rect_points(double x, double y, double w, double h, double rx, double ry,
                              const Eigen::Affine2d& to_world, double tolerance) {
  if (!(w > 0 && h > 0)) return {};
  rx = rx > 0 ? std::min(rx, 0.5 * w) : 0.0;
  ry = ry > 0 ? std::min(ry, 0.5 * h) : 0.0;
  const detail::Flattener f{to_world, tolerance};
  std::vector<Vec2> out;

  // sharp corners, in the same turning sense as ellipse_points (+x first, then +y)
  if (rx == 0.0 || ry == 0.0) {
    for (const Vec2& corner : {Vec2(x, y), Vec2(x + w, y), Vec2(x + w, y + h), Vec2(x, y + h)}) f.point(out, corner);
    if (out.size() > 1 && detail::same_point(out.front(), out.back())) out.pop_back();
    return out;
  }

  // rounded: each side, then a quarter ellipse around the next corner, as SVG draws it
  const Eigen::Matrix2d axes = Eigen::Vector2d(rx, ry).asDiagonal();
  struct Corner {
    Vec2 side_end, centre, arc_end;
    double t0;
  };
  const Corner corners[] = {
      {{x + w - rx, y}, {x + w - rx, y + ry}, {x + w, y + ry}, -0.5 * M_PI},
      {{x + w, y + h - ry}, {x + w - rx, y + h - ry}, {x + w - rx, y + h}, 0.0},
      {{x + rx, y + h}, {x + rx, y + h - ry}, {x, y + h - ry}, 0.5 * M_PI},
      {{x, y + ry}, {x + rx, y + ry}, {x + rx, y}, M_PI},
  };
  f.point(out, Vec2(x + rx, y));
  for (const Corner& k : corners) {
    f.point(out, k.side_end);
    f.centre_arc(out, k.centre, axes, k.t0, 0.5 * M_PI, &k.arc_end);
  }
  if (out.size() > 1 && detail::same_point(out.front(), out.back())) out.pop_back();
  return out;
}

}  // namespace rescuesim::svg
