// cmd_vel as geometry_msgs/TwistStamped from `rostopic pub`, against the bridge in this process:
// it drives the robot exactly as the same Twist does, and a stamp ahead of sim time, NaN, or a
// message of another type is refused with a warning. The test steps the simulation itself, so
// both drives start from the same snapshot with their command in place before the first step.

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "bridges/ros1/ros1_bridge.h"
#include "bridges/ros1/ros1_rig.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "support/log_capture.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using namespace testing;

TEST(Ros1TwistStamped, DrivesAsTwistDoesAndFutureStampsNanAndOtherTypesAreRefused) {
  SKIP_WITHOUT_ROS1();
  LogCapture log;
  const fs::path dir = temp_dir("ros1-twist-stamped");
  RosMaster master(dir);
  ASSERT_TRUE(master.start()) << "roscore did not come up on port " << master.port();
  for (const auto& [k, v] : master.env()) ::setenv(k.c_str(), v.c_str(), 1);

  // the rescue robot in the middle of a 20 m room, facing +x; settled on its wheels for 1 s
  Simulation sim(compile_world(testing::room_spec(), builtin_models()));
  for (int i = 0; i < 200; ++i) sim.step();
  Ros1Options options;
  options.node_name = "rescuesim_twist_stamped";
  auto bridge = make_ros1_bridge(options);
  bridge->start(sim);
  // the master has cmd_vel as the classic type, though the subscription takes either
  EXPECT_EQ(master.run("rostopic type /cmd_vel", kToolSeconds).out, "geometry_msgs/Twist\n");
  const State start = sim.snapshot();
  const double x0 = sim.state().robots[0].base.X_WB.p.x();
  const DriveSpec& drive = sim.world().robots[0].spec.drive;
  const double dt = sim.dt();
  // 80 steps = 0.4 s: less than the drive's command timeout (0.5 s), so the one command that is
  // in place before the first step drives the whole way, and nothing arriving later matters
  constexpr int kSteps = 80;
  ASSERT_LT(kSteps * dt, drive.command_timeout);

  // publishes `value` as `type` on /cmd_vel until the bridge has counted it (taken or refused),
  // then stops the publisher and takes the steps; the x distance driven from the start snapshot
  const auto drive_from_start = [&](const std::string& type, const std::string& value) {
    sim.restore(start);
    const BridgeStats before = bridge->stats();
    auto pub = master.spawn({"rostopic", "pub", "-r", "10", "/cmd_vel", type, value});
    const bool counted = wait_until(
        [&] {
          const BridgeStats now = bridge->stats();
          return now.received > before.received || now.rejected > before.rejected;
        },
        kPatience);
    pub->interrupt();
    EXPECT_TRUE(counted) << "nothing of " << type << " " << value << " arrived\n" << pub->output();
    for (int i = 0; i < kSteps; ++i) sim.step();
    return sim.state().robots[0].base.X_WB.p.x() - x0;
  };
  const std::string stamp_now =
      "{secs: " + std::to_string(sim.time().sec_part()) + ", nsecs: " + std::to_string(sim.time().nsec_part()) + "}";

  const double by_twist = drive_from_start("geometry_msgs/Twist", "{linear: {x: 0.3}}");
  const BridgeStats after_twist = bridge->stats();
  const double by_stamped = drive_from_start("geometry_msgs/TwistStamped",
                                             "{header: {stamp: " + stamp_now + ", frame_id: base_link}, twist: {linear: {x: 0.3}}}");
  const BridgeStats after_stamped = bridge->stats();
  EXPECT_GT(after_stamped.received, after_twist.received);
  EXPECT_EQ(after_stamped.rejected, 0u) << log.text();

  // the drive reaches 0.3 m/s at 2.5 m/s^2 at best: over T = 0.4 s it covers at most
  // v T - v^2 / (2 a) = 0.12 - 0.018 = 0.102 m (plus a step's travel for where the ramp starts)
  const double v = 0.3, T = kSteps * dt;
  const double ideal = v * T - v * v / (2 * drive.max_linear_accel);
  std::printf("0.3 m/s for %.2f s: Twist %.5f m, TwistStamped %.5f m (ideal ramp %.5f m)\n", T, by_twist, by_stamped, ideal);
  EXPECT_LT(by_twist, ideal + v * dt);
  EXPECT_GT(by_twist, 0.5 * ideal) << "the Twist barely moved the robot";
  // the same command from the same state: the same motion. Were the command to land a step
  // later, the robot would be at most one step's travel at the drive's top speed behind.
  EXPECT_NEAR(by_stamped, by_twist, drive.max_linear * dt);

  // refused, and the robot stays where it is: a stamp 100000 s ahead of sim time, a NaN speed,
  // a message of another type
  const auto refused = [&](const std::string& type, const std::string& value, const std::string& warning) {
    const std::uint64_t received = bridge->stats().received;
    const double moved = drive_from_start(type, value);
    EXPECT_NEAR(moved, 0.0, 0.002) << type << " " << value << " moved the robot";
    EXPECT_EQ(bridge->stats().received, received) << type << " " << value;
    EXPECT_TRUE(wait_until([&] { return log.text().find(warning) != std::string::npos; }, std::chrono::seconds(5)))
        << "no warning \"" << warning << "\" in\n"
        << log.text();
  };
  refused("geometry_msgs/TwistStamped", "{header: {stamp: {secs: 100000, nsecs: 0}}, twist: {linear: {x: 0.3}}}",
          "ROS 1: rejected a command on /cmd_vel: header.stamp 100000.000 s is 99");
  refused("geometry_msgs/TwistStamped", "{twist: {linear: {x: .nan}}}", "ROS 1: rejected a command on /cmd_vel: linear.x is");
  refused("std_msgs/String", "hello",
          "ROS 1: rejected a command on /cmd_vel: a std_msgs/String message: cmd_vel takes geometry_msgs/Twist or "
          "geometry_msgs/TwistStamped");
  EXPECT_GE(bridge->stats().rejected, 3u);
  bridge->stop();
}

