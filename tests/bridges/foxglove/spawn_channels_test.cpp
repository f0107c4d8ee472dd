// Robots spawned and deleted while a Foxglove client is connected (Simulation::add_robot,
// remove_robot; the bridge's Bus layout watcher): a spawned robot's topics are advertised before
// their first message, its latched robot_description and its scans reach a subscriber, a deleted
// robot's channels are unadvertised, a robot of that name spawned again is advertised again,
// and a client channel on a spawned robot's cmd_vel drives the robot of that name at whatever
// index it has now, and is refused once it is gone. The bridge runs in this process on a
// simulation this thread steps; the clients are the reference @foxglove/ws-protocol client.
// Expected counts by hand from the laser's 10 Hz schedule (tests/sim/spawn_test.cpp).

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <thread>

#include "bridges/foxglove/foxglove_bridge.h"
#include "bridges/foxglove/server_rig.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"

namespace rescuesim {
namespace {

using json = nlohmann::json;

/// The last line of a script's output as JSON.
json last_json(const std::string& out) {
  const auto end = out.find_last_not_of('\n');
  const auto start = out.rfind('\n', end);
  const std::size_t from = start == std::string::npos ? 0 : start + 1;
  return json::parse(out.substr(from, end + 1 - from), nullptr, false);
}

/// The built-in robot as SpawnEntity makes it: named, namespaced, placed at (x, y); with a
/// description when one is given (the built-in robot has none), so it offers robot_description.
RobotInstance spawned_robot(const std::string& name, double x, double y, const std::string& description = "") {
  RobotSpec spec = rescue_robot();
  spec.description = description;
  RobotInstance r = place_robot(name, spec, Pose3{Vec3(x, y, 0), Quat::Identity()});
  r.spawned = true;
  r.ns = name;
  return r;
}

/// Waits (wall time, the simulation not stepped) until `ok` or the client ended or 30 s passed.
bool wait_until(const std::function<bool()>& ok, const std::atomic<bool>& done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!ok()) {
    if (done || std::chrono::steady_clock::now() > deadline) return ok();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

/// Steps until the client is connected and something was sent to it.
void step_until_connected(Simulation& sim, Bridge& bridge, const std::atomic<bool>& done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (bridge.stats().sent == 0 && !done && std::chrono::steady_clock::now() < deadline) {
    sim.step();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

class FoxgloveSpawn : public testing::NodeClientTest {};

TEST_F(FoxgloveSpawn, ASpawnedRobotsChannelsAreAdvertisedAndADeletedOnesUnadvertised) {
  const std::string urdf = R"(<robot name="p3at"><link name="base_link"/></robot>)";
  Simulation sim(testing::one_wall_room());
  FoxgloveOptions options;
  options.port = free_local_port();
  ASSERT_GT(options.port, 0);
  auto bridge = make_foxglove_bridge(options);
  bridge->start(sim);
  const auto status_file = testing::temp_dir("fox-spawn") / "status.json";
  const auto status = [&] {
    const json s = json::parse(testing::slurp(status_file), nullptr, false);
    return s.is_object() ? s : json{{"ready", false}, {"scans", 0}, {"unadvertised", false}};
  };
  testing::CommandResult r;
  std::atomic<bool> done = false;
  std::thread client([&] {
    r = testing::node_script("spawn_channels_client.js",
                             "ws://127.0.0.1:" + std::to_string(options.port) + " " + testing::quoted(status_file) + " p3at");
    done = true;
  });
  step_until_connected(sim, *bridge, done);

  // spawned; no step until the client has subscribed to its scan and has its latched
  // description, so it sees every scan
  const SimTime spawned_at = sim.time();
  ASSERT_EQ(sim.add_robot(spawned_robot("p3at", 1.5, -1.5, urdf)), RobotIndex(1));
  EXPECT_TRUE(wait_until([&] { return status()["ready"].get<bool>(); }, done)) << status();
  // 1 s of sim time: its laser is due at once (sampled after the next step, 5 ms on), then on
  // the 0.1 s grid from the spawn: 11 scans
  while (sim.time() < spawned_at + SimTime::from_seconds(1.0)) {
    sim.step();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_TRUE(wait_until([&] { return status()["scans"].get<int>() >= 11; }, done)) << status();
  // deleted: its channels are unadvertised
  sim.remove_robot(RobotIndex(1));
  EXPECT_TRUE(wait_until([&] { return status()["unadvertised"].get<bool>(); }, done)) << status();
  for (int i = 0; i < 40; ++i) sim.step();  // nothing more on its channels
  // and spawned again: advertised again
  ASSERT_EQ(sim.add_robot(spawned_robot("p3at", 1.5, -1.5, urdf)), RobotIndex(1));
  client.join();
  bridge->stop();

  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const json d = last_json(r.out);
  ASSERT_TRUE(d.is_object()) << r.out;
  EXPECT_TRUE(d["errors"].empty()) << d["errors"];
  const auto& first = d["channelsAtConnect"];
  EXPECT_EQ(std::find(first.begin(), first.end(), "/p3at/scan"), first.end());
  // the spawned robot's channels, advertised once each, all under /p3at
  std::map<std::string, std::uint32_t> advertised;
  for (const auto& c : d["advertised"]) {
    const auto topic = c["topic"].get<std::string>();
    EXPECT_EQ(topic.rfind("/p3at/", 0), 0u) << topic;
    EXPECT_EQ(advertised.count(topic), 0u) << topic << " advertised twice";
    advertised[topic] = c["id"].get<std::uint32_t>();
    if (topic == "/p3at/scan") {
      EXPECT_EQ(c["schemaName"], "sensor_msgs/msg/LaserScan");
    }
    if (topic == "/p3at/robot_description") {
      EXPECT_EQ(c["schemaName"], "std_msgs/msg/String");
    }
  }
  ASSERT_TRUE(advertised.count("/p3at/scan"));
  ASSERT_TRUE(advertised.count("/p3at/robot_description"));
  EXPECT_TRUE(advertised.count("/p3at/cmd_vel") == 0);  // a command topic: clients publish it
  EXPECT_EQ(d["description"], urdf);
  // every scan, stamped on the laser's schedule from the spawn
  const auto& stamps = d["scanStamps"];
  ASSERT_EQ(stamps.size(), 11u);
  EXPECT_EQ(stamps[0].get<std::int64_t>(), spawned_at.ns + 5'000'000);
  for (std::size_t i = 1; i < stamps.size(); ++i) {
    EXPECT_EQ(stamps[i].get<std::int64_t>(), spawned_at.ns + static_cast<std::int64_t>(i) * 100'000'000) << i;
  }
  // every channel of the deleted robot unadvertised, nothing else; nothing after that
  std::set<std::uint32_t> unadvertised;
  for (const auto& id : d["unadvertised"]) unadvertised.insert(id.get<std::uint32_t>());
  std::set<std::uint32_t> ids;
  for (const auto& [topic, id] : advertised) ids.insert(id);
  EXPECT_EQ(unadvertised, ids);
  EXPECT_EQ(d["scansAfterUnadvertise"], 0);
  // spawned again: its channels are advertised again, all of them
  std::set<std::string> again(d["readvertised"].begin(), d["readvertised"].end());
  std::set<std::string> before;
  for (const auto& [topic, id] : advertised) before.insert(topic);
  EXPECT_EQ(again, before);
}

TEST_F(FoxgloveSpawn, CmdVelOfASpawnedRobotFollowsItsIndexAndIsRefusedOnceItIsDeleted) {
  Simulation sim(testing::one_wall_room());
  FoxgloveOptions options;
  options.port = free_local_port();
  ASSERT_GT(options.port, 0);
  auto bridge = make_foxglove_bridge(options);
  bridge->start(sim);
  testing::CommandResult r;
  std::atomic<bool> done = false;
  std::thread client([&] {
    r = testing::node_script("spawn_command_client.js", "ws://127.0.0.1:" + std::to_string(options.port));
    done = true;
  });
  step_until_connected(sim, *bridge, done);
  const auto cmd_x = [&](std::size_t robot) { return sim.state().robots[robot].cmd_linear.x(); };

  // a (index 1), then b (index 2): the client drives b at 0.25 m/s once /b/scan is advertised
  ASSERT_EQ(sim.add_robot(spawned_robot("a", -1.5, -1.5)), RobotIndex(1));
  ASSERT_EQ(sim.add_robot(spawned_robot("b", 1.5, -1.5)), RobotIndex(2));
  ASSERT_TRUE(sim.wait_for_velocity_commands(1, std::chrono::seconds(30)));
  sim.step();
  EXPECT_EQ(cmd_x(2), 0.25);
  EXPECT_EQ(cmd_x(1), 0.0);
  EXPECT_EQ(cmd_x(0), 0.0);
  // a deleted: b is robot 1 now, and the client's /b/cmd_vel channel goes there
  sim.remove_robot(RobotIndex(1));
  ASSERT_TRUE(sim.wait_for_velocity_commands(2, std::chrono::seconds(30)));
  sim.step();
  EXPECT_EQ(cmd_x(1), 0.5);
  EXPECT_EQ(cmd_x(0), 0.0);
  // b deleted: its cmd_vel is refused
  sim.remove_robot(RobotIndex(1));
  client.join();
  bridge->stop();

  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const json d = last_json(r.out);
  ASSERT_TRUE(d.is_object()) << r.out;
  EXPECT_TRUE(d["errors"].empty()) << d["errors"];
  ASSERT_EQ(d["refusals"].size(), 1u) << d;
  const std::string refusal = d["refusals"][0]["message"];
  EXPECT_NE(refusal.find("/b/cmd_vel"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("deleted"), std::string::npos) << refusal;
  EXPECT_EQ(sim.velocity_commands(), 2u);
  EXPECT_EQ(sim.state().robots.size(), 1u);
  EXPECT_EQ(cmd_x(0), 0.0);
  const BridgeStats s = bridge->stats();
  EXPECT_EQ(s.received, 2u);
  EXPECT_EQ(s.rejected, 1u);
}

}  // namespace
}  // namespace rescuesim
