#include "autonomy/slip_detector.h"

#include <algorithm>
#include <cmath>

namespace rescuesim::autonomy {

namespace {

bool is_return(const msg::LaserScan& s, float r) { return r >= s.range_min && r < s.range_max; }

// error (m, capped at 1) of a predicted range against a scan's beam: 1 for no return
double misfit(const msg::LaserScan& s, std::size_t beam, double predicted) {
  const float r = s.ranges[beam];
  return is_return(s, r) ? std::min(1.0, std::abs(static_cast<double>(r) - predicted)) : 1.0;
}

}  // namespace

SlipDetector::SlipDetector(SlipDetectorConfig config) : config_(config) {}

bool SlipDetector::add(const msg::LaserScan& scan, const Pose2& X_OS) {
  const bool same_setup = have_reference_ && scan.ranges.size() == reference_.ranges.size() &&
                          scan.angle_min == reference_.angle_min && scan.angle_increment == reference_.angle_increment;
  if (!same_setup || scan.ranges.empty() || !(scan.angle_increment != 0)) {
    reference_ = scan;
    X_OS_reference_ = X_OS;
    have_reference_ = true;
    return false;
  }

  // wait until odometry claims a motion worth checking
  const Pose2 X_RS = X_OS_reference_.inverse() * X_OS;  // this sensor pose in the reference's frame
  if (X_RS.position().norm() < config_.min_motion && std::abs(X_RS.yaw) < config_.min_turn) return false;

  // fit each reference return to this scan: moved as odometry says, and unmoved
  const Pose2 X_SR = X_RS.inverse();
  const std::size_t n = scan.ranges.size();
  const double per_turn = std::round(2 * M_PI / std::abs(scan.angle_increment));
  double moved = 0, still = 0;
  int count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const float r = reference_.ranges[i];
    if (!is_return(reference_, r)) continue;
    const double a = static_cast<double>(reference_.angle_min) + static_cast<double>(i) * reference_.angle_increment;
    const Vec2 p_S = X_SR.transform(Vec2(r * std::cos(a), r * std::sin(a)));
    // the beam of this scan looking at it (its fan may wrap round the full circle)
    double offset = std::atan2(p_S.y(), p_S.x()) - scan.angle_min;
    offset -= 2 * M_PI * std::floor(offset / (2 * M_PI));
    double beam = std::round(offset / scan.angle_increment);
    if (beam >= per_turn - 0.5) beam -= per_turn;
    if (!(beam >= 0 && beam < static_cast<double>(n))) continue;  // outside this scan's fan
    moved += misfit(scan, static_cast<std::size_t>(beam), p_S.norm());
    still += misfit(scan, i, r);
    ++count;
  }
  moved_error_ = count > 0 ? moved / count : 0.0;
  still_error_ = count > 0 ? still / count : 0.0;

  // remember the verdict; this scan is the next reference
  record(count > 0 && moved_error_ > config_.moved_misfit);
  reference_ = scan;
  X_OS_reference_ = X_OS;
  return true;
}

bool SlipDetector::add_motion(const Pose2& X_OB, const Pose2& X_MB) {
  if (!have_reference_) {
    X_OB_reference_ = X_OB;
    X_MB_reference_ = X_MB;
    have_reference_ = true;
    return false;
  }
  // wait until odometry claims a motion worth checking, then compare it with the matched one
  const Pose2 odom = X_OB_reference_.inverse() * X_OB;
  if (odom.position().norm() < config_.min_motion && std::abs(odom.yaw) < config_.min_turn) return false;
  const Pose2 matched = X_MB_reference_.inverse() * X_MB;
  moved_error_ = (odom.position() - matched.position()).norm();
  still_error_ = matched.position().norm();
  record(moved_error_ > config_.moved_misfit || std::abs(wrap_angle(odom.yaw - matched.yaw)) > 0.5 * config_.min_turn);
  X_OB_reference_ = X_OB;
  X_MB_reference_ = X_MB;
  return true;
}

void SlipDetector::record(bool misfit) {
  history_.push_back(misfit);
  while (static_cast<int>(history_.size()) > std::max(config_.window, 1)) history_.pop_front();
}

bool SlipDetector::slipping() const {
  return std::count(history_.begin(), history_.end(), true) >= std::max(config_.min_misfits, 1);
}

void SlipDetector::reset() {
  have_reference_ = false;
  history_.clear();
}

}  // namespace rescuesim::autonomy
