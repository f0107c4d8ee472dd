#include "viz/canvas.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace rescuesim {

namespace {

// largest canvas side and area: keeps allocations sane when sizes come from user input
constexpr int kMaxSide = 32768;
constexpr long long kMaxPixels = 1LL << 27;

bool finite(const Vec2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

double clamp01(double v) { return v < 0 ? 0 : (v > 1 ? 1 : v); }

// a double pixel bound clamped into [lo, hi] before it becomes an int (coordinates may be huge)
int clamp_to_int(double v, int lo, int hi) {
  if (!(v > lo)) return lo;
  if (!(v < hi)) return hi;
  return static_cast<int>(v);
}

// a closed interval on the x axis; empty when lo > hi
struct Span {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  bool empty() const { return lo > hi; }
  void hull(const Span& o) {
    if (o.empty()) return;
    lo = std::min(lo, o.lo);
    hi = std::max(hi, o.hi);
  }
};

// the x values where c0 <= k*x + m <= c1, intersected into s
void constrain(Span& s, double k, double m, double c0, double c1) {
  if (std::abs(k) < 1e-12) {
    if (m < c0 || m > c1) s = Span{};
    return;
  }
  double x0 = (c0 - m) / k, x1 = (c1 - m) / k;
  if (x0 > x1) std::swap(x0, x1);
  s.lo = std::max(s.lo, x0);
  s.hi = std::min(s.hi, x1);
}

// the slice of a disc of radius r at height y
Span disc_slice(const Vec2& c, double r, double y) {
  const double dy = y - c.y();
  if (std::abs(dy) > r) return {};
  const double h = std::sqrt(r * r - dy * dy);
  return {c.x() - h, c.x() + h};
}

// visits every pixel within reach of a stroked segment with its coverage: the distance
// from the pixel centre to the segment gives coverage = clamp(hw + 0.5 - d, 0, 1). Rows
// are cut to the x interval where the stadium of radius hw + 0.5 meets them, so long
// diagonal strokes cost their area, not their bounding box.
template <class Visit>
void stroke_segment(int width, int height, const Vec2& a, const Vec2& b, double hw, Visit&& visit) {
  const double reach = hw + 0.5;
  const int y0 = clamp_to_int(std::floor(std::min(a.y(), b.y()) - reach), 0, height);
  const int y1 = clamp_to_int(std::ceil(std::max(a.y(), b.y()) + reach), 0, height);
  const Vec2 ab = b - a;
  const double len = ab.norm();
  const Vec2 d = len > 0 ? Vec2(ab / len) : Vec2(1, 0);
  const Vec2 n(-d.y(), d.x());
  for (int y = y0; y < y1; ++y) {
    const double yc = y + 0.5;
    // row slice of the stadium: the two end discs and the band between them
    Span s = disc_slice(a, reach, yc);
    s.hull(disc_slice(b, reach, yc));
    if (len > 0) {
      Span band{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
      constrain(band, n.x(), n.y() * (yc - a.y()) - n.x() * a.x(), -reach, reach);
      constrain(band, d.x(), d.y() * (yc - a.y()) - d.x() * a.x(), 0, len);
      s.hull(band);
    }
    if (s.empty()) continue;
    const int x0 = clamp_to_int(std::floor(s.lo - 0.5), 0, width);
    const int x1 = clamp_to_int(std::ceil(s.hi + 0.5), 0, width);
    for (int x = x0; x < x1; ++x) {
      const Vec2 p(x + 0.5, yc);
      // distance to the segment, inlined for speed
      const Vec2 ap = p - a;
      const double t = len > 0 ? std::clamp(ap.dot(d), 0.0, len) : 0.0;
      const double dist = (ap - t * d).norm();
      const double cov = clamp01(reach - dist);
      if (cov > 0) visit(x, y, cov);
    }
  }
}

// strokes thinner than a pixel are drawn one pixel wide and fainter, so they neither
// vanish nor look heavier than they are
void stroke_params(double width, double alpha, double& hw, double& a) {
  const double w = std::max(width, 1.0);
  hw = 0.5 * w;
  a = clamp01(alpha) * std::min(width, 1.0);
}

}  // namespace

Canvas::Canvas(int width, int height, Rgb8 background) : width_(width), height_(height) {
  if (width < 0 || height < 0 || width > kMaxSide || height > kMaxSide ||
      static_cast<long long>(width) * height > kMaxPixels) {
    throw Error("canvas size " + std::to_string(width) + "x" + std::to_string(height) +
                " is out of range (0.." + std::to_string(kMaxSide) + " px per side, at most " +
                std::to_string(kMaxPixels) + " pixels)");
  }
  px_.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  for (std::size_t i = 0; i < px_.size(); i += 3) {
    px_[i] = background.r;
    px_[i + 1] = background.g;
    px_[i + 2] = background.b;
  }
}

Rgb8 Canvas::at(int x, int y) const {
  RS_DEMAND(x >= 0 && y >= 0 && x < width_ && y < height_, "Canvas::at outside the image");
  const std::size_t i = (static_cast<std::size_t>(y) * width_ + x) * 3;
  return {px_[i], px_[i + 1], px_[i + 2]};
}

void Canvas::set(int x, int y, Rgb8 c) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  const std::size_t i = (static_cast<std::size_t>(y) * width_ + x) * 3;
  px_[i] = c.r;
  px_[i + 1] = c.g;
  px_[i + 2] = c.b;
}

void Canvas::blend(int x, int y, Rgb8 c, double alpha) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  if (!(alpha > 0)) return;
  const double a = std::min(alpha, 1.0);
  const std::size_t i = (static_cast<std::size_t>(y) * width_ + x) * 3;
  // plain mix of the 8-bit sRGB values, rounded to nearest
  auto mix = [a](std::uint8_t under, std::uint8_t over) {
    return static_cast<std::uint8_t>(std::lround(under + (over - under) * a));
  };
  px_[i] = mix(px_[i], c.r);
  px_[i + 1] = mix(px_[i + 1], c.g);
  px_[i + 2] = mix(px_[i + 2], c.b);
}

