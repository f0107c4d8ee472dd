// rescuesim as a ROS 1 node, checked with the real ROS 1 tools: a roscore of the test's own,
// `rescuesim run --ros1` in realtime on a small room, and rostopic / rosbag / rosparam reading
// what it publishes. Expected values come from the room's geometry and the scenario's sensor
// settings (tests/bridges/ros1/ros1_rig.h), not from earlier output.

#include <gtest/gtest.h>

#include <chrono>

#include <future>
#include <semaphore>

#include "bridges/ros1/ros1_rig.h"

namespace rescuesim {
namespace {

using namespace testing;

/// A rospy publisher of "geometry_msgs/Twist" (name and MD5 right, so roscpp connects) whose
/// messages are 3 bytes instead of 48.
const char* kTruncatedTwistPy = R"(import rospy
from geometry_msgs.msg import Twist

class Truncated(Twist):
    def serialize(self, buff):
        buff.write(b"\x01\x02\x03")

rospy.init_node("truncated_twist", anonymous=True)
pub = rospy.Publisher("/cmd_vel", Truncated, queue_size=1)
rate = rospy.Rate(10)
while not rospy.is_shutdown():
    pub.publish(Truncated())
    rate.sleep()
)";

/// A roscore and rescuesim on it, for one test.
class Ros1Run : public ::testing::Test {
 protected:
  void start(const std::string& name, const std::vector<std::string>& args) {
    dir_ = temp_dir("ros1-" + name);
    master_ = std::make_unique<RosMaster>(dir_);
    ASSERT_TRUE(master_->start()) << "roscore did not come up on port " << master_->port();
    ASSERT_TRUE(sim_.start(*master_, dir_, args)) << sim_.output();
  }
  /// One message of `topic` as rostopic prints it (extra options before the topic).
  std::string echo(const std::string& topic, const std::string& options = "") {
    return master_->run("rostopic echo -n 1 " + options + " " + topic, kToolSeconds).out;
  }

  fs::path dir_;
  std::unique_ptr<RosMaster> master_;
  Simulator sim_;
};

TEST(Ros1Bridge, NoMasterIsABadInputErrorNamingTheUri) {
  SKIP_WITHOUT_ROS1();
  const auto dir = temp_dir("ros1-no-master");
  RosMaster nobody(dir);  // never started: its port has no master
  const auto t0 = std::chrono::steady_clock::now();
  const CommandResult r = run_command("env " + nobody.env_prefix() + "timeout 30 '" RESCUESIM_EXE "' run '" + write_room(dir).string() +
                                      "' --ros1 --no-cameras --duration 5 --out '" + (dir / "out").string() + "'");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("ROS 1: no master at " + nobody.uri() + " (ROS_MASTER_URI); start roscore first"), std::string::npos) << r.err;
  EXPECT_LT(seconds, 15.0);  // about 3 s of waiting, not forever
}

