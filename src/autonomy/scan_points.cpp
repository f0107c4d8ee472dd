#include "autonomy/scan_points.h"

#include <cmath>
#include <limits>

namespace rescuesim::autonomy {

std::vector<ScanPoint> scan_points_in_base(const msg::LaserScan& scan, const Pose2& X_BS) {
  std::vector<ScanPoint> points;
  points.reserve(scan.ranges.size());
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    double r = scan.ranges[i];
    bool too_close = false;
    // keep real returns and "too close" readings; drop no-return (+inf, >= range_max) and
    // invalid ones (NaN, finite below range_min)
    if (r == -std::numeric_limits<double>::infinity()) {
      r = scan.range_min;
      too_close = true;
    } else if (!(r >= scan.range_min && r < scan.range_max)) {
      continue;
    }
    const double angle = static_cast<double>(scan.angle_min) + static_cast<double>(i) * scan.angle_increment;
    const Vec2 p_B = X_BS.transform(Vec2(r * std::cos(angle), r * std::sin(angle)));
    points.push_back({p_B, std::atan2(p_B.y(), p_B.x()), p_B.norm(), too_close, static_cast<int>(i)});
  }
  return points;
}

double free_distance_ahead(const std::vector<ScanPoint>& points, double radius, double margin) {
  return free_distance_along(points, 0.0, radius, margin);
}

double free_distance_along(const std::vector<ScanPoint>& points, double heading, double radius, double margin) {
  const Vec2 u(std::cos(heading), std::sin(heading));
  const double reach = radius + margin;
  double travel = std::numeric_limits<double>::infinity();
  for (const ScanPoint& s : points) {
    // coordinates along and across the direction of travel
    const double along = u.dot(s.p_B), across = std::abs(u.x() * s.p_B.y() - u.y() * s.p_B.x());
    if (along <= 0 || across >= reach) continue;
    const double t = along - std::sqrt(reach * reach - across * across);
    if (t < 0 && across >= radius) continue;  // beside, within the margin: passing it, not hitting it
    travel = std::min(travel, std::max(0.0, t));
  }
  return travel;
}

std::vector<Vec2> thin_returns(const std::vector<ScanPoint>& points, const Vec2& laser_B, double max_width, double min_gap,
                               double link) {
  std::vector<Vec2> out;
  const auto range = [&](std::size_t k) { return (points[k].p_B - laser_B).norm(); };
  // does the beam next to the run (index k, if it is the very next beam) stand well behind it?
  const auto behind = [&](std::size_t k, int beam, double r) {
    if (k >= points.size() || points[k].beam != beam) return true;  // no return there
    return range(k) >= r + min_gap;
  };
  std::size_t i = 0;
  while (i < points.size()) {
    std::size_t j = i;
    while (j + 1 < points.size() && points[j + 1].beam == points[j].beam + 1 && (points[j + 1].p_B - points[j].p_B).norm() <= link) ++j;
    const std::size_t first = i, last = j;
    i = j + 1;
    if (last == first || (points[last].p_B - points[first].p_B).norm() > max_width) continue;
    Vec2 sum = Vec2::Zero();
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t k = first; k <= last; ++k) {
      sum += points[k].p_B;
      nearest = std::min(nearest, range(k));
    }
    const bool before_ok = first == 0 || behind(first - 1, points[first].beam - 1, nearest);
    if (!before_ok || !behind(last + 1, points[last].beam + 1, nearest)) continue;
    out.push_back(sum / static_cast<double>(last - first + 1));
  }
  return out;
}

}  // namespace rescuesim::autonomy
