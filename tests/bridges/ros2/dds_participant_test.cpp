// The Cyclone DDS wrapper: our serialiser's bytes go out unchanged, bytes that do not fit the
// topic's type are refused, failures to start say why. Two participants in this process, pinned
// to loopback.

#include "bridges/ros2/dds_participant.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>

#include "core/error.h"
#include "msgs/serialize.h"
#include "bridges/ros2/dds_loopback.h"
#include "support/dds_domain.h"

namespace rescuesim::ros2 {
namespace {

class DdsParticipantTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::pin_cyclone_to_loopback();
  }
  // domains of this process's own, so tests running in parallel (ctest -j) do not see each other
  int domain(int index = 0) const { return testing::leased_dds_domain(index); }
};

msg::LaserScan scan() {
  msg::LaserScan s;
  s.header.stamp = SimTime::from_ms(1500);
  s.header.frame_id = "laser";
  s.angle_min = -1, s.angle_max = 1, s.angle_increment = 0.5f;
  s.range_min = 0.05f, s.range_max = 20;
  s.ranges = {1, 2, 3, 4, 5};
  return s;
}

TEST_F(DdsParticipantTest, SerialisedBytesArriveUnchanged) {
  DdsParticipant a(domain(), participant_user_data()), b(domain(), participant_user_data());
  const int w = a.create_writer("rt/scan", "sensor_msgs::msg::dds_::LaserScan_", {});
  const int r = b.create_reader("rt/scan", "sensor_msgs::msg::dds_::LaserScan_", {});
  std::vector<std::uint8_t> sent;
  msg::to_cdr(scan(), sent);
  std::vector<std::uint8_t> got;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (got.empty() && std::chrono::steady_clock::now() < give_up) {
    std::string error;
    // a volatile writer only delivers to readers it has matched: write until one arrives
    if (a.matched_readers(w) > 0) {
      ASSERT_TRUE(a.write(w, sent, &error)) << error;
    }
    b.wait(std::chrono::milliseconds(100));
    b.take(r, [&](std::span<const std::uint8_t> bytes) { got.assign(bytes.begin(), bytes.end()); });
  }
  EXPECT_EQ(got, sent);
  const auto decoded = std::get<msg::LaserScan>(msg::from_cdr(*msg::find_type("sensor_msgs/LaserScan"), got));
  EXPECT_EQ(decoded.ranges, scan().ranges);
  EXPECT_EQ(decoded.header.frame_id, "laser");
}

TEST_F(DdsParticipantTest, BytesThatDoNotFitTheTypeAreRefused) {
  DdsParticipant a(domain(), participant_user_data());
  const int w = a.create_writer("rt/scan", "sensor_msgs::msg::dds_::LaserScan_", {});
  std::vector<std::uint8_t> bytes;
  msg::to_cdr(scan(), bytes);
  bytes.resize(bytes.size() - 9);  // cut into the ranges
  std::string error;
  EXPECT_FALSE(a.write(w, bytes, &error));
  EXPECT_NE(error.find("do not fit"), std::string::npos) << error;
  // a sequence count far beyond the data
  std::vector<std::uint8_t> twist;
  msg::to_cdr(msg::Twist{}, twist);
  const int tw = a.create_writer("rt/cmd", "geometry_msgs::msg::dds_::Twist_", {});
  EXPECT_TRUE(a.write(tw, twist, &error)) << error;
  twist.resize(12);
  EXPECT_FALSE(a.write(tw, twist, &error));
}

TEST_F(DdsParticipantTest, EveryBusTypeHasADescriptor) {
  for (const msg::TypeSupport& t : msg::all_types()) EXPECT_TRUE(DdsParticipant::knows_type(t.dds_name)) << t.dds_name;
}

TEST_F(DdsParticipantTest, AnImpossibleDomainIsAClearError) {
  try {
    DdsParticipant p(5000, participant_user_data());
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("could not create a participant on domain 5000"), std::string::npos) << e.what();
  }
}

TEST_F(DdsParticipantTest, DiscoveryInfoFitsTheGidSizeOfItsDistro) {
  DdsParticipant humble(domain(), participant_user_data()), iron(domain(1), participant_user_data());
  const int wh = humble.create_discovery_writer(24), wi = iron.create_discovery_writer(16);
  const NodeEntities node{"/", "rescuesim", {}, {humble.writer_guid(wh)}};
  std::string error;
  EXPECT_TRUE(humble.write(wh, encode_discovery_info(humble.participant_guid(), {node}, 24), &error)) << error;
  EXPECT_TRUE(iron.write(wi, encode_discovery_info(iron.participant_guid(), {node}, 16), &error)) << error;
  // Iron's layout is too short for Humble's descriptor (the other way round Cyclone reads the
  // padding as "no nodes" and, like any final-struct reader, ignores the rest: no error to see)
  EXPECT_FALSE(humble.write(wh, encode_discovery_info(humble.participant_guid(), {node}, 16), &error));
}

TEST_F(DdsParticipantTest, GuidsAreTheParticipantsPrefixPlusAnEntityId) {
  DdsParticipant a(domain(), participant_user_data());
  const int w = a.create_writer("rt/odom", "nav_msgs::msg::dds_::Odometry_", {});
  const Guid p = a.participant_guid(), g = a.writer_guid(w);
  EXPECT_TRUE(std::equal(p.begin(), p.begin() + 12, g.begin()));
  EXPECT_NE(p, g);
}

// CI once ran two DDS tests side by side on one domain, and one test's peer read the other's
// /scan: a domain leased by one process is never handed to another while it lives.
TEST(LeasedDdsDomain, AProcessesDomainsAreItsOwnUntilItExits) {
  const int mine = testing::leased_dds_domain(0), second = testing::leased_dds_domain(1);
  EXPECT_NE(mine, second);
  EXPECT_EQ(testing::leased_dds_domain(0), mine);  // the same lease, asked again
  EXPECT_GE(mine, testing::kFirstTestDomain);
  EXPECT_LE(second, testing::kLastTestDomain);
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // a second test process: ours are refused to it; it leases another and exits
    int report[3] = {testing::try_lease_dds_domain(mine), testing::try_lease_dds_domain(second), testing::lease_free_dds_domain()};
    (void)!::write(fds[1], report, sizeof report);
    ::_exit(0);
  }
  int report[3] = {-1, -1, -1};
  ASSERT_EQ(::read(fds[0], report, sizeof report), static_cast<ssize_t>(sizeof report));
  ::waitpid(child, nullptr, 0);
  ::close(fds[0]), ::close(fds[1]);
  EXPECT_EQ(report[0], 0);
  EXPECT_EQ(report[1], 0);
  EXPECT_NE(report[2], mine);
  EXPECT_NE(report[2], second);
  EXPECT_TRUE(testing::try_lease_dds_domain(report[2])) << "a dead process's domain is free again";
}

}  // namespace
}  // namespace rescuesim::ros2