void Canvas::line(Vec2 a, Vec2 b, Rgb8 c, double width, double alpha) {
  if (!finite(a) || !finite(b) || !(width > 0) || !(alpha > 0)) return;
  double hw = 0, opacity = 0;
  stroke_params(width, alpha, hw, opacity);
  stroke_segment(width_, height_, a, b, hw, [&](int x, int y, double cov) { blend(x, y, c, cov * opacity); });
}

void Canvas::polyline(const std::vector<Vec2>& pts, Rgb8 c, double width, bool closed, double alpha) {
  if (pts.empty() || !(width > 0) || !(alpha > 0)) return;
  if (!std::all_of(pts.begin(), pts.end(), finite)) return;
  double hw = 0, opacity = 0;
  stroke_params(width, alpha, hw, opacity);

  // coverage of the whole path is the maximum over its segments, blended once per pixel:
  // joins get no gaps (round joins) and no double-darkened overlaps
  Box2 box;
  for (const auto& p : pts) box.extend(p);
  const double reach = hw + 1.0;
  const int x0 = clamp_to_int(std::floor(box.min.x() - reach), 0, width_);
  const int x1 = clamp_to_int(std::ceil(box.max.x() + reach), 0, width_);
  const int y0 = clamp_to_int(std::floor(box.min.y() - reach), 0, height_);
  const int y1 = clamp_to_int(std::ceil(box.max.y() + reach), 0, height_);
  if (x0 >= x1 || y0 >= y1) return;
  const int mw = x1 - x0;
  std::vector<float> mask(static_cast<std::size_t>(mw) * static_cast<std::size_t>(y1 - y0), 0.0f);
  auto keep_max = [&](int x, int y, double cov) {
    float& m = mask[static_cast<std::size_t>(y - y0) * mw + (x - x0)];
    m = std::max(m, static_cast<float>(cov));
  };
  const std::size_t n = pts.size();
  if (n == 1) stroke_segment(width_, height_, pts[0], pts[0], hw, keep_max);
  for (std::size_t i = 0; i + 1 < n; ++i) stroke_segment(width_, height_, pts[i], pts[i + 1], hw, keep_max);
  if (closed && n > 2) stroke_segment(width_, height_, pts[n - 1], pts[0], hw, keep_max);

  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const float m = mask[static_cast<std::size_t>(y - y0) * mw + (x - x0)];
      if (m > 0) blend(x, y, c, m * opacity);
    }
  }
}

