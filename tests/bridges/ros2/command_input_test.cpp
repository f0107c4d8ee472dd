// Commands from ROS 2 are decoded before they reach the shared gate: bytes that are not a
// message of the type are refused with a reason; the values pass through unchanged (the gate,
// tests/bridges/common/commands_test.cpp, checks them).

#include "bridges/ros2/command_input.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "msgs/serialize.h"

namespace rescuesim::ros2 {
namespace {

std::vector<std::uint8_t> cdr(const msg::Message& m) {
  std::vector<std::uint8_t> out;
  msg::to_cdr(m, out);
  return out;
}

TEST(DecodeTwist, GivesTheTwistBackEvenWhenNotFinite) {
  msg::Twist t;
  t.linear = Vec3(0.3, 0, 0);
  t.angular = Vec3(0, 0, -0.5);
  auto c = decode_twist(cdr(t));
  ASSERT_TRUE(c.value) << c.problem;
  EXPECT_EQ(c.value->linear.x(), 0.3);
  EXPECT_EQ(c.value->angular.z(), -0.5);
  // a NaN is a value for the gate to refuse, not malformed bytes
  t.linear = Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  c = decode_twist(cdr(t));
  ASSERT_TRUE(c.value) << c.problem;
  EXPECT_TRUE(std::isnan(c.value->linear.x()));
}

TEST(DecodeTwist, RefusesMalformedBytes) {
  auto bytes = cdr(msg::Twist{});
  // a Twist from a sender with another idea of the type: 8 stray bytes after the 48 of a Twist
  auto longer = bytes;
  longer.resize(longer.size() + 8, 0);
  auto c = decode_twist(longer);
  EXPECT_FALSE(c.value);
  EXPECT_NE(c.problem.find("malformed CDR"), std::string::npos) << c.problem;
  // cut short
  bytes.resize(20);
  c = decode_twist(bytes);
  EXPECT_FALSE(c.value);
  EXPECT_NE(c.problem.find("malformed CDR"), std::string::npos) << c.problem;
  // big-endian encapsulation
  auto big = cdr(msg::Twist{});
  big[1] = 0x00;
  EXPECT_FALSE(decode_twist(big).value);
  EXPECT_FALSE(decode_twist({}).value);
}

TEST(DecodeHeadCommand, GivesTheDataArrayWhateverItsLength) {
  msg::Float64MultiArray a;
  a.data = {0.1, -0.2, 0.3, 0.0};
  auto c = decode_head_command(cdr(a));
  ASSERT_TRUE(c.value) << c.problem;
  EXPECT_EQ(*c.value, a.data);
  a.data = {0.1, 0.2};
  c = decode_head_command(cdr(a));
  ASSERT_TRUE(c.value) << c.problem;
  EXPECT_EQ(c.value->size(), 2u);
  auto bytes = cdr(a);
  bytes.resize(6);
  EXPECT_NE(decode_head_command(bytes).problem.find("malformed CDR"), std::string::npos);
}

}  // namespace
}  // namespace rescuesim::ros2
