// A robot's description and joint commands over ROS 1, checked with the real tools on a roscore
// of the test's own: `rosparam get /robot_description`, a latched `rostopic echo -n 1
// /robot_description`, a rospy node reading both byte for byte, and `rostopic pub` on
// /joint_command. Two set-ups: the rescuesim executable on a scenario with the TurtleBot3 burger
// URDF (worlds/robots/), and the bridge in this process on the hand-built slider robot
// (tests/sim/slider_robot.h), whose prismatic joint takes joint commands.

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <thread>

#include "bridges/ros1/ros1_bridge.h"
#include "bridges/ros1/ros1_rig.h"
#include "sim/simulation.h"
#include "sim/slider_robot.h"

namespace rescuesim {
namespace {

using namespace testing;

/// A rospy node that takes one message of the latched std_msgs/String topic argv[1] and the
/// parameter of the same name, and writes both, byte for byte, to argv[2] and argv[3].
const char* kReadDescriptionPy = R"(import sys
import rospy
from std_msgs.msg import String

rospy.init_node("description_reader", anonymous=True)
message = rospy.wait_for_message(sys.argv[1], String, timeout=60)
with open(sys.argv[2], "w", encoding="utf-8") as f:
    f.write(message.data)
with open(sys.argv[3], "w", encoding="utf-8") as f:
    f.write(rospy.get_param(sys.argv[1]))
)";

/// The description on the topic and in the parameter `name`, as the rospy node read them.
std::pair<std::string, std::string> read_description(const RosMaster& master, const fs::path& dir, const std::string& name) {
  write_text(dir / "read_description.py", kReadDescriptionPy);
  const fs::path topic = dir / "topic.txt", param = dir / "param.txt";
  const CommandResult r = master.run("/usr/bin/python3 '" + (dir / "read_description.py").string() + "' " + name + " '" + topic.string() +
                                         "' '" + param.string() + "'",
                                     kToolSeconds);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  return {slurp(topic), slurp(param)};
}

TEST(Ros1Urdf, TheDescriptionIsALatchedTopicAndAParameter) {
  SKIP_WITHOUT_ROS1();
  const fs::path dir = temp_dir("ros1-urdf");
  // the scenario's resource path "robots" is the project's worlds/robots
  const fs::path yaml = write_turtlebot3(dir, "ros1_turtlebot3");
  const CommandResult check = run_command("'" RESCUESIM_EXE "' check '" + yaml.string() + "'");
  ASSERT_EQ(check.exit_code, 0) << check.out << check.err;

  RosMaster master(dir);
  ASSERT_TRUE(master.start()) << "roscore did not come up on port " << master.port();
  Simulator sim;
  ASSERT_TRUE(sim.start(master, dir, yaml, {"--duration", "120", "--no-cameras"})) << sim.output();

  // the rospy node gets the same text from the topic (latched: it subscribes after it went out)
  // and from the parameter
  const auto [topic, param] = read_description(master, dir, "/robot_description");
  EXPECT_EQ(topic, param);
  EXPECT_NE(topic.find("<robot name=\"turtlebot3_burger\""), std::string::npos) << topic.substr(0, 200);
  EXPECT_NE(topic.find("base_footprint\""), std::string::npos);
  EXPECT_EQ(topic.find("${namespace}"), std::string::npos) << "placeholders left in the description";

  // and the command-line tools as a user runs them
  const CommandResult get = master.run("rosparam get /robot_description", kToolSeconds);
  EXPECT_EQ(get.exit_code, 0) << get.err;
  EXPECT_NE(get.out.find("turtlebot3_burger"), std::string::npos) << get.out.substr(0, 300);
  const CommandResult echo = master.run("rostopic echo -n 1 /robot_description", kToolSeconds);
  EXPECT_EQ(echo.exit_code, 0) << echo.err;
  EXPECT_EQ(echo.out.rfind("data: ", 0), 0u) << echo.out.substr(0, 300);
  EXPECT_NE(echo.out.find("turtlebot3_burger"), std::string::npos) << echo.out.substr(0, 300);
  EXPECT_NE(master.run("rostopic info /robot_description", kToolSeconds).out.find("Type: std_msgs/String"), std::string::npos);

  // the TF tree hangs from the URDF's root link: odom -> base_footprint -> base_link
  const std::string odom = master.run("rostopic echo -n 1 --noarr /odom", kToolSeconds).out;
  EXPECT_EQ(field(odom, "child_frame_id"), "base_footprint") << odom;
  const std::string tf_static = master.run("rostopic echo -n 1 /tf_static", kToolSeconds).out;
  EXPECT_NE(tf_static.find("frame_id: \"base_footprint\"\n    child_frame_id: \"base_link\""), std::string::npos) << tf_static;
  // the burger's moving joints are its drive wheels: nothing for joint_command, no such subscription
  const CommandResult joint_command = master.run("rostopic info /joint_command", kToolSeconds);
  EXPECT_EQ((joint_command.out + joint_command.err).find("/rescuesim"), std::string::npos) << joint_command.out << joint_command.err;

  EXPECT_EQ(sim.interrupt(), 0) << sim.output();
}

TEST(Ros1JointCommand, TheSlidersDescriptionAndJointCommandsThroughRealTools) {
  SKIP_WITHOUT_ROS1();
  const fs::path dir = temp_dir("ros1-joint-command");
  RosMaster master(dir);
  ASSERT_TRUE(master.start()) << "roscore did not come up on port " << master.port();
  for (const auto& [k, v] : master.env()) ::setenv(k.c_str(), v.c_str(), 1);

  // the bridge in this process; the simulation steps on a thread of its own at about real time
  Simulation sim(slider_world());
  Ros1Options options;
  options.node_name = "rescuesim_slider";
  auto bridge = make_ros1_bridge(options);
  bridge->start(sim);
  std::atomic<bool> stop{false};
  std::atomic<double> lift{0}, lift_target{0};
  std::thread stepper([&] {
    while (!stop.load()) {
      sim.step();
      lift = sim.state().robots[0].q[0];
      lift_target = sim.state().robots[0].joint_target[0];
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  });
  const auto finish = [&] {
    stop = true;
    stepper.join();
    bridge->stop();
  };

  const auto [topic, param] = read_description(master, dir, "/robot_description");
  EXPECT_EQ(topic, kSliderDescription);
  EXPECT_EQ(param, kSliderDescription);
  const CommandResult get = master.run("rosparam get /robot_description", kToolSeconds);
  EXPECT_EQ(get.exit_code, 0) << get.err;
  EXPECT_NE(get.out.find("prismatic"), std::string::npos) << get.out;
  const CommandResult echo = master.run("rostopic echo -n 1 /robot_description", kToolSeconds);
  EXPECT_EQ(echo.out.rfind("data: ", 0), 0u) << echo.out << echo.err;
  EXPECT_NE(echo.out.find("prismatic"), std::string::npos) << echo.out;

  // the node takes joint_command (sensor_msgs/JointState)
  const std::string info = master.run("rostopic info /joint_command", kToolSeconds).out;
  EXPECT_NE(info.find("Type: sensor_msgs/JointState"), std::string::npos) << info;
  EXPECT_NE(info.find("/rescuesim_slider"), std::string::npos) << info;

  // a wheel is cmd_vel's: refused, and nothing moves
  auto wheel =
      master.spawn({"rostopic", "pub", "-r", "10", "/joint_command", "sensor_msgs/JointState", "{name: [wheel], velocity: [1.0]}"});
  EXPECT_TRUE(wait_until([&] { return bridge->stats().rejected > 0; }, kPatience)) << wheel->output();
  wheel->interrupt();
  EXPECT_EQ(bridge->stats().received, 0u);

  // the prismatic joint goes where it is told, within its limits
  auto lift_cmd =
      master.spawn({"rostopic", "pub", "-r", "10", "/joint_command", "sensor_msgs/JointState", "{name: [lift], position: [0.15]}"});
  EXPECT_TRUE(wait_until([&] { return std::abs(lift.load() - 0.15) < 1e-3; }, kPatience))
      << "lift at " << lift.load() << " m, target " << lift_target.load() << "\n"
      << lift_cmd->output();
  lift_cmd->interrupt();
  EXPECT_EQ(lift_target.load(), 0.15);
  EXPECT_GT(bridge->stats().received, 0u);
  finish();
}

}  // namespace
}  // namespace rescuesim
