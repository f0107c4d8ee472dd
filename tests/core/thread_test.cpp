// Thread names as the kernel keeps them (/proc/self/task/TID/comm), what top -H and perf show.

#include <gtest/gtest.h>
#include <pthread.h>

#include <string>
#include <thread>

#include "core/thread.h"

namespace rescuesim {
namespace {

std::string kernel_name_of_this_thread() {
  char buf[32] = {};
  pthread_getname_np(pthread_self(), buf, sizeof buf);
  return buf;
}

TEST(ThreadNames, AThreadCarriesItsNameAndALongNameIsCutTo15Characters) {
  std::string short_name, long_name;
  std::thread([&] {
    name_this_thread("ros2-send");
    short_name = kernel_name_of_this_thread();
    // 16 characters: Linux keeps 15 (16 with the NUL)
    name_this_thread("fox-serialise-01");
    long_name = kernel_name_of_this_thread();
  }).join();
  EXPECT_EQ(short_name, "ros2-send");
  EXPECT_EQ(long_name, "fox-serialise-0");
}

TEST(ThreadNames, AStartedNamedThreadRunsItsWorkUnderItsName) {
  std::string seen;
  int ran = 0;
  start_named_thread("mcap-write", [&] {
    seen = kernel_name_of_this_thread();
    ++ran;
  }).join();
  EXPECT_EQ(ran, 1);
  EXPECT_EQ(seen, "mcap-write");
}

}  // namespace
}  // namespace rescuesim
