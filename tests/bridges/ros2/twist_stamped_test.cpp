// geometry_msgs/TwistStamped on cmd_vel: the bytes decoded by hand, the stamp rule, and the
// bridge driving a robot with it as it does with Twist (a second reader of the same topic, of
// the other type, listed in ros_discovery_info), refusing a stamp from the future and NaN.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <thread>

#include "bridges/common/cdr_stream.h"
#include "bridges/ros2/command_input.h"
#include "bridges/ros2/dds_participant.h"
#include "bridges/ros2/ros2_bridge.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "bridges/ros2/dds_loopback.h"
#include "support/dds_domain.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using Bytes = std::vector<std::uint8_t>;
using namespace std::chrono_literals;

/// TwistStamped {header {stamp, frame_id}, twist {linear (x, 0, 0), angular (0, 0, w)}} as a ROS 2 publisher writes it.
Bytes twist_stamped(SimTime stamp, const std::string& frame, double x, double w) {
  Bytes out;
  cdr::Writer writer(out, "geometry_msgs/TwistStamped");
  writer.value("header.stamp.sec", static_cast<std::int32_t>(stamp.sec_part()));
  writer.value("header.stamp.nanosec", stamp.nsec_part());
  writer.string("header.frame_id", frame);
  for (const double v : {x, 0.0, 0.0, 0.0, 0.0, w}) writer.value("twist", v);
  return out;
}

