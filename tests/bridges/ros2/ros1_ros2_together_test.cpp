// `rescuesim run --ros1 --ros2`: both bridges in one run. A ROS 1 tool (rostopic, on a roscore
// of the test's own) and an independent ROS 2 participant (the Fast DDS peer) read /scan at the
// same time, and the peer drives the robot through /cmd_vel. Compiled only when the ROS 1
// bridge and the Fast DDS peer were both built.

#include <gtest/gtest.h>

#include <cstdlib>
#include <future>
#include <nlohmann/json.hpp>

#if defined(RESCUESIM_ROS1_BRIDGE_BUILT) && !defined(ROS2_PEER_MISSING)
#include "bridges/ros1/ros1_rig.h"
#include "bridges/ros2/dds_loopback.h"
#include "support/dds_domain.h"
#endif

namespace rescuesim {
namespace {

#if !defined(RESCUESIM_ROS1_BRIDGE_BUILT) || defined(ROS2_PEER_MISSING)
TEST(Ros1Ros2Together, Skipped) { GTEST_SKIP() << "needs both the ROS 1 bridge and the Fast DDS peer in this build"; }
#else

using namespace rescuesim::testing;

TEST(Ros1Ros2Together, RostopicAndADdsPeerReadScanWhileThePeerDrives) {
  const std::string missing = ros1_tools_missing();
  if (!missing.empty()) GTEST_SKIP() << missing;
  const fs::path dir = temp_dir("ros1-ros2-together");
  pin_dds_to_loopback(dir);
  const int domain = testing::leased_dds_domain();
  RosMaster master(dir);
  ASSERT_TRUE(master.start()) << "roscore did not start";

  const fs::path yaml = write_room(dir);
  // the Fast DDS peer is built from Humble's IDL: the run speaks Humble
  auto sim = master.spawn({RESCUESIM_EXE, "run", yaml.string(), "--ros1", "--ros2", "--ros2-distro", "humble", "--ros-domain",
                           std::to_string(domain), "--duration", "60", "--quiet", "--out", (dir / "out").string()});
  ASSERT_TRUE(
      wait_until([&] { return sim->output().find("bridge        ros2 started") != std::string::npos || !sim->running(); }, kPatience));
  ASSERT_TRUE(sim->running()) << sim->output();
  EXPECT_NE(sim->output().find("bridge        ros1 started"), std::string::npos) << sim->output();

  // both at once: rostopic on ROS 1, the Fast DDS peer on ROS 2 (which drives at 0.3 m/s for 2 s)
  auto echo = std::async(std::launch::async, [&] { return master.run("rostopic echo -n 1 /scan", kToolSeconds); });
  const CommandResult peer =
      run_command(std::string("'") + ROS2_PEER_EXE + "' --domain " + std::to_string(domain) + " --mode drive --timeout 25");
  const CommandResult scan = echo.get();
  sim->signal(SIGINT);
  const std::optional<int> code = sim->wait(20s);

  // ROS 1: one /scan from the room's 181-beam laser in frame "laser"
  EXPECT_EQ(scan.exit_code, 0) << scan.err;
  EXPECT_EQ(field(scan.out, "frame_id"), "laser") << scan.out;
  EXPECT_EQ(numbers(scan.out, "ranges").size(), 181u) << scan.out;
  // ROS 2: the peer read the same laser and its /cmd_vel moved the robot forward (+x)
  ASSERT_EQ(peer.exit_code, 0) << peer.err << "\nsim: " << sim->output();
  const auto r = nlohmann::json::parse(peer.out, nullptr, false);
  ASSERT_FALSE(r.is_discarded()) << peer.out;
  EXPECT_GT(r["scan"]["count"].get<int>(), 0);
  EXPECT_EQ(r["scan"]["ranges"].get<int>(), 181);
  EXPECT_EQ(r["scan"]["frame"], "laser");
  EXPECT_GT(r["commands"].get<int>(), 10);
  // 0.3 m/s for 2 s of wall time; a loaded machine's realtime run may cover less sim time
  EXPECT_GT(r["odom"]["dx"].get<double>(), 0.25);
  EXPECT_NEAR(r["odom"]["vx_driving"].get<double>(), 0.3, 0.05);
  EXPECT_LT(std::abs(r["odom"]["dy"].get<double>()), 0.05);
  // the run ended cleanly and both bridges report what they did
  EXPECT_EQ(code, std::optional<int>(0)) << sim->output();
  const std::string out = sim->output();
  const auto line = [&](const std::string& name) {
    const auto at = out.find("bridge " + name + ":");
    return at == std::string::npos ? std::string() : out.substr(at, out.find('\n', at) - at);
  };
  EXPECT_NE(line("ros1").find(", 0 commands received"), std::string::npos) << out;  // nobody drove over ROS 1
  EXPECT_FALSE(line("ros2").empty()) << out;
  EXPECT_EQ(line("ros2").find(", 0 commands received"), std::string::npos) << out;  // the peer did, over ROS 2
}

#endif

}  // namespace
}  // namespace rescuesim
