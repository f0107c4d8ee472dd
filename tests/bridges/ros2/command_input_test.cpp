// Commands from ROS 2 are decoded and checked before they reach the simulation.

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

TEST(CheckTwist, AcceptsAFiniteTwist) {
  msg::Twist t;
  t.linear = Vec3(0.3, 0, 0);
  t.angular = Vec3(0, 0, -0.5);
  const auto c = check_twist(cdr(t));
  ASSERT_TRUE(c.value) << c.problem;
  EXPECT_EQ(c.value->linear.x(), 0.3);
  EXPECT_EQ(c.value->angular.z(), -0.5);
}

TEST(CheckTwist, RefusesNonFiniteComponentsByName) {
  msg::Twist t;
  t.linear = Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  auto c = check_twist(cdr(t));
  EXPECT_FALSE(c.value);
  EXPECT_NE(c.problem.find("linear.x is nan"), std::string::npos) << c.problem;
  t.linear = Vec3::Zero();
  t.angular = Vec3(0, 0, std::numeric_limits<double>::infinity());
  c = check_twist(cdr(t));
  EXPECT_FALSE(c.value);
  EXPECT_NE(c.problem.find("angular.z is inf"), std::string::npos) << c.problem;
}

TEST(CheckTwist, RefusesMalformedBytes) {
  auto bytes = cdr(msg::Twist{});
  // a Twist from a sender with another idea of the type: 8 stray bytes after the 48 of a Twist
  auto longer = bytes;
  longer.resize(longer.size() + 8, 0);
  auto c = check_twist(longer);
  EXPECT_FALSE(c.value);
  EXPECT_NE(c.problem.find("malformed CDR"), std::string::npos) << c.problem;
  // cut short
  bytes.resize(20);
  c = check_twist(bytes);
  EXPECT_FALSE(c.value);
  EXPECT_NE(c.problem.find("malformed CDR"), std::string::npos) << c.problem;
  // big-endian encapsulation
  auto big = cdr(msg::Twist{});
  big[1] = 0x00;
  EXPECT_FALSE(check_twist(big).value);
  EXPECT_FALSE(check_twist({}).value);
}

TEST(CheckHeadCommand, AcceptsOnePositionPerJoint) {
  msg::Float64MultiArray a;
  a.data = {0.1, -0.2, 0.3, 0.0};
  const auto c = check_head_command(cdr(a), 4);
  ASSERT_TRUE(c.value) << c.problem;
  EXPECT_EQ(*c.value, a.data);
}

TEST(CheckHeadCommand, RefusesWrongLengthAndNonFinite) {
  msg::Float64MultiArray a;
  a.data = {0.1, 0.2};
  auto c = check_head_command(cdr(a), 4);
  EXPECT_FALSE(c.value);
  EXPECT_NE(c.problem.find("data has 2 values, expected 4"), std::string::npos) << c.problem;
  a.data = {0.1, 0.2, std::nan(""), 0.0};
  c = check_head_command(cdr(a), 4);
  EXPECT_FALSE(c.value);
  EXPECT_NE(c.problem.find("data[2] is nan"), std::string::npos) << c.problem;
}

}  // namespace
}  // namespace rescuesim::ros2