TEST_F(Ros1Run, EverySensorTopicCarriesWhatTheScenarioConfigures) {
  SKIP_WITHOUT_ROS1();
  start("echo", {"--duration", "120", "--use-sim-time"});
  // every echo at once (each rostopic is a Python process that takes a while to start)
  const std::vector<std::pair<std::string, std::string>> topics = {
      {"/scan", ""},
      {"/sonar/front_left", ""},
      {"/imu/data", ""},
      {"/odom", ""},
      {"/ground_truth/pose", ""},
      {"/joint_states", ""},
      {"/camera/color/image_raw", "--noarr"},
      {"/camera/color/camera_info", ""},
      {"/camera/depth/image_raw", "--noarr"},
      {"/camera/depth/points", "--noarr"},
      {"/thermal/image_raw", "--noarr"},
      {"/thermal/image_mono8", "--noarr"},
      {"/tf", ""},
      {"/tf_static", ""},
  };
  // the laser's stamps, collected meanwhile: its rate is judged in sim time (on a loaded machine
  // a realtime run falls behind the wall clock, so a wall-clock rate says nothing about the laser)
  auto rate = master_->spawn({"rostopic", "echo", "/scan/header/stamp"});
  // a few echoes at a time (each rostopic is a Python process that takes a while to start)
  std::counting_semaphore<> slots(4);
  std::map<std::string, std::future<std::string>> pending;
  for (const auto& [topic, options] : topics) {
    // init-captures: clang (clang-tidy) before 16 cannot capture a structured binding by name
    pending[topic] = std::async(std::launch::async, [this, &slots, topic = topic, options = options] {
      slots.acquire();
      const std::string out = echo(topic, options);
      slots.release();
      return out;
    });
  }
  // /clock advances: two readings at least 2 s apart (a reading may be older than it looks: a
  // slow starting subscriber reads what waited in its socket, so only the lower bound is sharp)
  auto clock = std::async(std::launch::async, [this] {
    const std::string first = echo("/clock");
    std::this_thread::sleep_for(2s);
    return stamp_of(echo("/clock")) - stamp_of(first);
  });
  auto sim_time = std::async(std::launch::async, [this] { return master_->run("rosparam get /use_sim_time", kToolSeconds).out; });
  std::map<std::string, std::string> got;
  for (auto& [topic, f] : pending) {
    got[topic] = f.get();
    EXPECT_FALSE(got[topic].empty()) << "nothing on " << topic;
  }

  // laser: 180 degrees in 181 beams; straight ahead the east wall's inner face (x = 5.9) seen
  // from the laser at x = 1 + 0.26; sideways the walls at y = 0.1 and 3.9
  const std::string& scan = got["/scan"];
  EXPECT_EQ(field(scan, "frame_id"), "laser");
  const double increment = number(scan, "angle_increment");
  EXPECT_NEAR(increment, M_PI / 180, 1e-6);
  const std::vector<double> ranges = numbers(scan, "ranges");
  ASSERT_EQ(ranges.size(), static_cast<std::size_t>(std::lround(M_PI / increment)) + 1);
  EXPECT_NEAR(ranges[90], 5.9 - 1.26, 0.08);
  EXPECT_NEAR(ranges[0], 1.9, 0.08);
  EXPECT_NEAR(ranges[180], 1.9, 0.08);
  EXPECT_EQ(number(scan, "range_max"), 20.0);

  const std::string& sonar = got["/sonar/front_left"];
  EXPECT_EQ(field(sonar, "frame_id"), "sonar_front_left");
  EXPECT_EQ(field(sonar, "radiation_type"), "0");
  EXPECT_NEAR(number(sonar, "max_range"), 4.0, 1e-6);

  // at rest the IMU feels gravity upward
  const std::string& imu = got["/imu/data"];
  EXPECT_EQ(field(imu, "frame_id"), "imu_link");
  EXPECT_NEAR(number(imu, "z", imu.find("linear_acceleration")), 9.81, 0.5);

  EXPECT_EQ(field(got["/odom"], "frame_id"), "odom");
  EXPECT_EQ(field(got["/odom"], "child_frame_id"), "base_link");
  // ground truth: the robot's start at (1, 2) in map
  const std::string& truth = got["/ground_truth/pose"];
  EXPECT_EQ(field(truth, "frame_id"), "map");
  EXPECT_NEAR(number(truth, "x", truth.find("position")), 1.0, 0.05);
  EXPECT_NEAR(number(truth, "y", truth.find("position")), 2.0, 0.05);

  // the wheels and the head joints, by name
  const std::string& joints = got["/joint_states"];
  for (const char* joint : {"front_left_wheel_joint", "rear_right_wheel_joint", "mast_yaw", "shoulder_pitch", "elbow_pitch", "head_tilt"}) {
    EXPECT_NE(joints.find(std::string("- ") + joint + "\n"), std::string::npos) << joints;
  }
  EXPECT_EQ(numbers(joints, "position").size(), 8u) << joints;

  // cameras at the scenario's sizes; pinhole focal length (w / 2) / tan(hfov / 2)
  const std::string& color = got["/camera/color/image_raw"];
  EXPECT_EQ(field(color, "width"), "160");
  EXPECT_EQ(field(color, "height"), "120");
  EXPECT_EQ(field(color, "encoding"), "rgb8");
  EXPECT_EQ(field(color, "step"), "480");
  const std::vector<double> k = numbers(got["/camera/color/camera_info"], "K");
  ASSERT_EQ(k.size(), 9u) << got["/camera/color/camera_info"];
  EXPECT_NEAR(k[0], 80 / std::tan(35 * M_PI / 180), 0.5);
  EXPECT_NEAR(k[2], 80, 0.6);
  EXPECT_EQ(field(got["/camera/color/camera_info"], "width"), "160");
  EXPECT_EQ(field(got["/camera/color/camera_info"], "frame_id"), field(color, "frame_id"));

  const std::string& depth = got["/camera/depth/image_raw"];
  EXPECT_EQ(field(depth, "encoding"), "32FC1");
  EXPECT_EQ(field(depth, "width"), "80");
  EXPECT_EQ(field(depth, "step"), "320");
  const std::string& points = got["/camera/depth/points"];
  EXPECT_EQ(number(points, "height") * number(points, "width"), 80.0 * 60.0) << points;
  EXPECT_EQ(number(points, "row_step"), number(points, "width") * number(points, "point_step")) << points;

  EXPECT_EQ(field(got["/thermal/image_raw"], "encoding"), "mono16");
  EXPECT_EQ(field(got["/thermal/image_raw"], "step"), "160");
  EXPECT_EQ(field(got["/thermal/image_mono8"], "encoding"), "mono8");
  EXPECT_EQ(field(got["/thermal/image_mono8"], "step"), "80");

  // TF: odometry moves base_link in odom; the static tree places the laser and the cameras
  EXPECT_NE(got["/tf"].find("child_frame_id: \"base_link\""), std::string::npos) << got["/tf"];
  EXPECT_NE(got["/tf"].find("frame_id: \"odom\""), std::string::npos) << got["/tf"];
  const std::string& tf_static = got["/tf_static"];
  EXPECT_NE(tf_static.find("child_frame_id: \"laser\""), std::string::npos) << tf_static;
  EXPECT_NE(tf_static.find("child_frame_id: \"" + field(color, "frame_id") + "\""), std::string::npos) << tf_static;

  EXPECT_GT(clock.get(), 1.0);

  // the laser at 10 Hz of sim time: over at least 5 s of receiving, stamps 0.1 s apart, in
  // order; a subscriber that fell behind may miss some, but never more than a tenth of them
  ASSERT_TRUE(wait_until([&] { return rate->output().find("nsecs") != std::string::npos; }, kPatience)) << rate->output();
  std::this_thread::sleep_for(5s);
  rate->interrupt();
  std::vector<double> stamps;
  const std::string echoed = rate->output();
  for (std::size_t at = echoed.find("secs: "); at != std::string::npos; at = echoed.find("secs: ", echoed.find("---", at))) {
    const std::string one = echoed.substr(at, echoed.find("---", at) - at);
    if (one.find("nsecs") == std::string::npos) break;  // cut off by the interrupt
    stamps.push_back(stamp_of(one));
  }
  ASSERT_GE(stamps.size(), 20u) << echoed;
  for (std::size_t i = 1; i < stamps.size(); ++i) {
    const double gap = stamps[i] - stamps[i - 1];
    ASSERT_GT(gap, 0.0) << "scan " << i << " out of order";
    EXPECT_NEAR(gap / 0.1, std::round(gap / 0.1), 1e-3) << "scan " << i << " off the 10 Hz grid: " << gap << " s";
  }
  const double sim_span = stamps.back() - stamps.front();
  EXPECT_GE(static_cast<double>(stamps.size() - 1), 0.9 * sim_span / 0.1) << "scans over " << sim_span << " s of sim time";

  EXPECT_EQ(sim_time.get(), "true\n");
  EXPECT_TRUE(sim_.running());
  EXPECT_EQ(sim_.interrupt(), 0) << sim_.output();
}

