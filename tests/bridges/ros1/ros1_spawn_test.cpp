// Robots spawned and deleted while the ROS 1 bridge runs (Simulation::add_robot, remove_robot),
// checked with the real tools on a roscore of the test's own: a spawned robot's topics are
// published (its latched robot_description reaches a late `rostopic echo`) and its cmd_vel
// drives it; a deleted robot's publishers and subscriptions go, and the robot after it, now one
// index down, still answers its own cmd_vel. The test steps the simulation itself (it is the
// simulation thread, where robots are added and removed).

#include <gtest/gtest.h>

#include <string>

#include "bridges/ros1/ros1_bridge.h"
#include "bridges/ros1/ros1_rig.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using namespace testing;

constexpr const char* kNode = "rescuesim_spawn";
/// The description the spawned p3at carries, so that it has a latched robot_description.
constexpr const char* kP3atDescription = R"(<robot name="p3at"><link name="base_link"/></robot>)";

/// The rescue robot as SpawnEntity makes it: named, namespaced, at (x, y) facing +x.
RobotInstance spawned_robot(const std::string& name, double x, double y, const std::string& description = "") {
  RobotSpec spec = rescue_robot();
  spec.description = description;
  RobotInstance r = place_robot(name, std::move(spec), Pose3{Vec3(x, y, 0), Quat::Identity()});
  r.spawned = true;
  r.ns = name;
  return r;
}

/// The publishers part of `rostopic info`'s answer (up to "Subscribers:"), or all of it when the
/// master no longer knows the topic.
std::string publishers_of(const RosMaster& master, const std::string& topic) {
  const std::string info = master.run("rostopic info " + topic, kToolSeconds).out;
  return info.substr(0, info.find("Subscribers:"));
}
/// The subscribers part of `rostopic info`'s answer ("" when the master no longer knows it).
std::string subscribers_of(const RosMaster& master, const std::string& topic) {
  const std::string info = master.run("rostopic info " + topic, kToolSeconds).out;
  const auto at = info.find("Subscribers:");
  return at == std::string::npos ? std::string() : info.substr(at);
}

