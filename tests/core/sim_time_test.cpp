#include "core/sim_time.h"

#include <gtest/gtest.h>

namespace rescuesim {
namespace {

TEST(SimTime, ThousandMillisecondStepsAreExactlyOneSecond) {
  SimTime t;
  for (int i = 0; i < 1000; ++i) t += SimTime::from_ms(1);
  EXPECT_EQ(t.ns, 1'000'000'000);
  EXPECT_EQ(t.sec_part(), 1);
  EXPECT_EQ(t.nsec_part(), 0u);
}

TEST(SimTime, FromSecondsRoundsToNearestNanosecond) {
  EXPECT_EQ(SimTime::from_seconds(0.001).ns, 1'000'000);
  EXPECT_EQ(SimTime::from_seconds(1.0 / 240.0).ns, 4'166'667);
  EXPECT_EQ(SimTime::from_seconds(-0.5).ns, -500'000'000);
}

TEST(SimTime, SplitsIntoRosSecondsAndNanoseconds) {
  const SimTime t{12'345'678'901};
  EXPECT_EQ(t.sec_part(), 12);
  EXPECT_EQ(t.nsec_part(), 345'678'901u);
  EXPECT_DOUBLE_EQ(t.seconds(), 12.345678901);
}

}  // namespace
}  // namespace rescuesim
