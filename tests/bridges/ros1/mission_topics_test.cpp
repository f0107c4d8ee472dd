// A mission's topics over ROS 1 with the real tools: `rostopic pub` of a victim report
// (geometry_msgs/PoseStamped on /rescue/report), a datagram request and a relay drop
// (std_msgs/String), answered by the mission in the simulation; the latched /rescue/score read
// back with `rostopic echo`. The bridge runs in this process on its own roscore.

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <thread>

#include <nlohmann/json.hpp>

#include "bridges/ros1/ros1_bridge.h"
#include "bridges/ros1/ros1_rig.h"
#include "mission/mission.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"

namespace rescuesim {
namespace {

using namespace testing;

/// One robot "robot" at the origin facing +x, a victim "v1" at (3, 0), a 10 m square floor.
World victim_world() {
  WorldSpec s;
  s.name = "mission_topics";
  s.materials = default_materials();
  s.floor_min = {-5, -5};
  s.floor_max = {5, 5};
  s.robots.push_back(RobotPlacement{});
  VictimSpec v;
  v.name = "v1";
  v.pose = {3, 0, 0};
  s.victims.push_back(v);
  return compile_world(s, builtin_models());
}

TEST(Ros1MissionTopics, ReportsDatagramsAndRelaysFromRostopicPub) {
  SKIP_WITHOUT_ROS1();
  const fs::path dir = temp_dir("ros1-mission-topics");
  RosMaster master(dir);
  ASSERT_TRUE(master.start()) << "roscore did not come up on port " << master.port();
  for (const auto& [k, v] : master.env()) ::setenv(k.c_str(), v.c_str(), 1);

  Simulation sim(victim_world());
  Mission mission(MissionSpec{}, sim);  // ideal radio, RoboCup rules (1.5 m, −0.5 per false report)
  const Vec3 victim = sim.world().victims[0].centre;
  std::mutex mutex;
  std::vector<nlohmann::json> answers, results;  // written on the stepping thread's Bus callbacks
  sim.bus().subscribe("/rescue/report_result", [&](const Topic&, const msg::Message& m) {
    std::lock_guard lock(mutex);
    answers.push_back(nlohmann::json::parse(std::get<msg::String>(m).data));
  });
  sim.bus().subscribe("/rescue/comms/result", [&](const Topic&, const msg::Message& m) {
    std::lock_guard lock(mutex);
    results.push_back(nlohmann::json::parse(std::get<msg::String>(m).data));
  });
  Ros1Options options;
  options.node_name = "rescuesim_mission";
  auto bridge = make_ros1_bridge(options);
  bridge->start(sim);
  std::atomic<bool> stop{false};
  std::thread stepper([&] {
    while (!stop.load()) {
      sim.step();
      mission.after_step();
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  });
  const auto count = [&](std::vector<nlohmann::json>& v) {
    std::lock_guard lock(mutex);
    return v.size();
  };

  // the topics are there with the types a ROS user publishes
  const std::string info = master.run("rostopic info /rescue/report", kToolSeconds).out;
  EXPECT_NE(info.find("Type: geometry_msgs/PoseStamped"), std::string::npos) << info;

  // a report 1 m from the victim (0.6, 0.8) in the map frame: accepted, +1
  const std::string report = "rostopic pub -1 /rescue/report geometry_msgs/PoseStamped \"{header: {frame_id: map}, pose: {position: {x: " +
                             std::to_string(victim.x() + 0.6) + ", y: " + std::to_string(victim.y() + 0.8) +
                             ", z: " + std::to_string(victim.z()) + "}}}\"";
  const CommandResult pub = master.run(report, kToolSeconds);
  EXPECT_EQ(pub.exit_code, 0) << pub.err;
  ASSERT_TRUE(wait_until([&] { return count(answers) >= 1; }, kPatience)) << "no answer to the report";

  // a datagram to the base and a relay drop
  EXPECT_EQ(
      master
          .run("rostopic pub -1 /rescue/comms/send std_msgs/String \"data: '{\\\"to\\\": \\\"base\\\", \\\"text\\\": \\\"v1 at 3,0\\\"}'\"",
               kToolSeconds)
          .exit_code,
      0);
  EXPECT_EQ(master.run("rostopic pub -1 /rescue/drop_relay std_msgs/String \"data: ''\"", kToolSeconds).exit_code, 0);
  ASSERT_TRUE(wait_until([&] { return count(results) >= 2; }, kPatience)) << "no answers to the send and the relay drop";

  // the latched score, read back over ROS 1
  // (rostopic prints a long string as YAML folded with an escaped line break: unfold it)
  const std::string score =
      std::regex_replace(master.run("rostopic echo -n 1 /rescue/score", kToolSeconds).out, std::regex(R"(\\\n\s*)"), "");
  stop = true;
  stepper.join();
  bridge->stop();

  ASSERT_EQ(answers.size(), 1u);
  EXPECT_EQ(answers[0]["outcome"], "accepted");
  EXPECT_NEAR(answers[0]["distance"].get<double>(), 1.0, 1e-5);  // (coordinates went as text with 6 decimals)
  EXPECT_EQ(mission.referee().score(), 1.0);
  ASSERT_EQ(results.size(), 2u);
  // (rostopic pub -1 latches and waits for subscribers, so the order is the order of the commands)
  EXPECT_EQ(results[0]["request"], "send");
  EXPECT_EQ(results[0]["accepted"], true) << results[0];
  EXPECT_EQ(results[0]["bytes"], 9);
  EXPECT_EQ(results[1]["request"], "drop_relay");
  EXPECT_EQ(results[1]["accepted"], true) << results[1];
  EXPECT_EQ(results[1]["relays_left"], 11);
  EXPECT_EQ(mission.network().inbox(mission.base_nodes()[0]).size(), 1u);
  // (a JSON text inside rostopic's YAML: quotes come escaped or not, as its printer likes)
  EXPECT_TRUE(std::regex_search(score, std::regex(R"(score\\?["']?:\s*1\.0)"))) << score;
  EXPECT_EQ(bridge->stats().rejected, 0u);
}

}  // namespace
}  // namespace rescuesim