TEST_F(Ros1Run, FlipperCommandsFromRostopicMoveTheTrackedRobotsFlippers) {
  SKIP_WITHOUT_ROS1();
  dir_ = temp_dir("ros1-flippers");
  master_ = std::make_unique<RosMaster>(dir_);
  ASSERT_TRUE(master_->start()) << "roscore did not come up on port " << master_->port();
  write_room(dir_);
  std::string yaml = kRoomYaml;
  yaml.replace(yaml.find("    controller: none"), 0, "    model: tracked_robot\n");
  write_text(dir_ / "tracked.yaml", yaml);
  ASSERT_TRUE(sim_.start(*master_, dir_, dir_ / "tracked.yaml", {"--duration", "120", "--no-cameras"})) << sim_.output();
  const auto flipper = [&](const char* joint) {
    const std::string js = echo("/joint_states");
    // names are listed one per line ("- left_flipper_joint"), positions in one array, in the same order
    const std::vector<double> q = numbers(js, "position");
    int index = 0;
    for (std::size_t at = js.find("name:"); (at = js.find("\n  - ", at)) != std::string::npos && at < js.find("position:"); ++index) {
      at += 5;
      if (js.compare(at, std::string(joint).size(), joint) == 0 && static_cast<std::size_t>(index) < q.size()) {
        return q[static_cast<std::size_t>(index)];
      }
    }
    return std::nan("");
  };
  // a command of the wrong length is refused; two positions move the two flippers
  auto short_cmd = master_->spawn({"rostopic", "pub", "-r", "10", "/flippers/command", "std_msgs/Float64MultiArray", "{data: [0.5]}"});
  EXPECT_TRUE(sim_.says("rejected a command on /flippers/command: 1 positions, expected 2", kPatience)) << sim_.output();
  short_cmd->interrupt();
  EXPECT_NEAR(flipper("left_flipper_joint"), -170 * M_PI / 180, 0.02);  // stowed
  auto cmd = master_->spawn({"rostopic", "pub", "-r", "10", "/flippers/command", "std_msgs/Float64MultiArray", "{data: [-0.5, -0.3]}"});
  // both tips up, in the air: each flipper stands at its own target
  EXPECT_TRUE(wait_until(
      [&] { return std::abs(flipper("left_flipper_joint") + 0.5) < 0.02 && std::abs(flipper("right_flipper_joint") + 0.3) < 0.02; },
      kPatience))
      << echo("/joint_states");
  cmd->interrupt();
  EXPECT_EQ(sim_.interrupt(), 0) << sim_.output();
}

