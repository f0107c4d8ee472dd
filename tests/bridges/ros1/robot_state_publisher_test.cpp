// The TF tree of a URDF robot over ROS 1 matches what Debian's robot_state_publisher computes
// from the same URDF (the /robot_description parameter) and the simulator's /joint_states: a
// real roscore, the real robot_state_publisher node (its output remapped to /rsp/tf and
// /rsp/tf_static), and a rospy node comparing every transform it publishes with ours.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "bridges/ros1/ros1_rig.h"

namespace rescuesim {
namespace {

using namespace testing;

constexpr const char* kRobotStatePublisher = "/usr/lib/robot_state_publisher/robot_state_publisher";

/// Collects the last transform of every child frame on /tf + /tf_static (ours) and on
/// /rsp/tf + /rsp/tf_static (robot_state_publisher's), until robot_state_publisher has given
/// `argv[2]` frames and ours has them too, then writes their differences as JSON to argv[1].
const char* kCompareTfPy = R"(import json, math, sys, time
import rospy
from tf2_msgs.msg import TFMessage

rospy.init_node("tf_compare", anonymous=True)
ours, theirs = {}, {}
def keep(store):
    def callback(msg):
        for t in msg.transforms:
            store[t.child_frame_id] = (t.header.frame_id, t.transform)
    return callback
for topic, store in (("/tf", ours), ("/tf_static", ours), ("/rsp/tf", theirs), ("/rsp/tf_static", theirs)):
    rospy.Subscriber(topic, TFMessage, keep(store))
want = int(sys.argv[2])
deadline = time.time() + 90
while time.time() < deadline and not (len(theirs) >= want and all(c in ours for c in theirs)):
    time.sleep(0.1)
time.sleep(1.0)
out = {}
for child, (parent, t) in sorted(theirs.items()):
    entry = {"parent": parent}
    if child in ours:
        our_parent, u = ours[child]
        entry["our_parent"] = our_parent
        entry["translation_error"] = math.sqrt(sum((getattr(t.translation, a) - getattr(u.translation, a)) ** 2 for a in "xyz"))
        dot = abs(sum(getattr(t.rotation, a) * getattr(u.rotation, a) for a in "xyzw"))
        entry["rotation_error"] = 2 * math.acos(min(1.0, dot))
        entry["rotation_w"] = u.rotation.w
    out[child] = entry
with open(sys.argv[1], "w") as f:
    json.dump(out, f)
)";

TEST(Ros1RobotStatePublisher, TfMatchesRobotStatePublisherOnTheSameUrdfAndJointStates) {
  const std::string missing = ros1_tools_missing();
  if (!missing.empty()) GTEST_SKIP() << missing;
  if (!fs::exists(kRobotStatePublisher)) {
    GTEST_SKIP() << kRobotStatePublisher << " is not installed (Debian package ros-robot-state-publisher)";
  }
  const fs::path dir = temp_dir("ros1-rsp");
  const fs::path yaml = write_turtlebot3(dir, "ros1_rsp");
  write_text(dir / "compare_tf.py", kCompareTfPy);

  RosMaster master(dir);
  ASSERT_TRUE(master.start()) << "roscore did not come up on port " << master.port();
  Simulator sim;
  ASSERT_TRUE(sim.start(master, dir, yaml, {"--duration", "300", "--no-cameras"})) << sim.output();

  // turn the wheels away from their zero position, then let the robot stand (cmd_vel times out)
  auto drive = master.spawn({"rostopic", "pub", "-r", "10", "/cmd_vel", "geometry_msgs/Twist", "{linear: {x: 0.1}}"});
  std::this_thread::sleep_for(std::chrono::seconds(4));
  drive->interrupt();
  std::this_thread::sleep_for(std::chrono::seconds(1));

  // robot_state_publisher reads /robot_description (the parameter) and our /joint_states
  auto rsp = master.spawn({kRobotStatePublisher, "/tf:=/rsp/tf", "/tf_static:=/rsp/tf_static"});
  // base_link, caster_back_link, imu_link, base_scan (fixed) and the two wheels (moving)
  const CommandResult r =
      master.run("/usr/bin/python3 '" + (dir / "compare_tf.py").string() + "' '" + (dir / "tf.json").string() + "' 6", 120);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err << "\nrobot_state_publisher:\n" << rsp->output();
  const auto frames = nlohmann::json::parse(slurp(dir / "tf.json"));
  ASSERT_EQ(frames.size(), 6u) << frames.dump(2) << "\nrobot_state_publisher:\n" << rsp->output();
  for (const char* child : {"base_link", "wheel_left_link", "wheel_right_link", "caster_back_link", "imu_link", "base_scan"}) {
    ASSERT_TRUE(frames.contains(child)) << child << " missing from robot_state_publisher's output: " << frames.dump(2);
    const auto& f = frames[child];
    ASSERT_TRUE(f.contains("our_parent")) << child << " is not on rescuesim's /tf or /tf_static";
    EXPECT_EQ(f["our_parent"], f["parent"]) << child;
    EXPECT_LT(f["translation_error"].get<double>(), 1e-5) << child << ": " << f.dump();
    EXPECT_LT(f["rotation_error"].get<double>(), 1e-4) << child << ": " << f.dump();
  }
  // the wheels really turned (at zero, the wheel frame is the joint origin, roll -1.57: w = cos(0.785) = 0.707)
  EXPECT_GT(std::abs(frames["wheel_left_link"]["rotation_w"].get<double>() - std::cos(0.785)), 0.01) << frames.dump(2);
  rsp->interrupt();
  EXPECT_EQ(sim.interrupt(), 0) << sim.output();
}

}  // namespace
}  // namespace rescuesim
