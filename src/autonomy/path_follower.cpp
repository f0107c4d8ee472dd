#include "autonomy/path_follower.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rescuesim::autonomy {

PathFollower::PathFollower(PathFollowerConfig config) : config_(std::move(config)) {}

void PathFollower::set_path(std::vector<Vec2> path_O, SimTime now) {
  path_ = std::move(path_O);
  arc_.assign(path_.size(), 0.0);
  for (std::size_t i = 1; i < path_.size(); ++i) arc_[i] = arc_[i - 1] + (path_[i] - path_[i - 1]).norm();
  progress_ = 0;
  best_remaining_ = std::numeric_limits<double>::infinity();
  best_time_ = now;
  status_ = path_.empty() ? PathStatus::idle : PathStatus::following;
}

void PathFollower::clear() { set_path({}, SimTime{}); }

std::size_t PathFollower::next_index() const {
  return static_cast<std::size_t>(std::upper_bound(arc_.begin(), arc_.end(), progress_) - arc_.begin());
}

double PathFollower::remaining_length() const { return arc_.empty() ? 0 : arc_.back() - progress_; }

Vec2 PathFollower::point_at(double s) const {
  if (s <= 0 || path_.size() == 1) return path_.front();
  if (s >= arc_.back()) return path_.back();
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(arc_.begin(), arc_.end(), s) - arc_.begin());
  const double len = arc_[i] - arc_[i - 1];
  const double t = len > 0 ? (s - arc_[i - 1]) / len : 0.0;
  return path_[i - 1] + t * (path_[i] - path_[i - 1]);
}

msg::Twist PathFollower::command(const Pose2& X_OB, SimTime now) {
  msg::Twist twist;
  if (status_ != PathStatus::following) return twist;
  const Vec2 p = X_OB.position();

  // arrived?
  if ((p - path_.back()).norm() < config_.goal_tolerance) {
    status_ = PathStatus::reached;
    progress_ = arc_.back();
    return twist;
  }

  // advance the closest point, looking only a little way ahead of where it was
  double best_distance = std::numeric_limits<double>::infinity();
  double best_s = progress_;
  for (std::size_t i = 1; i < path_.size(); ++i) {
    if (arc_[i] < progress_) continue;
    if (arc_[i - 1] > progress_ + config_.search_window) break;
    const Vec2 a = path_[i - 1], ab = path_[i] - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double s = std::max(arc_[i - 1] + t * (arc_[i] - arc_[i - 1]), progress_);
    const double d = (p - point_at(s)).norm();
    if (d < best_distance) {
      best_distance = d;
      best_s = s;
    }
  }
  progress_ = best_s;
  if (path_.size() == 1) best_distance = (p - path_.front()).norm();

  // no progress (along the path, or toward it) for too long: stuck
  const double to_go = remaining_length() + best_distance;
  if (to_go < best_remaining_ - config_.stuck_progress) {
    best_remaining_ = to_go;
    best_time_ = now;
  } else if ((now - best_time_).seconds() > config_.stuck_time) {
    status_ = PathStatus::stuck;
    return twist;
  }

  // steer toward the lookahead point: on the spot when it is far off the nose, else on the
  // pure-pursuit arc through it
  const Vec2 target_B = X_OB.inverse().transform(point_at(progress_ + config_.lookahead));
  const double bearing = std::atan2(target_B.y(), target_B.x());
  if (std::abs(bearing) > config_.rotate_in_place_angle) {
    twist.angular.z() = std::clamp(config_.turn_gain * bearing, -config_.max_angular, config_.max_angular);
    return twist;
  }
  const double to_end = (path_.back() - p).norm();
  double v = config_.max_linear * (1 - 0.5 * std::abs(bearing) / config_.rotate_in_place_angle);
  v = std::min(v, std::max(0.1, 0.8 * to_end));
  const double curvature = 2 * std::sin(bearing) / std::max(target_B.norm(), 1e-6);
  double w = v * curvature;
  if (std::abs(w) > config_.max_angular) {
    v *= config_.max_angular / std::abs(w);
    w = std::clamp(w, -config_.max_angular, config_.max_angular);
  }
  twist.linear.x() = v;
  twist.angular.z() = w;
  return twist;
}

}  // namespace rescuesim::autonomy
