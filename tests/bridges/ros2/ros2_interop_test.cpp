// `rescuesim run --ros2` against ros2_peer, an independent participant built on Fast DDS (the
// middleware of ROS 2's default rmw) from its own IDL: sensor data decodes with the expected
// fields, /cmd_vel drives the robot, the node shows up in ros_discovery_info, bad commands are
// refused. Both processes are pinned to loopback on a domain of their own.

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "bridges/ros2/dds_loopback.h"
#include "support/command.h"
#include "support/dds_domain.h"

extern char** environ;

namespace rescuesim {
namespace {

#ifdef ROS2_PEER_MISSING
TEST(Ros2Interop, Skipped) { GTEST_SKIP() << "ROS 2 interop tests skipped: " << ROS2_PEER_MISSING; }
#else

using testing::slurp;
using testing::temp_dir;
using testing::pin_dds_to_loopback;
using testing::write_text;

/// A 6 m x 4 m room with the robot at (1, 2) m facing +x, and a scenario that leaves it to ROS.
std::filesystem::path write_scenario(const std::filesystem::path& dir, bool cameras) {
  write_text(dir / "room.svg",
             "<svg width=\"6m\" height=\"4m\" viewBox=\"0 0 600 400\">\n"
             "<rect x=\"0\" y=\"0\" width=\"600\" height=\"400\" fill=\"none\" stroke=\"black\" stroke-width=\"10\"/>\n"
             "<circle cx=\"100\" cy=\"200\" r=\"20\" fill=\"green\"/>\n"
             "<line x1=\"100\" y1=\"200\" x2=\"130\" y2=\"200\" stroke=\"green\"/>\n</svg>\n");
  std::string yaml =
      "name: ros2-interop\nseed: 1\nworld:\n  svg: room.svg\nrobots:\n  - name: robot\n    controller: none\n"
      "    sensors:\n      depth_camera: {enabled: false}\n      thermal_camera: {enabled: false}\n";
  if (!cameras) yaml += "      color_camera: {enabled: false}\n";
  write_text(dir / "scenario.yaml", yaml);
  return dir / "scenario.yaml";
}



/// rescuesim in the background, output to files; interrupted (Ctrl-C) and reaped by finish().
class Background {
 public:
  Background(const std::vector<std::string>& args, const std::filesystem::path& out, const std::filesystem::path& err) {
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, argv[0], &fa, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&fa);
  }
  ~Background() { finish(std::chrono::seconds(1)); }
  bool running() const { return pid_ > 0; }
  /// Sends SIGINT and waits up to `grace` for a clean exit (then SIGKILL); the exit code.
  int finish(std::chrono::milliseconds grace) {
    if (pid_ <= 0) return code_;
    ::kill(pid_, SIGINT);
    const auto give_up = std::chrono::steady_clock::now() + grace;
    int status = 0;
    while (::waitpid(pid_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > give_up) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    pid_ = -1;
    code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return code_;
  }

 private:
  pid_t pid_ = -1;
  int code_ = -1;
};

struct Session {
  nlohmann::json report;
  int sim_exit = -1, peer_exit = -1;
  std::string sim_out, sim_err, peer_err;
};

std::string peer_summary(const Session& s) { return s.report.is_discarded() ? "(none)" : s.report.dump(); }

/// Runs rescuesim --ros2 on the scenario and the peer in `mode` beside it.
Session run_with_peer(const std::string& name, const std::string& mode, bool cameras) {
  const auto dir = temp_dir(name);
  const auto scenario = write_scenario(dir, cameras);
  pin_dds_to_loopback(dir);
  const int domain = testing::leased_dds_domain();  // a domain of its own: tests run side by side
  Session s;
  const auto t0 = std::chrono::steady_clock::now();
  {
    // the peer is built from Humble's IDL (24-byte Gids, Range without variance): the run speaks Humble
    Background sim({RESCUESIM_EXE, "run", scenario.string(), "--ros2", "--ros2-distro", "humble", "--ros-domain", std::to_string(domain),
                    "--duration", "40", "--quiet", "--out", (dir / "run").string()},
                   dir / "sim.out", dir / "sim.err");
    EXPECT_TRUE(sim.running());
    const auto peer = testing::run_command(std::string("'") + ROS2_PEER_EXE + "' --domain " + std::to_string(domain) +
                                           " --mode " + mode + " --timeout 25");
    s.peer_exit = peer.exit_code;
    s.peer_err = peer.err;
    s.report = nlohmann::json::parse(peer.out, nullptr, false);
    s.sim_exit = sim.finish(std::chrono::seconds(10));
  }
  s.sim_out = slurp(dir / "sim.out");
  s.sim_err = slurp(dir / "sim.err");
  std::printf("[ %s: %.1f s wall; peer report %s ]\n", name.c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), peer_summary(s).c_str());
  return s;
}


TEST(Ros2Interop, FastDdsPeerReadsSensorsDrivesTheRobotAndSeesTheNode) {
  const Session s = run_with_peer("ros2-drive", "drive", true);
  ASSERT_EQ(s.peer_exit, 0) << "peer: " << s.peer_err << "\nsim: " << s.sim_out << s.sim_err << "\nreport: " << peer_summary(s);
  const auto& r = s.report;
  ASSERT_FALSE(r.is_discarded());
  EXPECT_EQ(s.sim_exit, 0) << s.sim_err;

  // /scan: the rescue robot's 270 degree laser, 541 beams in frame "laser"
  EXPECT_GT(r["scan"]["count"].get<int>(), 0);
  EXPECT_EQ(r["scan"]["ranges"].get<int>(), 541);
  EXPECT_EQ(r["scan"]["frame"], "laser");
  EXPECT_NEAR(r["scan"]["angle_min"].get<double>(), -3 * M_PI / 4, 1e-5);
  EXPECT_NEAR(r["scan"]["angle_increment"].get<double>(), 1.5 * M_PI / 540, 1e-6);
  // /camera/color/image_raw: 640 x 480 rgb8
  // a stream, not a lucky frame (with a 4 MB receive buffer; see docs/ros.md on large messages)
  EXPECT_GE(r["image"]["count"].get<int>(), 5);
  EXPECT_EQ(r["image"]["width"], 640);
  EXPECT_EQ(r["image"]["height"], 480);
  EXPECT_EQ(r["image"]["encoding"], "rgb8");
  EXPECT_EQ(r["image"]["step"], 1920);
  EXPECT_EQ(r["image"]["bytes"], 1920 * 480);
  EXPECT_EQ(r["image"]["frame"], "camera_color_optical_frame");
  // /clock: sim time, only ever increasing
  EXPECT_GT(r["clock"]["count"].get<int>(), 10);
  EXPECT_TRUE(r["clock"]["increasing"].get<bool>());
  EXPECT_GT(r["clock"]["last"].get<double>(), r["clock"]["first"].get<double>());
  // /tf_static, joined seconds after it was published once: kept for late joiners
  EXPECT_EQ(r["tf_static"]["count"], 1);
  EXPECT_GT(r["tf_static"]["transforms"].get<int>(), 5);
  EXPECT_TRUE(r["tf_static"]["laser"].get<bool>());
  // /odom: odom -> base_link
  EXPECT_EQ(r["odom"]["frame"], "odom");
  EXPECT_EQ(r["odom"]["child"], "base_link");

  // /cmd_vel linear.x = 0.3 m/s for 2 s of wall time. Realtime pacing may let sim time run
  // ahead of the wall clock for a moment (catching up after a slow step), so the distance is
  // checked against the speed the robot's pose shows while it cruises, and bounded by the time
  // odometry says passed: up to the 2.5 m/s^2 acceleration limit (0.3^2 / (2 * 2.5) = 0.018 m
  // lost) it may not beat 0.3 m/s, and 2 s of commands must take it well beyond 0.25 m (a
  // loaded machine's realtime run can fall behind the wall clock, so 2 s of commands may cover
  // only some 1.5 s of sim time: the cruise speed above is the precise check)
  const double elapsed = r["odom"]["t1"].get<double>() - r["odom"]["t0"].get<double>();
  const double dx = r["odom"]["dx"].get<double>(), dy = r["odom"]["dy"].get<double>();
  const double cruise_time = r["odom"]["cruise_time"].get<double>(), cruise_dx = r["odom"]["cruise_dx"].get<double>();
  EXPECT_GT(cruise_time, 1.0);
  EXPECT_NEAR(cruise_dx / cruise_time, 0.3, 0.015) << cruise_dx << " m in " << cruise_time << " s";
  EXPECT_GT(dx, 0.25);
  EXPECT_LT(dx, 0.3 * elapsed + 0.01) << "elapsed " << elapsed;
  EXPECT_LT(std::abs(dy), 0.05);
  EXPECT_NEAR(r["odom"]["vx_driving"].get<double>(), 0.3, 0.05);

  // ros_discovery_info: node /rescuesim, its Gids (Humble: 24 bytes) built from DDS GUIDs
  EXPECT_EQ(r["discovery"]["nodes"], nlohmann::json::array({"/rescuesim"}));
  EXPECT_TRUE(r["discovery"]["gid_is_writer_participant"].get<bool>());
  EXPECT_TRUE(r["discovery"]["gid_padding_zero"].get<bool>());
  EXPECT_TRUE(r["discovery"]["scan_writer_listed"].get<bool>());
  EXPECT_GT(r["discovery"]["writers"].get<int>(), 10);
  // cmd_vel (Twist and TwistStamped), head/command, lights; and the request readers of the control
  // services: 20 of the Simulation Interfaces, 3 of the simulate_steps action, 6 parameter services
  EXPECT_EQ(r["discovery"]["readers"], 4 + 20 + 3 + 6);

  EXPECT_NE(s.sim_out.find("bridge ros2:"), std::string::npos) << s.sim_out;
  EXPECT_EQ(s.sim_err.find("rejected"), std::string::npos) << s.sim_err;
}

TEST(Ros2Interop, NanMalformedAndWrongLengthCommandsAreRefusedAndTheRobotStaysPut) {
  const Session s = run_with_peer("ros2-bad", "bad", false);
  ASSERT_EQ(s.peer_exit, 0) << "peer: " << s.peer_err << "\nsim: " << s.sim_out << s.sim_err << "\nreport: " << peer_summary(s);
  const auto& r = s.report;
  EXPECT_EQ(s.sim_exit, 0) << s.sim_err;
  EXPECT_GT(r["commands"].get<int>(), 10);
  EXPECT_LT(std::abs(r["odom"]["dx"].get<double>()), 0.005);
  EXPECT_LT(std::abs(r["odom"]["dy"].get<double>()), 0.005);
  // warned (throttled), counted, and the run went on to its normal end
  EXPECT_NE(s.sim_err.find("rejected a command on /cmd_vel: linear.x is nan"), std::string::npos) << s.sim_err;
  EXPECT_NE(s.sim_err.find("rejected a command on /cmd_vel: malformed message: malformed CDR"), std::string::npos) << s.sim_err;
  EXPECT_NE(s.sim_err.find("rejected a command on /head/command: 2 positions, expected 4"), std::string::npos) << s.sim_err;
  EXPECT_NE(s.sim_out.find("0 commands received"), std::string::npos) << s.sim_out;
  const auto at = s.sim_out.find("commands received, ");
  ASSERT_NE(at, std::string::npos) << s.sim_out;
  EXPECT_GE(std::stoi(s.sim_out.substr(at + 19)), 3 * 10) << s.sim_out;
  EXPECT_NE(s.sim_out.find("stopped: "), std::string::npos) << s.sim_out;
}

#endif

}  // namespace
}  // namespace rescuesim
