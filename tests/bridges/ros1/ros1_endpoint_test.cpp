// Where the ROS 1 node looks for its master and which host name it gives its peers.

#include "bridges/ros1/ros1_endpoint.h"

#include <gtest/gtest.h>

namespace rescuesim {
namespace {

TEST(Ros1Endpoint, UnsetMasterMeansRoscoresDefaultAndALocalNode) {
  const Ros1Endpoint e = resolve_ros1_endpoint(nullptr, nullptr, nullptr);
  EXPECT_EQ(e.master_uri, "http://localhost:11311");
  EXPECT_EQ(e.hostname, "localhost");
}

TEST(Ros1Endpoint, EmptyVariablesCountAsUnset) {
  const Ros1Endpoint e = resolve_ros1_endpoint("", "", "");
  EXPECT_EQ(e.master_uri, "http://localhost:11311");
  EXPECT_EQ(e.hostname, "localhost");
}

TEST(Ros1Endpoint, TheUsersHostnameOrIpWins) {
  EXPECT_EQ(resolve_ros1_endpoint("http://localhost:11311", "robot-pc", nullptr).hostname, "");
  EXPECT_EQ(resolve_ros1_endpoint("http://127.0.0.1:11311", nullptr, "10.0.0.5").hostname, "");
}

TEST(Ros1Endpoint, ARemoteMasterLeavesTheHostNameToRoscpp) {
  const Ros1Endpoint e = resolve_ros1_endpoint("http://base-station:11311/", nullptr, nullptr);
  EXPECT_EQ(e.master_uri, "http://base-station:11311/");
  EXPECT_EQ(e.hostname, "");
}

TEST(Ros1Endpoint, LoopbackUris) {
  for (const char* uri : {"http://localhost:11311", "http://LOCALHOST:1/", "http://127.0.0.1:11311", "http://127.1.2.3:5",
                          "http://[::1]:11311", "localhost:11311"}) {
    EXPECT_TRUE(is_loopback_uri(uri)) << uri;
  }
  for (const char* uri : {"http://10.0.0.2:11311", "http://robot:11311", "http://localhostess:11311", "http://[fe80::1]:11311"}) {
    EXPECT_FALSE(is_loopback_uri(uri)) << uri;
  }
}

}  // namespace
}  // namespace rescuesim
