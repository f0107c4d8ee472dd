#pragma once
/// Delivery latency for `rescuesim bench` (ROS section): the wall-clock time at which the
/// simulation published a message on its Bus is joined with the time a subscriber in another
/// process received it, matched by topic and header stamp, and the delays are summarised.
/// Plain data and arithmetic, no ROS: the bench and its probe processes fill these in.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace rescuesim::bench {

/// One message seen at one end: its topic, header stamp (ns of sim time) and the wall clock
/// (CLOCK_REALTIME, ns) when it was published on the Bus or received by the subscriber.
struct StampedWallTime {
  std::string topic;
  std::int64_t stamp_ns = 0;
  std::int64_t wall_ns = 0;
};

/// The p-th percentile (p in 0..100) of `values`, interpolated linearly between the two nearest
/// ranks (numpy's default): rank (n - 1) * p / 100 of the sorted values. NaN when empty.
inline double percentile(std::vector<double> values, double p) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const double rank = (static_cast<double>(values.size()) - 1) * std::clamp(p, 0.0, 100.0) / 100.0;
  const auto lo = static_cast<std::size_t>(std::floor(rank));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (rank - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

/// Delays in ms (receipt minus publication) of the messages on `topic` that were both published
/// and received, in receipt order. Publications stamped before `warmup_ns` are left out (the
/// subscriber may still be connecting), and so are receipts with no publication to match; a
/// message received twice counts once, at its first receipt.
inline std::vector<double> join_latencies(const std::vector<StampedWallTime>& published, const std::vector<StampedWallTime>& received,
                                          const std::string& topic, std::int64_t warmup_ns = 0) {
  std::map<std::int64_t, std::int64_t> sent;  // stamp -> wall time of publication
  for (const auto& p : published) {
    if (p.topic == topic && p.stamp_ns >= warmup_ns) sent.emplace(p.stamp_ns, p.wall_ns);
  }
  std::vector<double> delays;
  for (const auto& r : received) {
    if (r.topic != topic) continue;
    const auto it = sent.find(r.stamp_ns);
    if (it == sent.end()) continue;
    delays.push_back(static_cast<double>(r.wall_ns - it->second) * 1e-6);
    sent.erase(it);
  }
  return delays;
}

/// What one topic's delivery looked like.
struct LatencySummary {
  std::size_t published = 0;  ///< messages published on the Bus after the warm-up
  std::size_t matched = 0;    ///< of those, received by the subscriber
  double median_ms = std::numeric_limits<double>::quiet_NaN();
  double p99_ms = std::numeric_limits<double>::quiet_NaN();
  double min_ms = std::numeric_limits<double>::quiet_NaN();
  double max_ms = std::numeric_limits<double>::quiet_NaN();
};

/// join_latencies, summarised.
inline LatencySummary summarize_latency(const std::vector<StampedWallTime>& published, const std::vector<StampedWallTime>& received,
                                        const std::string& topic, std::int64_t warmup_ns = 0) {
  LatencySummary s;
  for (const auto& p : published) s.published += p.topic == topic && p.stamp_ns >= warmup_ns;
  const std::vector<double> d = join_latencies(published, received, topic, warmup_ns);
  s.matched = d.size();
  if (d.empty()) return s;
  s.median_ms = percentile(d, 50);
  s.p99_ms = percentile(d, 99);
  s.min_ms = *std::min_element(d.begin(), d.end());
  s.max_ms = *std::max_element(d.begin(), d.end());
  return s;
}

}  // namespace rescuesim::bench