// roscpp gives a cmd_vel subscription the type of the first publisher it connects to and keeps it
// after that publisher leaves. A publisher that connects and leaves between two of the bridge's
// master checks (period 4 s here, so that the handover below fits between two) must not leave
// the subscription deaf to the next publisher of the other type: a Twist publisher takes over
// from a TwistStamped one that took over from a Twist one, and its commands arrive.
TEST(Ros1TwistStamped, EachPublisherTakesOverWhenThePreviousTypeLeavesBetweenChecks) {
  SKIP_WITHOUT_ROS1();
  LogCapture log;
  const fs::path dir = temp_dir("ros1-velocity-handover");
  RosMaster master(dir);
  ASSERT_TRUE(master.start()) << "roscore did not come up on port " << master.port();
  for (const auto& [k, v] : master.env()) ::setenv(k.c_str(), v.c_str(), 1);
  Simulation sim(compile_world(testing::room_spec(), builtin_models()));
  Ros1Options options;
  options.node_name = "rescuesim_velocity_handover";
  options.master_check_period = 4.0;
  auto bridge = make_ros1_bridge(options);
  bridge->start(sim);
  const auto arrives = [&](const char* what) {
    const std::uint64_t before = bridge->stats().received;
    const bool ok = wait_until([&] { return bridge->stats().received > before + 2; }, kPatience);
    EXPECT_TRUE(ok) << what << " never arrived\n" << log.text();
    return ok;
  };
  const auto pub = [&](const std::string& type, const std::string& value) {
    return master.spawn({"rostopic", "pub", "-r", "20", "/cmd_vel", type, value});
  };
  const std::string twist = "{linear: {x: 0.1}}";
  const std::string stamped = "{twist: {linear: {x: 0.1}}}";  // stamp 0: unset, taken
  auto first = pub("geometry_msgs/Twist", twist);
  ASSERT_TRUE(arrives("the first Twist publisher's commands"));
  auto second = pub("geometry_msgs/TwistStamped", stamped);
  first->interrupt();
  ASSERT_TRUE(arrives("the TwistStamped publisher's commands, once the Twist publisher left"));
  // a Twist publisher comes and the TwistStamped one leaves at once, likely before the next check
  auto third = pub("geometry_msgs/Twist", twist);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // registered with the master
  second->interrupt();
  EXPECT_TRUE(arrives("the second Twist publisher's commands, once the TwistStamped publisher left"));
  third->interrupt();
  EXPECT_EQ(bridge->stats().rejected, 0u) << log.text();
  bridge->stop();
}

}  // namespace
}  // namespace rescuesim
