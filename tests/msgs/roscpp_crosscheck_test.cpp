// The ROS 1 bytes and MD5 sums against roscpp itself: Debian's generated message headers
// serialise the same samples (tests/msgs/roscpp_reference.cpp). Built only when those headers
// are installed; otherwise the test is skipped with the reason.

#include <gtest/gtest.h>

#include "msgs/serialize.h"
#include "samples.h"

#ifdef RESCUESIM_HAVE_ROSCPP_MSGS
#include "roscpp_reference.h"
#endif

namespace rescuesim::msg {
namespace {

TEST(RoscppCrossCheck, SameBytesAndMd5AsRoscpp) {
#ifndef RESCUESIM_HAVE_ROSCPP_MSGS
  GTEST_SKIP() << "Debian's ROS 1 message headers (libroscpp-dev, libsensor-msgs-dev, libnav-msgs-dev, "
                  "libtf2-msgs-dev, libros-rosgraph-msgs-dev) were not found when configuring";
#else
  int compared = 0;
  for (const Message& m : test::all_samples()) {
    const TypeSupport& t = type_of(m);
    const test::RoscppSample ref = test::roscpp_sample(t.ros1_name, 41);
    if (!ref.known) continue;  // rescuesim_msgs/Contacts has no roscpp type
    std::vector<std::uint8_t> ours;
    to_ros1(m, ours, 41);
    EXPECT_EQ(ours, ref.bytes) << t.ros1_name;
    EXPECT_EQ(t.ros1_md5, ref.md5) << t.ros1_name;
    EXPECT_EQ(t.ros1_name, ref.datatype);
    // and roscpp's bytes decode to the sample
    const Message back = from_ros1(t, ref.bytes);
    EXPECT_EQ(to_json(back), to_json(m)) << t.ros1_name;
    ++compared;
  }
  EXPECT_EQ(compared, 17);
#endif
}

}  // namespace
}  // namespace rescuesim::msg