TEST(Ros1Spawn, ASpawnedRobotIsPublishedAndDrivenAndADeletedOneGoes) {
  SKIP_WITHOUT_ROS1();
  const fs::path dir = temp_dir("ros1-spawn");
  RosMaster master(dir);
  ASSERT_TRUE(master.start()) << "roscore did not come up on port " << master.port();
  for (const auto& [k, v] : master.env()) ::setenv(k.c_str(), v.c_str(), 1);

  // the rescue robot in the middle of a 20 m room; the bridge starts with it alone
  Simulation sim(compile_world(testing::room_spec(), builtin_models()));
  Ros1Options options;
  options.node_name = kNode;
  auto bridge = make_ros1_bridge(options);
  bridge->start(sim);
  for (int i = 0; i < 20; ++i) sim.step();

  // p3at comes (robot 1, with a description) and settles on its wheels for 1 s
  ASSERT_EQ(sim.add_robot(spawned_robot("p3at", 3, 3, kP3atDescription)), RobotIndex(1));
  for (int i = 0; i < 200; ++i) sim.step();

  const CommandResult list = master.run("rostopic list", kToolSeconds);
  EXPECT_NE(list.out.find("/p3at/scan\n"), std::string::npos) << list.out << list.err;
  EXPECT_NE(list.out.find("/p3at/odom\n"), std::string::npos) << list.out;
  EXPECT_NE(list.out.find("/scan\n"), std::string::npos) << list.out;
  EXPECT_NE(publishers_of(master, "/p3at/scan").find(kNode), std::string::npos);
  EXPECT_NE(subscribers_of(master, "/p3at/cmd_vel").find(kNode), std::string::npos);
  // the master has cmd_vel as the classic type, as for the scenario's robot
  EXPECT_EQ(master.run("rostopic type /p3at/cmd_vel", kToolSeconds).out, "geometry_msgs/Twist\n");

  // the description was published before the bridge heard of the robot: latched, it still
  // reaches a subscriber that comes later, and it is the parameter of that name too
  const CommandResult echo = master.run("rostopic echo -n 1 /p3at/robot_description", kToolSeconds);
  EXPECT_EQ(echo.exit_code, 0) << echo.err;
  EXPECT_NE(echo.out.find("<robot name=\\\"p3at\\\">"), std::string::npos) << echo.out;
  EXPECT_NE(master.run("rosparam get /p3at/robot_description", kToolSeconds).out.find("p3at"), std::string::npos);

  // scout comes after it (robot 2), and settles
  ASSERT_EQ(sim.add_robot(spawned_robot("scout", 3, -3)), RobotIndex(2));
  for (int i = 0; i < 200; ++i) sim.step();
  EXPECT_NE(master.run("rostopic list", kToolSeconds).out.find("/scout/scan\n"), std::string::npos);

  // `rostopic pub` of a Twist on a robot's cmd_vel until the bridge has taken one, then 80 steps
  // (0.4 s, less than the drive's command timeout of 0.5 s, so the command in place before the
  // first step drives the whole way); how far each robot went along x
  const double dt = sim.dt();
  constexpr int kSteps = 80;
  const double v = 0.3;
  const auto drive = [&](const std::string& topic) {
    std::vector<double> x0;
    for (const RobotState& r : sim.state().robots) x0.push_back(r.base.X_WB.p.x());
    const std::uint64_t before = bridge->stats().received;
    auto pub = master.spawn({"rostopic", "pub", "-r", "10", topic, "geometry_msgs/Twist", "{linear: {x: 0.3}}"});
    const bool taken = wait_until([&] { return bridge->stats().received > before; }, kPatience);
    pub->interrupt();
    EXPECT_TRUE(taken) << "nothing arrived on " << topic << "\n" << pub->output();
    for (int i = 0; i < kSteps; ++i) sim.step();
    std::vector<double> moved;
    for (std::size_t r = 0; r < x0.size(); ++r) moved.push_back(sim.state().robots[r].base.X_WB.p.x() - x0[r]);
    return moved;
  };
  // the drive reaches 0.3 m/s at its acceleration a at best: over T = 0.4 s it covers at most
  // v T - v^2 / (2 a) = 0.12 - 0.018 = 0.102 m for a = 2.5 m/s^2 (plus a step's travel for where
  // the ramp starts); well over half of that when the command drives
  const DriveSpec& spec = sim.world().robots[1].spec.drive;
  const double T = kSteps * dt;
  const double ideal = v * T - v * v / (2 * spec.max_linear_accel);
  const auto expect_only = [&](const std::vector<double>& moved, std::size_t robot, const char* what) {
    ASSERT_EQ(moved.size(), sim.world().robots.size());
    for (std::size_t r = 0; r < moved.size(); ++r) {
      if (r == robot) {
        EXPECT_LT(moved[r], ideal + v * dt) << what << ": robot " << r;
        EXPECT_GT(moved[r], 0.5 * ideal) << what << ": robot " << r << " barely moved";
      } else {
        EXPECT_NEAR(moved[r], 0.0, 0.002) << what << ": robot " << r << " moved";
      }
    }
  };
  const std::vector<double> by_p3at = drive("/p3at/cmd_vel");
  std::printf("/p3at/cmd_vel 0.3 m/s for %.2f s: robot 1 went %.5f m (ideal ramp %.5f m)\n", T, by_p3at[1], ideal);
  expect_only(by_p3at, 1, "/p3at/cmd_vel");

  // p3at goes: its publishers and its cmd_vel subscription with it (the master may still list
  // the topics, but nothing of this node is on them); scout is robot 1 now
  sim.remove_robot(RobotIndex(1));
  ASSERT_EQ(sim.world().robots.size(), 2u);
  ASSERT_EQ(sim.world().robots[1].name, "scout");
  for (const char* topic : {"/p3at/scan", "/p3at/odom", "/p3at/robot_description"}) {
    EXPECT_EQ(publishers_of(master, topic).find(kNode), std::string::npos) << topic << " is still published";
  }
  EXPECT_EQ(subscribers_of(master, "/p3at/cmd_vel").find(kNode), std::string::npos) << "/p3at/cmd_vel is still subscribed";
  EXPECT_NE(publishers_of(master, "/scout/scan").find(kNode), std::string::npos);
  EXPECT_NE(publishers_of(master, "/scan").find(kNode), std::string::npos);
  // and its description parameter
  const CommandResult params = master.run("rosparam list", kToolSeconds);
  EXPECT_EQ(params.out.find("/p3at/robot_description"), std::string::npos) << params.out;

  // scout's laser still comes, while the simulation steps
  auto scan = master.spawn({"rostopic", "echo", "-n", "1", "/scout/scan"});
  const bool scanned = wait_until(
      [&] {
        for (int i = 0; i < 20; ++i) sim.step();
        return scan->output().find("angle_min") != std::string::npos;
      },
      kPatience);
  EXPECT_TRUE(scanned) << scan->output();
  scan->interrupt();

  // scout's own cmd_vel drives scout, at its new index
  const std::vector<double> by_scout = drive("/scout/cmd_vel");
  std::printf("/scout/cmd_vel 0.3 m/s for %.2f s: robot 1 went %.5f m\n", T, by_scout[1]);
  expect_only(by_scout, 1, "/scout/cmd_vel");
  bridge->stop();
}

}  // namespace
}  // namespace rescuesim