TEST_F(Ros1Run, LightsFromRostopicLightTheDarkRoomForTheColourCamera) {
  SKIP_WITHOUT_ROS1();
  dir_ = temp_dir("ros1-lights");
  master_ = std::make_unique<RosMaster>(dir_);
  ASSERT_TRUE(master_->start()) << "roscore did not come up on port " << master_->port();
  write_room(dir_);
  // the room at night (no daylight, no sun), with a tiny colour camera to read back in text
  std::string yaml = kRoomYaml;
  yaml.replace(yaml.find("  svg_scale: 100\n"), 0, "  ambient_light: 0\n  sun: false\n");
  yaml.replace(yaml.find("{width: 160, height: 120, hfov: 70}"), 35, "{width: 16, height: 12, hfov: 70}");
  write_text(dir_ / "dark.yaml", yaml);
  ASSERT_TRUE(sim_.start(*master_, dir_, dir_ / "dark.yaml", {"--duration", "120"})) << sim_.output();
  const auto brightness = [&] {
    const std::vector<double> px = numbers(echo("/camera/color/image_raw"), "data");
    double sum = 0;
    for (double v : px) sum += v;
    return px.empty() ? -1.0 : sum / static_cast<double>(px.size());
  };
  EXPECT_EQ(brightness(), 0.0);  // black: nothing lights the room
  auto on = master_->spawn({"rostopic", "pub", "-r", "10", "/lights", "std_msgs/Bool", "data: true"});
  EXPECT_TRUE(wait_until([&] { return brightness() > 5.0; }, kPatience)) << brightness();
  on->interrupt();
  auto off = master_->spawn({"rostopic", "pub", "-r", "10", "/lights", "std_msgs/Bool", "data: false"});
  EXPECT_TRUE(wait_until([&] { return brightness() == 0.0; }, kPatience)) << brightness();
  off->interrupt();
  EXPECT_EQ(sim_.interrupt(), 0) << sim_.output();
}