TEST(TwistStamped, DecodesTheHeaderAndTheTwistFromBytesWorkedOutByHand) {
  // sec at 0, nanosec at 4, frame_id's length 10 at 8, "base_link\0" at 12..21, padding to 24,
  // then six doubles from 24
  Bytes b = {0x00, 0x01, 0x00, 0x00, 1, 0, 0, 0, 0xf4, 0x01, 0, 0, 10, 0, 0, 0};
  for (const char c : std::string("base_link")) b.push_back(static_cast<std::uint8_t>(c));
  b.insert(b.end(), {0, 0, 0});
  const double values[6] = {0.4, 0, 0, 0, 0, -0.25};
  for (const double v : values) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
    b.insert(b.end(), p, p + 8);
  }
  ASSERT_EQ(b.size(), 4u + 72u);
  EXPECT_EQ(b, twist_stamped(SimTime{1'000'000'500}, "base_link", 0.4, -0.25));
  const auto d = ros2::decode_twist_stamped(b);
  ASSERT_TRUE(d.value) << d.problem;
  EXPECT_EQ(d.value->stamp, SimTime{1'000'000'500});
  EXPECT_EQ(d.value->frame_id, "base_link");
  EXPECT_EQ(d.value->twist.linear.x(), 0.4);
  EXPECT_EQ(d.value->twist.angular.z(), -0.25);
}

TEST(TwistStamped, MalformedBytesSayWhatIsWrong) {
  const Bytes good = twist_stamped(SimTime{0}, "", 1, 0);
  auto d = ros2::decode_twist_stamped(Bytes(good.begin(), good.end() - 8));
  EXPECT_FALSE(d.value);
  EXPECT_NE(d.problem.find("twist.angular.z: 8 bytes needed, 0 left"), std::string::npos) << d.problem;
  Bytes bad_nanos = good;
  bad_nanos[8] = 0xff, bad_nanos[9] = 0xff, bad_nanos[10] = 0xff, bad_nanos[11] = 0xff;
  d = ros2::decode_twist_stamped(bad_nanos);
  EXPECT_NE(d.problem.find("header.stamp.nanosec: 4294967295 is not below 1e9"), std::string::npos) << d.problem;
  Bytes long_name = good;
  long_name[12] = 0xff;  // frame_id's length far beyond the bytes: 255, with 4 + 48 after it
  d = ros2::decode_twist_stamped(long_name);
  EXPECT_NE(d.problem.find("header.frame_id: 255 bytes needed, 52 left"), std::string::npos) << d.problem;
  Bytes extra = good;
  extra.insert(extra.end(), 8, 0);
  d = ros2::decode_twist_stamped(extra);
  EXPECT_NE(d.problem.find("8 trailing bytes"), std::string::npos) << d.problem;
  d = ros2::decode_twist_stamped(Bytes{0x00, 0x07, 0, 0});
  EXPECT_NE(d.problem.find("encapsulation 00 07 is not supported"), std::string::npos) << d.problem;
}

class TwistStampedBridgeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::pin_cyclone_to_loopback();
  }
  int domain() const { return testing::leased_dds_domain(); }
};

/// The reader GIDs of the nodes in a Humble ros_discovery_info sample (24-byte Gids).
std::vector<ros2::Guid> discovery_readers(std::span<const std::uint8_t> bytes) {
  using Gid = std::array<std::uint8_t, 24>;
  struct Node {
    std::string ns, name;
    std::vector<Gid> readers, writers;
  };
  cdr::Reader in(bytes, "ParticipantEntitiesInfo");
  Gid gid;
  in.octets("gid", gid);
  std::vector<Node> nodes;
  // a node takes at least two empty strings (5 bytes each) and two counts
  in.elements("node_entities_info_seq", nodes, 18, cdr::kUnbounded, [&](Node& n) {
    in.string("node_namespace", n.ns);
    in.string("node_name", n.name);
    in.elements("reader_gid_seq", n.readers, 24, cdr::kUnbounded, [&](Gid& g) { in.octets("data", g); });
    in.elements("writer_gid_seq", n.writers, 24, cdr::kUnbounded, [&](Gid& g) { in.octets("data", g); });
  });
  std::vector<ros2::Guid> out;
  for (const Node& n : nodes) {
    for (const Gid& g : n.readers) {
      ros2::Guid guid;
      std::copy(g.begin(), g.begin() + 16, guid.begin());
      out.push_back(guid);
    }
  }
  return out;
}

TEST_F(TwistStampedBridgeTest, DrivesARobotAsTwistDoesAndRefusesFutureStampsAndNaN) {
  Simulation sim(compile_world(testing::room_spec(20.0, {0, 0, 0}), builtin_models()));
  Ros2Options o;
  o.domain_id = domain();
  auto bridge = make_ros2_bridge(o);
  bridge->start(sim);
  sim.step();

  ros2::DdsParticipant ros(domain(), ros2::participant_user_data());
  const int cmd = ros.create_raw_writer("rt/cmd_vel", "geometry_msgs::msg::dds_::TwistStamped_", {});
  const int discovery = ros.create_reader(ros2::kDiscoveryTopic, ros2::kDiscoveryType, ros2::discovery_qos());

  // 2 s at 0.4 m/s, stamped with sim time as a node on use_sim_time stamps
  const auto give_up = std::chrono::steady_clock::now() + 20s;
  SimTime driving_since{-1};
  while (std::chrono::steady_clock::now() < give_up) {
    std::string error;
    if (ros.matched_readers(cmd) > 0) {
      ASSERT_TRUE(ros.write(cmd, twist_stamped(sim.time(), "base_link", 0.4, 0), &error)) << error;
      if (driving_since.ns < 0) driving_since = sim.time();
    }
    std::this_thread::sleep_for(10ms);  // let the command arrive
    sim.step_until(sim.time() + SimTime::from_ms(50));
    if (driving_since.ns >= 0 && sim.time() - driving_since > SimTime::from_seconds(2.0)) break;
  }
  ASSERT_GE(driving_since.ns, 0) << "the bridge's TwistStamped reader on rt/cmd_vel never matched";
  const Vec3 driven = sim.state().robots[0].base.X_WB.p;
  EXPECT_GT(driven.x(), 0.5);
  EXPECT_LT(driven.x(), 0.4 * 2.2);
  EXPECT_NEAR(driven.y(), 0.0, 0.05);
  const BridgeStats before = bridge->stats();
  EXPECT_GT(before.received, 10u);
  EXPECT_EQ(before.rejected, 0u);

  // backwards, stamped 10 s ahead: refused; NaN, unstamped: refused
  std::string error;
  ASSERT_TRUE(ros.write(cmd, twist_stamped(sim.time() + SimTime::from_seconds(10), "", -0.4, 0), &error)) << error;
  ASSERT_TRUE(ros.write(cmd, twist_stamped(SimTime{0}, "", std::numeric_limits<double>::quiet_NaN(), 0), &error)) << error;
  while (bridge->stats().rejected < 2 && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(10ms);
    sim.step_until(sim.time() + SimTime::from_ms(50));
  }
  // a backward command taken would have pulled the robot back within the next second
  sim.step_until(sim.time() + SimTime::from_seconds(1.0));
  // (forward commands of the first part may still have been arriving: `received` may have grown)
  EXPECT_EQ(bridge->stats().rejected, 2u);
  EXPECT_GE(sim.state().robots[0].base.X_WB.p.x(), driven.x() - 0.02);  // a taken one: some 0.1 m back

  // the reader that took them is the node's, in ros_discovery_info
  const std::vector<ros2::Guid> matched = ros.matched_reader_guids(cmd);
  ASSERT_EQ(matched.size(), 1u);
  std::vector<ros2::Guid> listed;
  while (listed.empty() && std::chrono::steady_clock::now() < give_up) {
    ros.take(discovery, [&](std::span<const std::uint8_t> bytes) { listed = discovery_readers(bytes); });
    if (listed.empty()) std::this_thread::sleep_for(10ms);
  }
  bridge->stop();
  EXPECT_NE(std::find(listed.begin(), listed.end(), matched[0]), listed.end());
}

}  // namespace
}  // namespace rescuesim