void Canvas::fill_polygon(const std::vector<Vec2>& pts, Rgb8 c, double alpha) {
  if (pts.size() < 3 || !(alpha > 0)) return;
  if (!std::all_of(pts.begin(), pts.end(), finite)) return;
  Box2 box;
  for (const auto& p : pts) box.extend(p);
  const int y0 = clamp_to_int(std::floor(box.min.y()), 0, height_);
  const int y1 = clamp_to_int(std::ceil(box.max.y()), 0, height_);
  const int x0 = clamp_to_int(std::floor(box.min.x()), 0, width_);
  const int x1 = clamp_to_int(std::ceil(box.max.x()), 0, width_);
  if (x0 >= x1 || y0 >= y1) return;

  // scanlines: four sub-rows per pixel row; on each, even-odd spans between sorted edge
  // crossings add their exact horizontal overlap with every pixel (so coverage is exact
  // in x and 4x supersampled in y)
  constexpr int kSub = 4;
  constexpr double kRowWeight = 1.0 / kSub;
  std::vector<double> acc(static_cast<std::size_t>(x1 - x0) + 1, 0.0);
  std::vector<double> xs;
  const std::size_t n = pts.size();
  for (int y = y0; y < y1; ++y) {
    std::fill(acc.begin(), acc.end(), 0.0);
    bool any = false;
    for (int s = 0; s < kSub; ++s) {
      const double ys = y + (s + 0.5) / kSub;
      xs.clear();
      for (std::size_t i = 0; i < n; ++i) {
        const Vec2& p = pts[i];
        const Vec2& q = pts[(i + 1) % n];
        // half-open rule: a vertex on the sub-row counts for exactly one of its edges
        if ((p.y() <= ys) == (q.y() <= ys)) continue;
        xs.push_back(p.x() + (ys - p.y()) * (q.x() - p.x()) / (q.y() - p.y()));
      }
      std::sort(xs.begin(), xs.end());
      for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
        const double a = std::clamp(xs[k], double(x0), double(x1));
        const double b = std::clamp(xs[k + 1], double(x0), double(x1));
        if (b <= a) continue;
        any = true;
        const int ia = static_cast<int>(std::floor(a)), ib = static_cast<int>(std::floor(b));
        if (ia == ib) {
          acc[ia - x0] += (b - a) * kRowWeight;
          continue;
        }
        acc[ia - x0] += (ia + 1 - a) * kRowWeight;
        for (int i = ia + 1; i < ib; ++i) acc[i - x0] += kRowWeight;
        if (ib < x1) acc[ib - x0] += (b - ib) * kRowWeight;
      }
    }
    if (!any) continue;
    for (int x = x0; x < x1; ++x) {
      const double cov = clamp01(acc[x - x0]);
      if (cov > 0) blend(x, y, c, cov * clamp01(alpha));
    }
  }
}

void Canvas::fill_circle(Vec2 centre, double radius, Rgb8 c, double alpha) {
  if (!finite(centre) || !(radius > 0) || !std::isfinite(radius) || !(alpha > 0)) return;
  // discs smaller than a pixel are drawn at half a pixel radius with their area's weight
  double r = radius, opacity = clamp01(alpha);
  if (r < 0.5) {
    opacity *= (r / 0.5) * (r / 0.5);
    r = 0.5;
  }
  // coverage from the distance to the centre: a one-pixel ramp across the rim
  const double reach = r + 0.5;
  const int y0 = clamp_to_int(std::floor(centre.y() - reach), 0, height_);
  const int y1 = clamp_to_int(std::ceil(centre.y() + reach), 0, height_);
  for (int y = y0; y < y1; ++y) {
    const Span s = disc_slice(centre, reach, y + 0.5);
    if (s.empty()) continue;
    const int x0 = clamp_to_int(std::floor(s.lo - 0.5), 0, width_);
    const int x1 = clamp_to_int(std::ceil(s.hi + 0.5), 0, width_);
    for (int x = x0; x < x1; ++x) {
      const double d = (Vec2(x + 0.5, y + 0.5) - centre).norm();
      const double cov = clamp01(reach - d);
      if (cov > 0) blend(x, y, c, cov * opacity);
    }
  }
}