TEST_F(Ros1Run, CmdVelDrivesTheRobotAndBadCommandsAreRefused) {
  SKIP_WITHOUT_ROS1();
  start("drive", {"--duration", "120", "--no-cameras"});
  const auto x_now = [&] {
    const std::string truth = echo("/ground_truth/pose");
    return number(truth, "x", truth.find("position"));
  };
  const auto pub = [&](const std::string& topic, const std::string& type, const std::string& value) {
    return master_->spawn({"rostopic", "pub", "-r", "10", topic, type, value});
  };

  // refused: NaN speeds, a head command of the wrong length, a message of another type on
  // head/command (which cannot connect: ROS 1 checks the MD5), and bytes that claim to be a
  // Twist (name and MD5) but are 3 bytes long
  auto nan = pub("/cmd_vel", "geometry_msgs/Twist", "{linear: {x: .nan}}");
  auto short_head = pub("/head/command", "std_msgs/Float64MultiArray", "{data: [0.5]}");
  auto other_head = pub("/head/command", "std_msgs/String", "hello");
  write_text(dir_ / "truncated_twist.py", kTruncatedTwistPy);
  auto truncated = master_->spawn({"/usr/bin/python3", (dir_ / "truncated_twist.py").string()});
  const double x0 = x_now();
  ASSERT_NEAR(x0, 1.0, 0.05);
  EXPECT_TRUE(sim_.says("rejected a command on /cmd_vel: linear.x is", kPatience)) << sim_.output();
  EXPECT_TRUE(std::regex_search(sim_.output(), std::regex("rejected a command on /cmd_vel: linear.x is -?nan"))) << sim_.output();
  EXPECT_TRUE(sim_.says("rejected a command on /head/command: 1 positions, expected 4", kPatience)) << sim_.output();
  EXPECT_TRUE(sim_.says("rejected a command on /cmd_vel: malformed message: geometry_msgs/Twist: linear.x", kPatience)) << sim_.output();
  nan->interrupt();
  short_head->interrupt();
  truncated->interrupt();
  // cmd_vel takes either velocity type, so another type connects too (once the Twist publishers
  // are gone: one type at a time) and its messages are refused one by one
  auto other = pub("/cmd_vel", "std_msgs/String", "hello");
  EXPECT_TRUE(sim_.says("rejected a command on /cmd_vel: a std_msgs/String message: cmd_vel takes geometry_msgs/Twist or "
                        "geometry_msgs/TwistStamped",
                        kPatience))
      << sim_.output();
  other->interrupt();
  EXPECT_NEAR(x_now(), x0, 0.03) << "the robot moved on refused commands";
  // the String publisher on head/command cannot connect (md5 mismatch): rescuesim says so and goes on
  EXPECT_TRUE(sim_.says("publisher(s) (", kPatience)) << sim_.output();
  EXPECT_TRUE(
      std::regex_search(sim_.output(), std::regex("ROS 1: /head/command has \\d publisher\\(s\\) \\(.*/rostopic_.*\\) but rescuesim is "
                                                  "connected to \\d")))
      << sim_.output();
  other_head->interrupt();
  EXPECT_TRUE(sim_.running());
  // a TwistStamped stamped 100000 s ahead of the simulation is refused too (the drive below
  // shows that cmd_vel connects again once the String publisher is gone)
  auto future = pub("/cmd_vel", "geometry_msgs/TwistStamped", "{header: {stamp: {secs: 100000}}, twist: {linear: {x: 0.3}}}");
  EXPECT_TRUE(sim_.says("rejected a command on /cmd_vel: header.stamp 100000.000 s is ", kPatience)) << sim_.output();
  future->interrupt();

  // 0.3 m/s forward: once it has accelerated, odometry moves at that speed (50 messages = 1 s)
  auto drive = pub("/cmd_vel", "geometry_msgs/Twist", "{linear: {x: 0.3}}");
  const auto speed = [&] {
    const std::string o = echo("/odom", "--noarr");
    return number(o, "x", o.find("linear"));
  };
  ASSERT_TRUE(wait_until([&] { return speed() > 0.25; }, kPatience)) << "never reached 0.3 m/s";
  const std::vector<std::string> odom = messages(master_->run("rostopic echo -n 50 --noarr /odom", kToolSeconds).out);
  ASSERT_GE(odom.size(), 40u);
  const std::string &a = odom.front(), &b = odom.back();
  const double dt = stamp_of(b) - stamp_of(a);
  const double dx = number(b, "x", b.find("position")) - number(a, "x", a.find("position"));
  ASSERT_GT(dt, 0.5) << a << b;
  EXPECT_NEAR(dx / dt, 0.3, 0.03) << "odometry moved " << dx << " m in " << dt << " s";
  std::printf("odometry at cmd_vel 0.3 m/s: %.3f m/s over %.2f s of sim time\n", dx / dt, dt);
  EXPECT_NEAR(number(b, "x", b.find("linear")), 0.3, 0.03) << b;
  drive->interrupt();

  // without commands the robot stops (command timeout 0.5 s); ground truth agrees it went forward
  std::this_thread::sleep_for(1s);
  const std::vector<std::string> still = messages(master_->run("rostopic echo -n 25 /ground_truth/pose", kToolSeconds).out);
  ASSERT_GE(still.size(), 20u);
  const double x1 = number(still.front(), "x"), x2 = number(still.back(), "x");
  EXPECT_NEAR(x2, x1, 0.005) << "still moving after the command timeout";
  EXPECT_GT(x1 - x0, 0.3) << "ground truth moved " << x1 - x0 << " m";

  EXPECT_EQ(sim_.interrupt(), 0) << sim_.output();
  const std::string out = sim_.output();
  const std::regex stats(
      "bridge ros1: (\\d+) messages sent, (\\d+) dropped \\(slow subscribers\\), (\\d+) commands received, (\\d+) rejected");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(out, m, stats)) << out;
  EXPECT_GE(std::stoi(m[3]), 10);  // the 0.3 m/s twists at 10 Hz
  EXPECT_GE(std::stoi(m[4]), 4);   // NaN twists, short head commands, strings and future stamps on cmd_vel
}

