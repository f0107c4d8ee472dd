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
    points.push_back({p_B, std::atan2(p_B.y(), p_B.x()), p_B.norm(), too_close});
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

}  // namespace rescuesim::autonomy
