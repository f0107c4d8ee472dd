#include "world/media.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace rescuesim {

const char* MediumSpec::kind_name(Kind kind) {
  switch (kind) {
    case Kind::smoke: return "smoke";
    case Kind::dust: return "dust";
  }
  return "?";
}

double band_ratio(MediumSpec::Kind kind, SensingBand band) {
  const bool smoke = kind == MediumSpec::Kind::smoke;
  switch (band) {
    case SensingBand::visible: return 1.0;
    // 905 nm. Dust grains (1-100 um) are much larger than either wavelength, so their extinction
    // efficiency is near its large-particle limit of 2 in both bands: the same coefficient. Soot
    // aggregates (under 1 um) extinguish roughly as 1/wavelength, which would give (550/905) ~ 0.6;
    // we keep 1 (the lidar sees no further than the eye), a deliberate upper bound: real smoke
    // also carries larger droplets and ash, and a lidar's detection threshold is not the eye's.
    case SensingBand::near_infrared: return 1.0;
    // 8-14 um (take 10 um). Soot is far smaller than the wavelength (Rayleigh regime): it
    // scatters almost nothing and absorbs roughly as 1/wavelength, (0.55 / 10) ~ 0.055, so 0.05;
    // this is why thermal cameras see through fire smoke. Coarse dust (size parameter pi*D/lambda
    // still above ~3 for D > 10 um) keeps much of its extinction; the fine fraction falls away:
    // 0.7.
    case SensingBand::long_wave_infrared: return smoke ? 0.05 : 0.7;
    // 40 kHz: the wavelength (8.6 mm) dwarfs every particle, so scattering (as (ka)^4) is nil.
    // What remains is the viscous and thermal drag of the particles on the air (Epstein-Carhart),
    // which grows with the mass loaded into the air: negligible for smoke (we take 0: sonar does
    // not feel smoke), small for heavy dust (0.01: 1/m of visible dust costs a sonar 1 % per m).
    case SensingBand::ultrasound: return smoke ? 0.0 : 0.01;
  }
  return 1.0;
}

double extinction(const MediumSpec& medium, SensingBand band) { return medium.density * band_ratio(medium.kind, band); }

double visibility(double sigma) { return sigma > 0 ? 3.0 / sigma : std::numeric_limits<double>::infinity(); }

double medium_echo_probability(SensingBand band) {
  switch (band) {
    case SensingBand::visible:
    case SensingBand::near_infrared: return 0.5;
    case SensingBand::long_wave_infrared:
    case SensingBand::ultrasound: return 0.0;
  }
  return 0.0;
}

double scattering_albedo(MediumSpec::Kind kind) {
  // Flaming-combustion smoke: soot aggregates absorb most of what they extinguish (measured
  // single-scattering albedos of soot-laden smoke lie around 0.2-0.4). Mineral dust scatters
  // most of it (0.85-0.95 in visible light).
  return kind == MediumSpec::Kind::smoke ? 0.3 : 0.9;
}

Polygon2 medium_outline(const MediumSpec& medium, double t) {
  const Polygon2& p = medium.outline;
  const std::size_t n = p.size();
  const double out = medium.growth * t;
  const Vec2 shift = medium.drift * t;
  Polygon2 q(n);
  for (std::size_t i = 0; i < n; ++i) {
    Vec2 v = p[i];
    if (out != 0 && n >= 3) {
      // the two edges meeting at v, each moved out along its outward normal; the corner is where
      // the moved edges meet: v + out * (n1 + n2) / (1 + n1 . n2)
      const Vec2 d1 = (p[i] - p[(i + n - 1) % n]).normalized(), d2 = (p[(i + 1) % n] - p[i]).normalized();
      const Vec2 n1(d1.y(), -d1.x()), n2(d2.y(), -d2.x());
      const double c = 1.0 + n1.dot(n2);
      if (c > 1e-9) v += out * (n1 + n2) / c;
    }
    q[i] = v + shift;
  }
  return q;
}

void media_at(std::span<const MediumSpec> media, double t, SensingBand band, std::vector<MediumVolume>& out) {
  out.clear();
  for (const MediumSpec& m : media) {
    const double sigma = extinction(m, band);
    if (!(sigma > 0)) continue;
    MediumVolume v;
    v.outline = medium_outline(m, t);
    v.bottom = m.bottom;
    v.top = m.bottom + m.height;
    v.sigma = sigma;
    const Box2 b = bounds(v.outline);
    v.box_min = {b.min.x(), b.min.y(), v.bottom};
    v.box_max = {b.max.x(), b.max.y(), v.top};
    out.push_back(std::move(v));
  }
}

