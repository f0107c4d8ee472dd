#include "core/throttle.h"

#include <gtest/gtest.h>

namespace rescuesim {
namespace {

using namespace std::chrono_literals;

TEST(Throttle, LetsOneThroughPerPeriodAndCountsTheRest) {
  Throttle t(2s);
  const Throttle::Clock::time_point t0{};
  std::uint64_t held = 99;
  EXPECT_TRUE(t.allow_at(t0, &held));
  EXPECT_EQ(held, 0u);
  // three more within the 2 s are held back
  EXPECT_FALSE(t.allow_at(t0 + 500ms));
  EXPECT_FALSE(t.allow_at(t0 + 1s));
  EXPECT_FALSE(t.allow_at(t0 + 1999ms));
  // at 2 s the next goes through and reports the three
  EXPECT_TRUE(t.allow_at(t0 + 2s, &held));
  EXPECT_EQ(held, 3u);
  // the count starts again: one held between 2 s and 4 s
  EXPECT_FALSE(t.allow_at(t0 + 3s));
  EXPECT_TRUE(t.allow_at(t0 + 4s, &held));
  EXPECT_EQ(held, 1u);
}

TEST(Throttle, ThePeriodRunsFromTheLastOneLetThrough) {
  Throttle t(1s);
  const Throttle::Clock::time_point t0{};
  std::uint64_t held = 0;
  EXPECT_TRUE(t.allow_at(t0));
  EXPECT_TRUE(t.allow_at(t0 + 1500ms));
  // 2 s is only 0.5 s after the last one let through
  EXPECT_FALSE(t.allow_at(t0 + 2s));
  EXPECT_TRUE(t.allow_at(t0 + 2500ms, &held));
  EXPECT_EQ(held, 1u);
}

}  // namespace
}  // namespace rescuesim