TEST_F(Ros1Run, RosbagRecordsEveryTopicWithItsTypeAndRate) {
  SKIP_WITHOUT_ROS1();
  // wall-clock time (s since the epoch, as rosbag stamps) before the simulator is launched
  const double launched = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  start("bag", {"--duration", "120"});
  // nominal rates of the rescue robot's topics (src/robots/rescue_robot.cpp), /clock every 5 ms step
  const std::vector<std::tuple<std::string, std::string, double>> topics = {
      {"/clock", "rosgraph_msgs/Clock", 200},
      {"/tf", "tf2_msgs/TFMessage", 100},  // 50 Hz twice: odom -> base_link, and the moving joints
      {"/tf_static", "tf2_msgs/TFMessage", 0},
      {"/scan", "sensor_msgs/LaserScan", 10},
      {"/sonar/front_left", "sensor_msgs/Range", 10},
      {"/sonar/rear_right", "sensor_msgs/Range", 10},
      {"/imu/data", "sensor_msgs/Imu", 100},
      {"/odom", "nav_msgs/Odometry", 50},
      {"/ground_truth/pose", "geometry_msgs/PoseStamped", 50},
      {"/joint_states", "sensor_msgs/JointState", 20},
      {"/bumper", "rescuesim_msgs/Contacts", 20},
      {"/camera/color/image_raw", "sensor_msgs/Image", 10},
      {"/camera/color/camera_info", "sensor_msgs/CameraInfo", 10},
      {"/camera/depth/image_raw", "sensor_msgs/Image", 10},
      {"/camera/depth/points", "sensor_msgs/PointCloud2", 10},
      {"/thermal/image_raw", "sensor_msgs/Image", 10},
      {"/thermal/image_mono8", "sensor_msgs/Image", 10},
  };
  const fs::path bag = dir_ / "x.bag";
  std::vector<std::string> record = {"rosbag", "record", "-q", "-O", bag.string()};
  for (const auto& [topic, type, rate] : topics) record.push_back(topic);
  // about 6 s once rosbag has started recording; Ctrl-C closes the bag
  auto recorder = master_->spawn(record);
  ASSERT_TRUE(wait_until([&] { return fs::exists(bag.string() + ".active"); }, kPatience)) << recorder->output();
  std::this_thread::sleep_for(6s);
  recorder->interrupt(30s);
  const CommandResult info = master_->run("rosbag info --yaml '" + bag.string() + "'", kToolSeconds);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const double duration = number(info.out, "duration");
  ASSERT_GT(duration, 2.0) << info.out;
  // the sim time the bag covers, from /clock (published every 5 ms step): on a loaded machine a
  // realtime run may fall behind the wall clock, and every topic's rate is a sim-time rate
  const auto clock_at = info.out.find("topic: /clock\n");
  ASSERT_NE(clock_at, std::string::npos) << info.out;
  const double sim_seconds = number(info.out, "messages", clock_at) / 200.0;
  std::printf("rosbag recorded %.2f s of wall time, %.2f s of sim time\n", duration, sim_seconds);
  EXPECT_GT(sim_seconds, 1.0);
  // realtime: the sim clock never runs ahead of the wall clock. Judged from the launch, not over
  // the bag's window: a run that fell behind under load catches up, so within a window it may
  // cover more sim time than wall time. The last /clock in the bag, read with rostopic from the
  // bag itself (-p: receipt time and clock in ns), was received by the bag's end.
  const CommandResult echo = master_->run("rostopic echo -b '" + bag.string() + "' -p /clock | tail -n 1", kToolSeconds);
  ASSERT_EQ(echo.exit_code, 0) << echo.err;
  const auto comma = echo.out.find(',');
  ASSERT_NE(comma, std::string::npos) << echo.out;
  const double last_clock = std::stod(echo.out.substr(comma + 1)) * 1e-9;
  const double bag_end = number(info.out, "end");
  std::printf("last /clock %.3f s sim, received %.3f s after the simulator was launched\n", last_clock, bag_end - launched);
  EXPECT_GT(last_clock, sim_seconds * 0.5);
  EXPECT_LE(last_clock, bag_end - launched + 0.05);
  for (const auto& [topic, type, rate] : topics) {
    const auto at = info.out.find("topic: " + topic + "\n");
    ASSERT_NE(at, std::string::npos) << topic << " missing in\n" << info.out;
    EXPECT_EQ(field(info.out, "type", at), type) << topic;
    const double count = number(info.out, "messages", at);
    if (rate == 0) {
      EXPECT_EQ(count, 1) << topic << " (latched, published once)";
    } else {
      // never more than the rate gives (10 % plus two messages for where the bag starts and
      // ends); fewer by up to 40 %, as rosbag (a Python program) connects to each topic on its
      // own, and on a loaded machine some connections come up a second or more after the first.
      // A topic at half or twice its rate fails either way.
      const double expected = rate * sim_seconds;
      EXPECT_LE(count, 1.1 * expected + 2) << topic;
      EXPECT_GE(count, 0.6 * expected - 2) << topic;
    }
  }
  EXPECT_EQ(sim_.interrupt(), 0) << sim_.output();
}