namespace {

/// Narrows [lo, hi] to the ray parameters inside the slab a <= origin + s d <= b along one axis,
/// with inv = 1 / d; false when it misses.
bool clip_slab(double o, double d, double inv, double a, double b, double& lo, double& hi) {
  if (std::abs(d) < 1e-15) return o >= a && o <= b;
  double s0 = (a - o) * inv, s1 = (b - o) * inv;
  if (s0 > s1) std::swap(s0, s1);
  lo = std::max(lo, s0);
  hi = std::min(hi, s1);
  return lo <= hi;
}

/// Narrows [lo, hi] (from 0 and the segment's length) to the volume's bounding box.
bool clip_box(const MediumVolume& v, const Vec3& origin, const Vec3& direction, const Vec3& inv, double& lo, double& hi) {
  for (int k = 0; k < 3; ++k) {
    if (!clip_slab(origin[k], direction[k], inv[k], v.box_min[k], v.box_max[k], lo, hi)) return false;
  }
  return lo < hi;
}

/// Crossings of footprints with more than 32 of them, per thread.
std::vector<double>& overflow_crossings() {
  thread_local std::vector<double> v;
  return v;
}

/// The stretches of [lo, hi] (already inside the volume's box, so between its bottom and top)
/// where the ray is over the footprint, appended to `out`.
void footprint_spans(const MediumVolume& v, const Vec3& origin, const Vec3& direction, double lo, double hi,
                     std::vector<MediumSegment>& out) {
  // a vertical ray is over the footprint everywhere or nowhere
  const double ox = origin.x(), oy = origin.y(), dx = direction.x(), dy = direction.y();
  if (dx * dx + dy * dy < 1e-24) {
    if (contains(v.outline, Vec2(ox, oy), 0.0)) out.push_back({lo, hi, v.sigma});
    return;
  }

  // where the ray's line crosses the footprint's edges, an edge counting when its ends lie on
  // opposite sides of the line (one end on the line counts as the positive side, so a line through
  // a vertex crosses once and the crossings pair up); between the 1st and 2nd, 3rd and 4th, ... the
  // line is inside. The crossing of edge a->b is at s = ((a - o) x e) / (d x e), e = b - a. Up to
  // 32 crossings stay on the stack (a convex footprint has 2), sorted by insertion.
  constexpr std::size_t kInline = 32;
  double inline_cross[kInline];
  std::vector<double>* many = nullptr;
  double* cross = inline_cross;
  std::size_t count = 0;
  const std::size_t n = v.outline.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& pa = v.outline[i];
    const Vec2& pb = v.outline[i + 1 == n ? 0 : i + 1];
    const double ax = pa.x() - ox, ay = pa.y() - oy, bx = pb.x() - ox, by = pb.y() - oy;
    const double ya = dx * ay - dy * ax, yb = dx * by - dy * bx;
    if ((ya > 0) == (yb > 0)) continue;
    const double ex = bx - ax, ey = by - ay;
    const double s = (ax * ey - ay * ex) / (dx * ey - dy * ex);
    if (count == kInline && !many) {
      many = &overflow_crossings();
      many->assign(inline_cross, inline_cross + kInline);
    }
    if (!many) {
      std::size_t j = count;
      for (; j > 0 && cross[j - 1] > s; --j) cross[j] = cross[j - 1];
      cross[j] = s;
    } else {
      many->push_back(s);
    }
    ++count;
  }
  if (many) {
    std::sort(many->begin(), many->end());
    cross = many->data();
  }
  for (std::size_t k = 0; k + 1 < count; k += 2) {
    const double enter = std::max(lo, cross[k]), leave = std::min(hi, cross[k + 1]);
    if (enter < leave) out.push_back({enter, leave, v.sigma});
  }
}

Vec3 inverse(const Vec3& d) { return {1.0 / d.x(), 1.0 / d.y(), 1.0 / d.z()}; }

}  // namespace

bool segment_meets_box(const MediumVolume& v, const Vec3& origin, const Vec3& direction, double length) {
  double lo = 0, hi = length;
  return clip_box(v, origin, direction, inverse(direction), lo, hi);
}

void ray_in_volume(const MediumVolume& v, const Vec3& origin, const Vec3& direction, double length,
                   std::vector<MediumSegment>& out) {
  double lo = 0, hi = length;
  if (clip_box(v, origin, direction, inverse(direction), lo, hi)) footprint_spans(v, origin, direction, lo, hi, out);
}

double optical_depth(std::span<const MediumVolume> volumes, const Vec3& origin, const Vec3& direction, double length,
                     std::vector<MediumSegment>& segments) {
  segments.clear();
  const Vec3 inv = inverse(direction);
  for (const MediumVolume& v : volumes) {
    double lo = 0, hi = length;
    if (clip_box(v, origin, direction, inv, lo, hi)) footprint_spans(v, origin, direction, lo, hi, segments);
  }
  double tau = 0;
  for (const MediumSegment& s : segments) tau += s.sigma * (s.leave - s.enter);
  return tau;
}

double distance_at_depth(std::span<const MediumSegment> segments, double tau) {
  if (segments.size() == 1) {
    const MediumSegment& s = segments[0];
    const double inside = tau / s.sigma;
    return inside <= s.leave - s.enter ? s.enter + inside : std::numeric_limits<double>::infinity();
  }
  // overlapping stretches add: walk the ends in order with the sigma in force between them
  thread_local std::vector<std::pair<double, double>> ends;
  ends.clear();
  for (const MediumSegment& s : segments) {
    ends.emplace_back(s.enter, s.sigma);
    ends.emplace_back(s.leave, -s.sigma);
  }
  std::sort(ends.begin(), ends.end());
  double sigma = 0, at = 0, depth = 0;
  for (const auto& [x, ds] : ends) {
    if (sigma > 0 && depth + sigma * (x - at) >= tau) return at + (tau - depth) / sigma;
    depth += sigma * (x - at);
    at = x;
    sigma += ds;
    if (sigma < 1e-12) sigma = 0;
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace rescuesim
