// ROS 2's mapping onto DDS as the bridge applies it: names, QoS, domain, discovery bytes.

#include "bridges/ros2/ros2_conventions.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "core/error.h"
#include "msgs/serialize.h"

namespace rescuesim::ros2 {
namespace {

TEST(DdsTopicName, PrefixesRtAndDropsTheLeadingSlash) {
  EXPECT_EQ(dds_topic_name("/scan"), "rt/scan");
  EXPECT_EQ(dds_topic_name("/camera/color/image_raw"), "rt/camera/color/image_raw");
  EXPECT_EQ(dds_topic_name("/robot2/cmd_vel"), "rt/robot2/cmd_vel");
}

TEST(WriterQos, ReliableVolatileExceptLatchedAndClock) {
  Topic scan{TopicId{0}, "/scan", "sensor_msgs/LaserScan", 10, false, RobotIndex(0)};
  EXPECT_EQ(writer_qos(scan), (EndpointQos{Reliability::reliable, Durability::volatile_local, 10}));
  Topic tf_static{TopicId{1}, "/tf_static", "tf2_msgs/TFMessage", 0, true, RobotIndex()};
  EXPECT_EQ(writer_qos(tf_static), (EndpointQos{Reliability::reliable, Durability::transient_local, 1}));
  Topic clock{TopicId{2}, "/clock", "rosgraph_msgs/Clock", 200, false, RobotIndex()};
  EXPECT_EQ(writer_qos(clock), (EndpointQos{Reliability::reliable, Durability::volatile_local, 1}));
  EXPECT_EQ(command_reader_qos().reliability, Reliability::best_effort);
  EXPECT_EQ(discovery_qos(), (EndpointQos{Reliability::reliable, Durability::transient_local, 1}));
}

TEST(QueueCapacity, AboutOneSecondOfEachTopicWithinBounds) {
  const Topic clock{TopicId{0}, "/clock", "rosgraph_msgs/Clock", 200, false, RobotIndex()};
  const Topic image{TopicId{1}, "/camera/color/image_raw", "sensor_msgs/Image", 10, false, RobotIndex(0)};
  const Topic slow{TopicId{2}, "/slow", "sensor_msgs/Range", 0.5, false, RobotIndex(0)};
  const Topic tf_static{TopicId{3}, "/tf_static", "tf2_msgs/TFMessage", 0, true, RobotIndex()};
  EXPECT_EQ(queue_capacity(clock, 64), 64u);
  EXPECT_EQ(queue_capacity(image, 64), 10u);
  EXPECT_EQ(queue_capacity(slow, 64), 4u);
  EXPECT_EQ(queue_capacity(tf_static, 64), 64u);
  EXPECT_EQ(queue_capacity(image, 3), 3u);
}

TEST(ResolveDomain, OptionThenEnvironmentThenZero) {
  ::unsetenv("ROS_DOMAIN_ID");
  EXPECT_EQ(resolve_domain(-1), 0);
  ::setenv("ROS_DOMAIN_ID", "42", 1);
  EXPECT_EQ(resolve_domain(-1), 42);
  EXPECT_EQ(resolve_domain(7), 7);
  ::setenv("ROS_DOMAIN_ID", "forty", 1);
  try {
    resolve_domain(-1);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ROS_DOMAIN_ID=forty"), std::string::npos) << e.what();
  }
  ::setenv("ROS_DOMAIN_ID", "233", 1);
  EXPECT_THROW(resolve_domain(-1), Error);
  ::unsetenv("ROS_DOMAIN_ID");
}

TEST(AdaptToDistro, IronRangeGainsAZeroVarianceOtherMessagesStayAsTheyAre) {
  msg::Range r;
  r.header.frame_id = "sonar_front_left";
  r.min_range = 0.03f, r.max_range = 4, r.range = 1.5f;
  std::vector<std::uint8_t> humble;
  msg::to_cdr(r, humble);
  auto same = humble;
  adapt_to_distro(r, Ros2Distro::humble, same);
  EXPECT_EQ(same, humble);
  auto iron = humble;
  adapt_to_distro(r, Ros2Distro::iron_or_newer, iron);
  ASSERT_EQ(iron.size(), humble.size() + 4);
  EXPECT_TRUE(std::equal(humble.begin(), humble.end(), iron.begin()));
  EXPECT_EQ((std::vector<std::uint8_t>(iron.end() - 4, iron.end())), (std::vector<std::uint8_t>{0, 0, 0, 0}));
  // range, the float before it, sits at a 4-byte boundary (counted after the encapsulation header)
  EXPECT_EQ((humble.size() - 4) % 4, 0u);
  msg::Twist t;
  std::vector<std::uint8_t> twist;
  msg::to_cdr(t, twist);
  const auto before = twist;
  adapt_to_distro(t, Ros2Distro::iron_or_newer, twist);
  EXPECT_EQ(twist, before);
}

TEST(UserData, IsTheEnclaveAsRmwWritesIt) { EXPECT_EQ(participant_user_data(), "enclave=/;"); }

TEST(DiscoveryInfo, HumbleLayoutByHand) {
  Guid participant{}, writer{}, reader{};
  for (int i = 0; i < 16; ++i) {
    participant[i] = static_cast<std::uint8_t>(i + 1);
    writer[i] = static_cast<std::uint8_t>(0x40 + i);
    reader[i] = static_cast<std::uint8_t>(0x80 + i);
  }
  NodeEntities node{"/", "rescuesim", {reader}, {writer}};
  const auto b = encode_discovery_info(participant, {node}, gid_size(Ros2Distro::humble));
  // header 4 | gid 24 | nodes 4 | ns: 4 + "/\0" = 6, pad 2 | name: 4 + 10, pad 2 | readers 4 + 24 | writers 4 + 24
  ASSERT_EQ(b.size(), 4u + 24 + 4 + 6 + 2 + 14 + 2 + 28 + 28);
  EXPECT_EQ((std::vector<std::uint8_t>(b.begin(), b.begin() + 4)), (std::vector<std::uint8_t>{0, 1, 0, 0}));
  EXPECT_EQ(b[4], 1);
  EXPECT_EQ(b[19], 16);
  EXPECT_EQ(b[20], 0);  // zero padding to 24 bytes
  EXPECT_EQ(b[27], 0);
  EXPECT_EQ(b[28], 1);  // one node
  EXPECT_EQ(b[32], 2);  // "/" with its NUL
  EXPECT_EQ(b[36], '/');
  EXPECT_EQ(b[37], 0);
  EXPECT_EQ(b[40], 10);  // "rescuesim" with its NUL, after 2 bytes of alignment
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(&b[44])), "rescuesim");
  EXPECT_EQ(b[56], 1);  // one reader, after 2 bytes of alignment
  EXPECT_EQ(b[60], 0x80);
  EXPECT_EQ(b[84], 1);  // one writer
  EXPECT_EQ(b[88], 0x40);
  EXPECT_EQ(b.back(), 0);
}

TEST(DiscoveryInfo, IronGidsAreSixteenBytes) {
  Guid participant{}, writer{};
  participant.fill(7);
  writer.fill(9);
  const auto b = encode_discovery_info(participant, {NodeEntities{"/", "n", {}, {writer}}}, gid_size(Ros2Distro::iron_or_newer));
  // header 4 | gid 16 | nodes 4 | ns 6, pad 2 | name 4 + 2, pad 2 | readers 4 | writers 4 + 16
  ASSERT_EQ(b.size(), 4u + 16 + 4 + 8 + 8 + 4 + 20);
  EXPECT_EQ(b[19], 7);
  EXPECT_EQ(b[20], 1);
  EXPECT_EQ(b[40], 0);  // no readers
  EXPECT_EQ(b[44], 1);  // one writer
  EXPECT_EQ(b[48], 9);
}

}  // namespace
}  // namespace rescuesim::ros2