void Canvas::circle(Vec2 centre, double radius, Rgb8 c, double width, double alpha) {
  if (!finite(centre) || !(radius >= 0) || !std::isfinite(radius) || !(width > 0) || !(alpha > 0)) return;
  double hw = 0, opacity = 0;
  stroke_params(width, alpha, hw, opacity);
  // a ring: coverage from the distance to the circle, |d - r|; each row visits the outer
  // disc's slice minus the inner disc where coverage is zero
  const double outer = radius + hw + 0.5, inner = radius - hw - 0.5;
  const int y0 = clamp_to_int(std::floor(centre.y() - outer), 0, height_);
  const int y1 = clamp_to_int(std::ceil(centre.y() + outer), 0, height_);
  for (int y = y0; y < y1; ++y) {
    const double yc = y + 0.5;
    const Span s = disc_slice(centre, outer, yc);
    if (s.empty()) continue;
    const Span hole = inner > 0 ? disc_slice(centre, inner, yc) : Span{};
    const int x0 = clamp_to_int(std::floor(s.lo - 0.5), 0, width_);
    const int x1 = clamp_to_int(std::ceil(s.hi + 0.5), 0, width_);
    // pixels whose centres lie inside the hole: [h0, h1)
    const int h0 = hole.empty() ? x1 : clamp_to_int(std::ceil(hole.lo - 0.5), x0, x1);
    const int h1 = hole.empty() ? x1 : clamp_to_int(std::floor(hole.hi - 0.5) + 1, h0, x1);
    auto run = [&](int from, int to) {
      for (int x = from; x < to; ++x) {
        const double d = (Vec2(x + 0.5, yc) - centre).norm();
        const double cov = clamp01(hw + 0.5 - std::abs(d - radius));
        if (cov > 0) blend(x, y, c, cov * opacity);
      }
    };
    run(x0, h0);
    run(h1, x1);
  }
}

void Canvas::fill_rect(int x0, int y0, int x1, int y1, Rgb8 c) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, width_);
  y1 = std::min(y1, height_);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) set(x, y, c);
  }
}

void Canvas::paste(const Canvas& other, int x, int y) {
  // the overlap of the two images, in this canvas's coordinates
  const long long lx0 = std::max<long long>(x, 0), ly0 = std::max<long long>(y, 0);
  const long long lx1 = std::min<long long>(static_cast<long long>(x) + other.width_, width_);
  const long long ly1 = std::min<long long>(static_cast<long long>(y) + other.height_, height_);
  if (lx0 >= lx1 || ly0 >= ly1) return;
  const std::size_t run = static_cast<std::size_t>(lx1 - lx0) * 3;
  for (long long row = ly0; row < ly1; ++row) {
    const std::size_t src = (static_cast<std::size_t>(row - y) * other.width_ + static_cast<std::size_t>(lx0 - x)) * 3;
    const std::size_t dst = (static_cast<std::size_t>(row) * width_ + static_cast<std::size_t>(lx0)) * 3;
    std::copy_n(other.px_.begin() + static_cast<std::ptrdiff_t>(src), run, px_.begin() + static_cast<std::ptrdiff_t>(dst));
  }
}

// plot frame: sizes round up so the whole region fits; the small tolerance keeps exact
// products (10 m x 50 px/m) from gaining a pixel to floating-point noise
namespace {
int round_up_px(double v) {
  if (!(v > 0)) return 0;
  return static_cast<int>(std::ceil(std::min(v, 1e9) - 1e-6));
}
}  // namespace

int PlotFrame::width() const { return round_up_px(world.size().x() * px_per_m) + 2 * margin; }

int PlotFrame::height() const { return round_up_px(world.size().y() * px_per_m) + 2 * margin; }

Vec2 PlotFrame::to_px(const Vec2& p_W) const {
  // x grows east as in the world; y is flipped so north is up
  return {margin + (p_W.x() - world.min.x()) * px_per_m, margin + (world.max.y() - p_W.y()) * px_per_m};
}

double nice_step(double span, int max_ticks) {
  const double raw = span / std::max(1, max_ticks);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * p >= raw) return m * p;
  }
  return 10 * p;
}

}  // namespace rescuesim
