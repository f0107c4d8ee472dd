#include "radio/wall_count.h"

#include <cmath>

#include "core/error.h"

namespace rescuesim {

namespace {

/// How far past a hit the next cast starts (m).
constexpr double kStepPast = 1e-3;
/// Casts per segment at most: a guard against a tracer that keeps hitting the same point.
constexpr int kMaxCastsPerSegment = 4096;

}  // namespace

WallCounter::WallCounter(const RayScene& scene, const World& world) : scene_(scene) {
  is_wall_.reserve(world.statics.size());
  for (const StaticObject& o : world.statics) {
    is_wall_.push_back(o.kind != ObjectKind::floor && o.kind != ObjectKind::victim);
  }
}

bool WallCounter::is_wall(int index) const {
  return index >= 0 && static_cast<std::size_t>(index) < is_wall_.size() && is_wall_[static_cast<std::size_t>(index)];
}

int WallCounter::count(const Vec3& p_W, const Vec3& q_W, int cap) const {
  const RadioSegment s{p_W, q_W};
  int n = 0;
  count(std::span<const RadioSegment>(&s, 1), std::span<int>(&n, 1), cap);
  return n;
}

void WallCounter::count(std::span<const RadioSegment> segments, std::span<int> counts, int cap) const {
  RS_DEMAND(segments.size() == counts.size(), "WallCounter::count: one count per segment");
  // per segment: where the next cast starts along it, the last wall counted, casts so far
  struct Walk {
    std::size_t segment = 0;
    double length = 0;
    Vec3 dir = Vec3::UnitX();
    double t = 0;
    int last_wall = -1;
    int casts = 0;
  };
  std::vector<Walk> active;
  active.reserve(segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i) {
    counts[i] = 0;
    const Vec3 d = segments[i].q_W - segments[i].p_W;
    const double length = d.norm();
    if (!std::isfinite(length) || length <= 0 || cap <= 0) continue;
    active.push_back({i, length, d / length});
  }

  // cast all unfinished walks as one batch, step past what they hit, repeat
  std::vector<Ray> rays;
  std::vector<RayHit> hits;
  while (!active.empty()) {
    rays.clear();
    for (const Walk& w : active) {
      const Vec3 origin = segments[w.segment].p_W + w.t * w.dir;
      rays.push_back({origin, w.dir, static_cast<float>(w.length - w.t)});
    }
    hits.assign(rays.size(), RayHit{});
    scene_.cast(rays, hits);

    std::size_t kept = 0;
    for (std::size_t k = 0; k < active.size(); ++k) {
      Walk w = active[k];
      const RayHit& h = hits[k];
      if (!h.hit()) continue;  // nothing more on this segment
      if (h.source == RayHit::Source::static_object && is_wall(h.index) && h.index != w.last_wall) {
        w.last_wall = h.index;
        ++counts[w.segment];
      }
      w.t += static_cast<double>(h.distance) + kStepPast;
      ++w.casts;
      if (w.t >= w.length || counts[w.segment] >= cap || w.casts >= kMaxCastsPerSegment) continue;
      active[kept++] = w;
    }
    active.resize(kept);
  }
}

}  // namespace rescuesim
