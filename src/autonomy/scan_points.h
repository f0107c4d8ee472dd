#pragma once
/// Laser returns as points in the robot's base frame, the shared first step of the reactive
/// controllers.

#include <vector>

#include "core/pose.h"
#include "msgs/messages.h"

namespace rescuesim::autonomy {

/// One laser return placed in the base_link frame.
struct ScanPoint {
  Vec2 p_B;               ///< m, base_link frame (x forward, y left)
  double bearing_B = 0;   ///< rad, atan2 of p_B: 0 ahead, > 0 to the left
  double distance_B = 0;  ///< m, |p_B|
  bool too_close = false; ///< the beam read -inf (closer than range_min) and was placed at range_min
  int beam = 0;           ///< the beam's index in the scan: neighbours differ by 1
};

/// The returns of `scan` in base_link, given the laser's mounting pose `X_BS` (laser frame
/// in base_link). REP-117: -inf (something closer than the laser can measure) becomes a point
/// at range_min; +inf and finite ranges at or beyond range_max (no return), NaN and finite
/// ranges below range_min (invalid) are dropped.
std::vector<ScanPoint> scan_points_in_base(const msg::LaserScan& scan, const Pose2& X_BS);

/// How far (m) the robot, a disc of radius `radius` centred on the base origin, can travel
/// straight ahead (along base x) before it comes within `margin` of a return: over the
/// returns ahead with |y| < radius + margin, the least x - sqrt((radius + margin)^2 - y^2),
/// +inf when nothing is in the way, 0 when something is already that close in front.
/// Returns beside the robot (|y| >= radius) that are already within the margin do not count:
/// driving on takes the robot past them, not into them.
double free_distance_ahead(const std::vector<ScanPoint>& points, double radius, double margin = 0.0);

/// The same along the base_link direction `heading` (rad, 0 = ahead, > 0 = left).
double free_distance_along(const std::vector<ScanPoint>& points, double heading, double radius, double margin = 0.0);

/// Thin things standing alone in a scan, such as a post or another robot's mast: runs of
/// neighbouring beams whose returns lie within `link` (m) of each other, at least two and
/// spanning at most `max_width` (m) end to end, whose neighbouring beams on both sides return
/// nothing or return at least `min_gap` (m) farther from the laser at `laser_B`. The centre of
/// each run's returns (base_link).
std::vector<Vec2> thin_returns(const std::vector<ScanPoint>& points, const Vec2& laser_B, double max_width, double min_gap,
                               double link = 0.05);

}  // namespace rescuesim::autonomy
