// The process clock reads the kernel's start time of this process: positive, and it never runs
// backwards.

#include "core/process_clock.h"

#include <gtest/gtest.h>

namespace rescuesim {
namespace {

TEST(ProcessClock, CountsFromThisProcessesStartAndNeverRunsBackwards) {
  const double a = seconds_since_process_start();
  // the test binary has been loaded and started: at least one clock tick ago or exactly now
  EXPECT_GE(a, 0.0);
  // and it started on this boot, within the time the machine has been up (/proc/uptime)
  EXPECT_LT(a, 1e8);
  double b = a;
  for (int k = 0; k < 1000; ++k) b = seconds_since_process_start();
  EXPECT_GE(b, a);
}

}  // namespace
}  // namespace rescuesim
