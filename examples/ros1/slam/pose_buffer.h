#pragma once
/// A short history of stamped planar poses (odometry, a TF edge) that answers "where was it at
/// time t", interpolating between samples, as a tf buffer would for one edge.

#include <algorithm>
#include <deque>
#include <iterator>
#include <optional>
#include <utility>

#include "pose2.h"

namespace slam_demo {

class PoseBuffer {
 public:
  /// Keeps samples for `span` seconds behind the newest one.
  explicit PoseBuffer(double span = 10.0) : span_(span) {}

  /// Adds a sample; out-of-order samples (older than the newest) are ignored.
  void add(double t, const Pose2& pose) {
    if (!samples_.empty() && t <= samples_.back().first) return;
    samples_.emplace_back(t, pose);
    while (samples_.size() > 2 && samples_.front().first < t - span_) samples_.pop_front();
  }

  bool empty() const { return samples_.empty(); }
  /// Stamp of the newest sample (s); only when not empty.
  double newest() const { return samples_.back().first; }

  /// The pose at t, interpolated; nothing when t is outside the stored span.
  std::optional<Pose2> at(double t) const {
    if (samples_.empty() || t < samples_.front().first || t > samples_.back().first) return std::nullopt;
    const auto it = first_at_or_after(t);
    if (it == samples_.begin()) return it->second;
    const auto& [t1, p1] = *it;
    const auto& [t0, p0] = *std::prev(it);
    return interpolate(p0, p1, t1 > t0 ? (t - t0) / (t1 - t0) : 1.0);
  }

  /// The newest sample stamped at or before t (a step function, like a TF edge that is only
  /// republished when it changes); nothing before the first one.
  std::optional<Pose2> latest_at(double t) const {
    auto it = std::upper_bound(samples_.begin(), samples_.end(), t, [](double v, const auto& s) { return v < s.first; });
    if (it == samples_.begin()) return std::nullopt;
    return std::prev(it)->second;
  }

 private:
  using Samples = std::deque<std::pair<double, Pose2>>;
  // the first sample stamped at or after t (binary search: samples are in time order)
  Samples::const_iterator first_at_or_after(double t) const {
    return std::lower_bound(samples_.begin(), samples_.end(), t, [](const auto& s, double v) { return s.first < v; });
  }

  double span_;
  Samples samples_;
};

}  // namespace slam_demo