TEST_F(Ros1Run, TheSimulationOutlivesItsMasterAndRegistersWithTheNextOne) {
  SKIP_WITHOUT_ROS1();
  start("master-loss", {"--duration", "120", "--no-cameras", "--use-sim-time"});
  const std::string before = echo("/scan");
  ASSERT_FALSE(before.empty());
  const auto wall_before = std::chrono::steady_clock::now();
  // a subscriber connected before the outage (laser stamps only)
  auto watcher = master_->spawn({"rostopic", "echo", "/scan/header/stamp"});
  const auto last_stamp = [&] {
    const std::string out = watcher->output();
    const auto at = out.rfind("secs: ", out.rfind("nsecs: "));
    return at == std::string::npos ? -1.0 : std::stod(out.substr(at + 6));
  };
  ASSERT_TRUE(wait_until([&] { return last_stamp() >= 0; }, kPatience)) << watcher->output();

  master_->kill();
  EXPECT_TRUE(sim_.says("ROS 1 master at " + master_->uri() + " lost; still simulating, retrying", 10s)) << sim_.output();
  std::this_thread::sleep_for(1s);
  EXPECT_TRUE(sim_.running());

  ASSERT_TRUE(master_->start());
  EXPECT_TRUE(sim_.says("reconnected", 30s)) << sim_.output();
  // the new master knows the topics, the command subscriptions, the parameter and the latched /tf_static
  auto teleop = master_->spawn({"rostopic", "pub", "-r", "10", "/cmd_vel", "geometry_msgs/Twist", "{}"});
  auto param = std::async(std::launch::async, [&] { return master_->run("rosparam get /use_sim_time", kToolSeconds).out; });
  auto tf_static = std::async(std::launch::async, [&] { return echo("/tf_static"); });
  auto services = std::async(std::launch::async, [&] { return master_->run("rosservice list", kToolSeconds).out; });
  const double wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_before).count();
  const std::string scan = echo("/scan");
  EXPECT_EQ(field(scan, "frame_id"), "laser") << scan;
  EXPECT_NE(tf_static.get().find("child_frame_id: \"laser\""), std::string::npos);
  EXPECT_EQ(param.get(), "true\n");
  const std::string service_list = services.get();
  for (const char* s : {"/reset_simulation", "/pause_physics", "/unpause_physics", "/step_simulation"}) {
    EXPECT_NE(service_list.find(std::string(s) + "\n"), std::string::npos) << s << " not registered again:\n" << service_list;
  }
  // the subscriber from before still receives: data flows between nodes, not through the master
  EXPECT_TRUE(wait_until([&] { return last_stamp() >= std::floor(stamp_of(scan)); }, 20s))
      << "last stamp " << last_stamp() << ", now " << stamp_of(scan);
  watcher->interrupt();

  // and the simulation ran on at its realtime pace all the while
  const double sim_seconds = stamp_of(scan) - stamp_of(before);
  EXPECT_GT(sim_seconds, wall_seconds - 0.5) << "sim time " << sim_seconds << " s over " << wall_seconds << " s of wall time";
  EXPECT_TRUE(sim_.running());
  teleop->interrupt();
  EXPECT_EQ(sim_.interrupt(), 0) << sim_.output();
  std::smatch m;
  const std::string out = sim_.output();
  ASSERT_TRUE(std::regex_search(out, m, std::regex("(\\d+) commands received"))) << out;
  EXPECT_GT(std::stoi(m[1]), 0) << "no cmd_vel arrived through the new master";
}

}  // namespace
}  // namespace rescuesim
