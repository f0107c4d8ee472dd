#include "autonomy/wall_follower.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rescuesim::autonomy {

namespace {
constexpr double kDeg = M_PI / 180.0;
}  // namespace

WallFollower::WallFollower(WallFollowerConfig config) : config_(std::move(config)) {}

void WallFollower::reset() {
  seen_wall_ = false;
  state_ = WallFollowerState::no_data;
}

msg::Twist WallFollower::command(const msg::LaserScan& scan) {
  if (scan.ranges.empty()) {
    state_ = WallFollowerState::no_data;
    return {};
  }
  return command(scan_points_in_base(scan, config_.X_BS), scan.header.stamp);
}

msg::Twist WallFollower::command(const std::vector<ScanPoint>& points_B, SimTime stamp) {
  const double s = config_.side == WallSide::left ? 1.0 : -1.0;  // sign of the wall side
  const double w_max = config_.max_angular;
  msg::Twist twist;

  // what is ahead, the nearest return on the wall side (bearings 10..170 degrees), and the
  // nearest return diagonally ahead on that side (40..50 degrees)
  front_distance_ = free_distance_ahead(points_B, config_.robot_radius);
  wall_distance_ = std::numeric_limits<double>::infinity();
  double wall_bearing = s * M_PI / 2;
  double diagonal = std::numeric_limits<double>::infinity();
  for (const ScanPoint& p : points_B) {
    const double side_bearing = s * p.bearing_B;
    if (side_bearing >= 40 * kDeg && side_bearing <= 50 * kDeg) diagonal = std::min(diagonal, p.distance_B);
    if (side_bearing < 10 * kDeg || side_bearing > 170 * kDeg || p.distance_B >= wall_distance_) continue;
    wall_distance_ = p.distance_B;
    wall_bearing = p.bearing_B;
  }

  // too close ahead: turn away from the wall side on the spot
  if (front_distance_ <= config_.stop_distance) {
    state_ = WallFollowerState::blocked;
    twist.angular.z() = -s * 0.8 * w_max;
    return twist;
  }

  // steer along the wall: face parallel to it (nearest return abeam) and hold the distance;
  // where it ends (nothing diagonally ahead where a straight wall would be, nearest return
  // abeam or behind) circle its end slowly; just after losing it, arc toward its side; long
  // after, drive straight to find another
  double turn = 0;
  double speed = config_.max_linear;
  const double corner_speed = 0.5 * config_.max_linear;
  bool rounding_end = false;
  if (wall_distance_ <= config_.wall_lost_distance) {
    seen_wall_ = true;
    last_wall_seen_ = stamp;
    const double heading_error = wall_bearing - s * M_PI / 2;
    const double distance_error =
        std::clamp(wall_distance_ - config_.target_distance, -config_.max_distance_error, config_.max_distance_error);
    turn = config_.angle_gain * heading_error + s * config_.distance_gain * distance_error;
    rounding_end = diagonal > 2 * wall_distance_ + 0.3 && s * wall_bearing >= 75 * kDeg;
    if (rounding_end) {
      speed = corner_speed;
      turn += s * speed / std::max(config_.target_distance, 0.1);
    }
    state_ = rounding_end ? WallFollowerState::turning_corner : WallFollowerState::following;
  } else if (seen_wall_ && (stamp - last_wall_seen_).seconds() < config_.corner_memory) {
    speed = corner_speed;
    turn = s * speed / std::max(config_.target_distance, 0.1);
    state_ = WallFollowerState::turning_corner;
  } else {
    state_ = WallFollowerState::seeking;
  }

  // something ahead on the way it is turning to (where the heading will be in a moment):
  // blend toward turning away from the wall side, and slow down
  const double look = std::clamp(turn * config_.look_ahead_time, -M_PI / 2, M_PI / 2);
  const double way = free_distance_along(points_B, look, config_.robot_radius, config_.front_margin);
  const double span = std::max(config_.slow_distance - config_.stop_distance, 1e-6);
  double ahead = std::clamp((config_.slow_distance - way) / span, 0.0, 1.0);
  if (rounding_end) ahead = 0;  // circling the wall's end turns away from what is ahead already
  if (ahead > 0) {
    turn = (1 - ahead) * turn - ahead * s * w_max;
    state_ = WallFollowerState::avoiding;
  }
  turn = std::clamp(turn, -w_max, w_max);
  speed *= (1 - ahead) * std::max(0.25, 1 - 0.6 * std::abs(turn) / w_max);
  twist.linear.x() = std::clamp(speed, 0.0, config_.max_linear);
  twist.angular.z() = turn;
  return twist;
}

}  // namespace rescuesim::autonomy
