// cmd_vel in either type over ROS 1: which type a connection header names, TwistStamped bytes
// worked out by hand from the .msg layout (std_msgs/Header: uint32 seq, uint32 sec, uint32 nsec,
// string frame_id; geometry_msgs/Twist: six float64), malformed bytes named by field, and the
// stamp check against sim time.

#include "bridges/ros1/ros1_velocity.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "msgs/md5.h"
#include "msgs/serialize.h"

namespace rescuesim {
namespace {

using namespace ros1_wire;

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put_f64(std::vector<std::uint8_t>& out, double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, 8);
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<std::uint8_t>(bits >> (8 * i)));
}

/// A TwistStamped: seq 7, stamp 12.5 s, frame "base_link", linear (0.3, 0, 0), angular (0, 0, -0.5).
std::vector<std::uint8_t> twist_stamped_bytes() {
  std::vector<std::uint8_t> b;
  put_u32(b, 7);
  put_u32(b, 12);
  put_u32(b, 500'000'000);
  put_u32(b, 9);
  for (char c : std::string("base_link")) b.push_back(static_cast<std::uint8_t>(c));
  for (double v : {0.3, 0.0, 0.0, 0.0, 0.0, -0.5}) put_f64(b, v);
  return b;
}

const std::string& twist_md5() { return msg::find_type("geometry_msgs/Twist")->ros1_md5; }

TEST(Ros1Velocity, TwistStampedMd5IsTheOneRos1Computes) {
  // genmsg: the MD5 of the message text with each field type replaced by its own MD5
  // (std_msgs/Header's is 2176decaecbce78abc3b96ef049fabed)
  EXPECT_EQ(twist_md5(), "9f195f881246fdfa2798d1d3eebca84a");
  EXPECT_EQ(msg::md5_hex("2176decaecbce78abc3b96ef049fabed header\n" + twist_md5() + " twist"), kTwistStampedMd5);
}

TEST(Ros1Velocity, TheConnectionHeaderSaysWhichTypeArrives) {
  std::string why;
  EXPECT_EQ(velocity_type("geometry_msgs/Twist", twist_md5(), &why), VelocityType::twist);
  EXPECT_EQ(velocity_type("geometry_msgs/TwistStamped", kTwistStampedMd5, &why), VelocityType::twist_stamped);
  EXPECT_EQ(why, "");

  EXPECT_FALSE(velocity_type("std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1", &why));
  EXPECT_EQ(why, "a std_msgs/String message: cmd_vel takes geometry_msgs/Twist or geometry_msgs/TwistStamped");
  // the right name with another layout's MD5, and a wildcard MD5, say nothing of the layout
  EXPECT_FALSE(velocity_type("geometry_msgs/TwistStamped", twist_md5(), &why));
  EXPECT_EQ(
      why.rfind("a geometry_msgs/TwistStamped with MD5 9f195f881246fdfa2798d1d3eebca84a, expected 98d34b0043a2093cf9d9345ab6eef12e", 0), 0u)
      << why;
  EXPECT_FALSE(velocity_type("geometry_msgs/Twist", "*", &why));
  EXPECT_EQ(why.rfind("a geometry_msgs/Twist with MD5 *, expected 9f195f881246fdfa2798d1d3eebca84a", 0), 0u) << why;
}

TEST(Ros1Velocity, TwistStampedDecodesFromBytesWorkedOutByHand) {
  const std::vector<std::uint8_t> b = twist_stamped_bytes();
  ASSERT_EQ(b.size(), 4u + 4 + 4 + 4 + 9 + 6 * 8);  // 73
  const VelocityCommand c = decode_velocity(VelocityType::twist_stamped, b);
  EXPECT_TRUE(c.stamped);
  EXPECT_EQ(c.stamp.ns, 12'500'000'000);
  EXPECT_EQ(c.frame_id, "base_link");
  EXPECT_EQ(c.twist.linear.x(), 0.3);
  EXPECT_EQ(c.twist.linear.y(), 0.0);
  EXPECT_EQ(c.twist.angular.z(), -0.5);

  // a Twist is the last 48 bytes alone
  const VelocityCommand t = decode_velocity(VelocityType::twist, std::span(b).subspan(25));
  EXPECT_FALSE(t.stamped);
  EXPECT_EQ(t.twist.linear.x(), 0.3);
  EXPECT_EQ(t.twist.angular.z(), -0.5);
}

TEST(Ros1Velocity, MalformedTwistStampedIsAnErrorNamingTheField) {
  const std::vector<std::uint8_t> b = twist_stamped_bytes();
  const auto error = [](std::span<const std::uint8_t> bytes) {
    try {
      decode_velocity(VelocityType::twist_stamped, bytes);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // 10 bytes: seq and sec, then 2 of nsec's 4
  EXPECT_EQ(error(std::span(b).first(10)), "geometry_msgs/TwistStamped: header.stamp.nsec: truncated: a value needs 4 bytes, 2 left");
  // a frame_id that claims 4294967280 bytes, with 57 left
  std::vector<std::uint8_t> absurd = b;
  absurd[12] = 0xF0;
  absurd[13] = absurd[14] = absurd[15] = 0xFF;
  EXPECT_EQ(error(absurd),
            "geometry_msgs/TwistStamped: header.frame_id: truncated: string of 4294967280 bytes needs 4294967280 bytes, 57 left");
  // the twist cut short, and a byte too many: msgs' Twist decoder, inside the TwistStamped
  const std::string short_twist = error(std::span(b).first(b.size() - 8));
  EXPECT_EQ(short_twist.rfind("geometry_msgs/TwistStamped: twist: angular.z: truncated", 0), 0u) << short_twist;
  std::vector<std::uint8_t> longer = b;
  longer.push_back(0);
  EXPECT_EQ(error(longer), "geometry_msgs/TwistStamped: twist: 1 trailing bytes after the message");
  EXPECT_EQ(error({}), "geometry_msgs/TwistStamped: header.seq: truncated: a value needs 4 bytes, 0 left");
}

}  // namespace
}  // namespace rescuesim
