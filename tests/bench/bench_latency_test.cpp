// The latency arithmetic of `rescuesim bench` (ROS section) on lists small enough to check by hand.

#include "bench/bench_latency.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rescuesim::bench {
namespace {

TEST(BenchLatency, PercentileInterpolatesBetweenRanks) {
  // 1..100 in scrambled order: the median lies halfway between 50 and 51; p99 is at rank 98.01
  std::vector<double> v;
  for (int k = 100; k >= 1; --k) v.push_back(k);
  EXPECT_DOUBLE_EQ(percentile(v, 50), 50.5);
  EXPECT_DOUBLE_EQ(percentile(v, 99), 99.01);
  EXPECT_DOUBLE_EQ(percentile(v, 0), 1);
  EXPECT_DOUBLE_EQ(percentile(v, 100), 100);
  // odd count: the median is the middle value
  EXPECT_DOUBLE_EQ(percentile({3, 1, 2}, 50), 2);
  EXPECT_DOUBLE_EQ(percentile({7}, 99), 7);
  EXPECT_TRUE(std::isnan(percentile({}, 50)));
}

TEST(BenchLatency, JoinsReceiptsToPublicationsByTopicAndStamp) {
  const std::int64_t ms = 1'000'000;
  // three scans and two images published; stamps in sim time, wall times in ns
  const std::vector<StampedWallTime> published = {
      {"/scan", 100 * ms, 1000 * ms}, {"/scan", 200 * ms, 1100 * ms}, {"/scan", 300 * ms, 1200 * ms},
      {"/image", 100 * ms, 1010 * ms}, {"/image", 200 * ms, 1110 * ms}};
  const std::vector<StampedWallTime> received = {
      {"/scan", 100 * ms, 1002 * ms},   // 2 ms
      {"/image", 100 * ms, 1025 * ms},  // 15 ms (same stamp, other topic)
      {"/scan", 300 * ms, 1205 * ms},   // 5 ms (the 200 ms scan was lost)
      {"/scan", 300 * ms, 1300 * ms},   // a duplicate: only the first receipt counts
      {"/scan", 999 * ms, 1400 * ms},   // never published (e.g. before recording began)
      {"/image", 200 * ms, 1130 * ms}};  // 20 ms
  const std::vector<double> scan = join_latencies(published, received, "/scan");
  ASSERT_EQ(scan.size(), 2u);
  EXPECT_DOUBLE_EQ(scan[0], 2);
  EXPECT_DOUBLE_EQ(scan[1], 5);
  const std::vector<double> image = join_latencies(published, received, "/image");
  ASSERT_EQ(image.size(), 2u);
  EXPECT_DOUBLE_EQ(image[0], 15);
  EXPECT_DOUBLE_EQ(image[1], 20);

  // the warm-up leaves out publications stamped before it, and their receipts with them
  const LatencySummary s = summarize_latency(published, received, "/scan", 150 * ms);
  EXPECT_EQ(s.published, 2u);  // the 200 ms and 300 ms scans
  EXPECT_EQ(s.matched, 1u);    // only the 300 ms one arrived
  EXPECT_DOUBLE_EQ(s.median_ms, 5);
  EXPECT_DOUBLE_EQ(s.p99_ms, 5);

  const LatencySummary all = summarize_latency(published, received, "/scan");
  EXPECT_EQ(all.published, 3u);
  EXPECT_EQ(all.matched, 2u);
  EXPECT_DOUBLE_EQ(all.median_ms, 3.5);
  EXPECT_DOUBLE_EQ(all.p99_ms, 2 + 0.99 * 3);
  EXPECT_DOUBLE_EQ(all.min_ms, 2);
  EXPECT_DOUBLE_EQ(all.max_ms, 5);

  const LatencySummary none = summarize_latency(published, received, "/odom");
  EXPECT_EQ(none.matched, 0u);
  EXPECT_TRUE(std::isnan(none.median_ms));
}

}  // namespace
}  // namespace rescuesim::bench
