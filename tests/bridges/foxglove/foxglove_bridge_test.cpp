// `rescuesim run --foxglove` as Foxglove meets it: the reference client (@foxglove/ws-protocol
// over `ws`, CDR decoded by @foxglove/rosmsg2-serialization) sees the server info, every Bus
// topic advertised with its ROS 2 schema, decodable laser and camera messages stamped with sim
// time, the scene, and drives the robot through /cmd_vel, and a URDF-like robot's joints through
// joint_command. Misbehaving clients get status errors while the others are still served, and a
// client that stops reading costs bounded memory.
// Expected values come from the scenario (tests/bridges/foxglove/server_rig.h), by hand.

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <cmath>
#include <regex>
#include <sstream>
#include <thread>

#include "bridges/foxglove/foxglove_bridge.h"
#include "bridges/foxglove/server_rig.h"
#include "import/scenario/scenario.h"
#include "mission/mission.h"
#include "msgs/serialize.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "sim/slider_robot.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using json = nlohmann::json;
using testing::Background;

/// The topics the simulation of a scenario puts on its Bus.
std::vector<Topic> bus_topics(const std::filesystem::path& yaml) {
  const ModelMap models = builtin_models();
  const Scenario s = load_scenario(yaml, models);
  const WorldSpec spec = build_world(s);
  Simulation sim(compile_scenario(s, spec, models));
  return sim.bus().topics();
}

/// The last line of a script's output as JSON.
json last_json(const std::string& out) {
  const auto end = out.find_last_not_of('\n');
  const auto start = out.rfind('\n', end);
  return json::parse(out.substr(start == std::string::npos ? 0 : start + 1, end + 1 - (start == std::string::npos ? 0 : start + 1)));
}

/// The "bridge foxglove: ..." line of a run's output, as numbers.
struct BridgeLine {
  long sent = -1, dropped = -1, received = -1, rejected = -1;
};
BridgeLine bridge_line(const std::string& out) {
  std::smatch m;
  BridgeLine b;
  const std::regex re(
      R"(bridge foxglove: (\d+) messages sent, (\d+) dropped \(slow subscribers\), (\d+) commands received, (\d+) rejected)");
  if (std::regex_search(out, m, re)) b = {std::stol(m[1]), std::stol(m[2]), std::stol(m[3]), std::stol(m[4])};
  return b;
}

class FoxgloveServer : public testing::NodeClientTest {};

TEST_F(FoxgloveServer, ClientDecodesTopicsAndDrivesTheRobot) {
  const auto dir = testing::temp_dir("fox-stream");
  const auto yaml = testing::write_room(dir);
  // no --duration: with --foxglove a run is live (realtime, controllers off) until Ctrl-C
  Background sim(dir, "run room.yaml --foxglove=0 --out out");
  ASSERT_GT(sim.port(), 0) << sim.err();
  const auto r = testing::node_script("stream_client.js", sim.url() + " 2 0.3");
  sim.signal(SIGINT);
  ASSERT_EQ(sim.wait(20), 0) << sim.out() << sim.err();
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const json d = last_json(r.out);
  EXPECT_TRUE(d["errors"].empty()) << d["errors"];
  EXPECT_TRUE(d["statuses"].empty()) << d["statuses"];

  // live run: realtime until Ctrl-C, controllers off, stopped cleanly by SIGINT
  const std::string out = sim.out();
  EXPECT_NE(out.find("realtime, until Ctrl-C"), std::string::npos) << out;
  EXPECT_NE(out.find("controllers   off"), std::string::npos) << out;
  EXPECT_NE(out.find("stopped: interrupted"), std::string::npos) << out;
  const BridgeLine b = bridge_line(out);
  EXPECT_GT(b.sent, 0) << out;
  EXPECT_GT(b.received, 10) << out;  // 20 Hz of cmd_vel for 2 s
  EXPECT_EQ(b.rejected, 0) << out;

  // server info as the issue asks
  EXPECT_EQ(d["serverInfo"]["name"], "rescuesim");
  EXPECT_EQ(d["serverInfo"]["supportedEncodings"], json({"cdr", "json"}));
  const auto& caps = d["serverInfo"]["capabilities"];
  EXPECT_NE(std::find(caps.begin(), caps.end(), "time"), caps.end());
  EXPECT_NE(std::find(caps.begin(), caps.end(), "clientPublish"), caps.end());

  // one cdr channel per Bus topic with its ROS 2 type, plus the json scene
  const std::vector<Topic> topics = bus_topics(yaml);
  ASSERT_EQ(d["channels"].size(), topics.size() + 1);
  for (const Topic& t : topics) {
    const auto c = std::find_if(d["channels"].begin(), d["channels"].end(), [&](const json& c) { return c["topic"] == t.name; });
    ASSERT_NE(c, d["channels"].end()) << t.name;
    EXPECT_EQ((*c)["encoding"], "cdr") << t.name;
    EXPECT_EQ((*c)["schemaEncoding"], "ros2msg") << t.name;
    EXPECT_EQ((*c)["schemaName"], msg::find_type(t.type)->ros2_name) << t.name;
  }
  const auto scene = std::find_if(d["channels"].begin(), d["channels"].end(), [](const json& c) { return c["topic"] == "/scene"; });
  ASSERT_NE(scene, d["channels"].end());
  EXPECT_EQ((*scene)["encoding"], "json");
  EXPECT_EQ((*scene)["schemaName"], "foxglove.SceneUpdate");
  EXPECT_EQ((*scene)["schemaEncoding"], "jsonschema");

  // the laser: 180 degrees in 181 beams, 1 degree apart; straight ahead the east wall's inner
  // face at x = 4.95 m seen from the laser at x = 1.0 + 0.26 m
  const json& scan = d["scan"];
  ASSERT_TRUE(scan.is_object());
  EXPECT_EQ(scan["frame_id"], "laser");
  const double fov = scan["angle_max"].get<double>() - scan["angle_min"].get<double>();
  EXPECT_NEAR(fov, M_PI, 1e-6);
  EXPECT_NEAR(scan["angle_increment"].get<double>(), M_PI / 180, 1e-6);
  EXPECT_EQ(scan["count"], std::lround(fov / scan["angle_increment"].get<double>()) + 1);
  EXPECT_EQ(scan["count"], 181);
  EXPECT_NEAR(scan["ahead"].get<double>(), 4.95 - 1.26, 0.05);
  EXPECT_EQ(scan["trailing"], false);
  // stamps are sim time; a message goes out when it is published, at or after its stamp
  EXPECT_GT(scan["stamp"].get<double>(), 0);
  EXPECT_GE(scan["receive"].get<double>(), scan["stamp"].get<double>());

  // the colour camera: the rescue robot's 640 x 480 rgb8 in its optical frame
  const json& image = d["image"];
  ASSERT_TRUE(image.is_object());
  EXPECT_EQ(image["width"], 640);
  EXPECT_EQ(image["height"], 480);
  EXPECT_EQ(image["encoding"], "rgb8");
  EXPECT_EQ(image["step"], 640 * 3);
  EXPECT_EQ(image["bytes"], 640 * 480 * 3);
  EXPECT_EQ(image["frame_id"], "camera_color_optical_frame");
  EXPECT_GE(image["receive"].get<double>(), image["stamp"].get<double>());

  // time messages: sim time, monotonic
  EXPECT_GT(d["times"]["count"].get<int>(), 20);
  EXPECT_TRUE(d["times"]["monotonic"].get<bool>());
  EXPECT_GT(d["times"]["last"].get<double>(), d["times"]["first"].get<double>() + 2e9);

  // the scene: walls as cubes in the odom frame (the robot starts at (1, 1.5)): the north wall,
  // 5 m + 0.1 m long, centred at world (2.5, 3) = odom (1.5, 1.5)
  const json& sc = d["scene"];
  ASSERT_TRUE(sc.is_object());
  std::map<std::string, json> entities;
  for (const auto& e : sc["entities"]) entities[e["id"]] = e;
  for (const char* id : {"floor", "walls", "raised_areas", "victim/alice", "rubble", "victim_labels", "robot/robot/base_link"}) {
    EXPECT_TRUE(entities.count(id)) << id;
  }
  EXPECT_EQ(entities["walls"]["frame_id"], "odom");
  ASSERT_EQ(entities["walls"]["cubes"].size(), 4u);
  bool north = false;
  for (const auto& c : entities["walls"]["cubes"]) {
    if (std::abs(c["pose"]["position"]["y"].get<double>() - 1.5) < 0.01) {
      north = true;
      EXPECT_NEAR(c["pose"]["position"]["x"].get<double>(), 1.5, 0.01);
      EXPECT_NEAR(c["size"]["x"].get<double>(), 5.1, 0.01);
      EXPECT_NEAR(c["size"]["y"].get<double>(), 0.1, 1e-6);
      EXPECT_NEAR(c["size"]["z"].get<double>(), 1.0, 1e-6);
    }
  }
  EXPECT_TRUE(north) << entities["walls"];
  EXPECT_EQ(entities["robot/robot/base_link"]["frame_id"], "base_link");
  EXPECT_EQ(entities["robot/robot/base_link"]["frame_locked"], true);

  // teleop: 0.3 m/s on /cmd_vel; odometry (in sim time) shows x growing at 0.3 m/s once the
  // drive has accelerated (2.5 m/s^2: 0.12 s), and stopping after the commands stop
  std::vector<std::pair<double, double>> moving;  // (t, x) while at speed
  for (const auto& o : d["odom"]) {
    EXPECT_EQ(o["frame_id"], "odom");
    EXPECT_EQ(o["child"], "base_link");
    if (o["v"].get<double>() > 0.28) moving.emplace_back(o["stamp"].get<double>() * 1e-9, o["x"].get<double>());
  }
  ASSERT_GE(moving.size(), 20u) << d["odom"].size() << " odometry messages";
  const double span = moving.back().first - moving.front().first;
  ASSERT_GT(span, 1.0);
  EXPECT_NEAR((moving.back().second - moving.front().second) / span, 0.3, 0.03);
  const json& last = d["odom"].back();
  const double drive_time = (d["drive"]["end_time"].get<double>() - d["drive"]["start_time"].get<double>()) * 1e-9;
  EXPECT_GT(last["x"].get<double>(), 0.3 * drive_time - 0.1);
  EXPECT_LT(last["x"].get<double>(), 0.3 * (drive_time + 0.5) + 0.1);  // + at most the 0.5 s command timeout
  EXPECT_NEAR(last["y"].get<double>(), 0.0, 0.05);
}

TEST_F(FoxgloveServer, BadClientsGetStatusErrorsAndSlowOnesLoseFramesNotMemory) {
  const auto dir = testing::temp_dir("fox-abuse");
  testing::write_room(dir);
  Background sim(dir, "run room.yaml --foxglove=0 --duration 12 --out out");
  ASSERT_GT(sim.port(), 0) << sim.err();
  // memory, sampled while clients misbehave and one stops reading the camera streams
  std::atomic<bool> sampling = true;
  std::vector<long> rss;
  std::thread sampler([&] {
    while (sampling) {
      if (const long kb = sim.rss_kb(); kb > 0) rss.push_back(kb);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  const auto r = testing::node_script("abuse_client.js", sim.url() + " 6");
  const int code = sim.wait(30);
  sampling = false;
  sampler.join();
  ASSERT_EQ(code, 0) << sim.out() << sim.err();  // never crashed
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const json d = last_json(r.out);
  EXPECT_TRUE(d["errors"].empty()) << d["errors"];

  // handshake: the subprotocol is required
  EXPECT_EQ(d["refusals"]["wrong"]["status"], 400) << d["refusals"];
  EXPECT_NE(d["refusals"]["wrong"]["body"].get<std::string>().find("foxglove.websocket.v1"), std::string::npos);
  EXPECT_EQ(d["refusals"]["none"]["status"], 400) << d["refusals"];
  EXPECT_EQ(d["refusals"]["right"]["status"], 101) << d["refusals"];
  EXPECT_EQ(d["refusals"]["right"]["protocol"], "foxglove.websocket.v1");

  // every bad frame answered with a status error that says what was wrong
  const std::map<std::string, std::string> expected = {
      {"garbage text", "malformed JSON"},
      {"not an object", "JSON object"},
      {"unknown op", "unknown op 'frobnicate'"},
      {"unsupported op", "not supported"},
      {"bad subscribe field", "channelId"},
      {"unknown channel subscribe", "unknown channel id 99999"},
      {"unknown subscription", "unknown subscription id 42"},
      {"empty binary", "empty binary"},
      {"short binary", "at least 5 bytes"},
      {"unknown opcode", "0x07"},
      {"unknown client channel", "unknown channel id 77"},
      {"oversize text", "exceeds the limit of 1048576 bytes"},
      {"oversize binary", "exceeds the limit of 1048576 bytes"},
      {"advertise foreign topic", "does not take this topic"},
      {"advertise wrong schema", "does not match geometry_msgs/msg/Twist"},
      {"advertise bad encoding", "'protobuf' is not supported"},
      {"nan twist", "linear.x is nan"},
      {"inf twist", "angular.z is inf"},
      {"truncated cdr twist", "geometry_msgs/msg/Twist"},
      {"json twist not json", "not valid JSON"},
      {"json twist wrong type", "linear.x: expected a number"},
      {"head wrong size", "1 positions, expected 4"},
      {"head non-number", "data[1] (shoulder_pitch) is nan (positions must be finite)"},  // JSON's null is NaN, as to_json writes it
  };
  ASSERT_EQ(d["replies"].size(), expected.size()) << d["replies"];
  for (const auto& reply : d["replies"]) {
    const std::string label = reply["label"];
    EXPECT_EQ(reply["level"], 2) << label << ": " << reply["message"];
    ASSERT_TRUE(expected.count(label)) << label;
    EXPECT_NE(reply["message"].get<std::string>().find(expected.at(label)), std::string::npos) << label << ": " << reply["message"];
  }
  // at most 16 clients: with three open, 13 of 20 more are let in, the others refused (HTTP 503)
  EXPECT_EQ(d["crowd"]["accepted"], 13) << d["crowd"];
  EXPECT_EQ(d["crowd"]["refused"], 7) << d["crowd"];
  // ... and the connection still works afterwards
  EXPECT_TRUE(d["afterAbuse"]["open"].get<bool>());
  EXPECT_GT(d["afterAbuse"]["messages"].get<int>(), 2);

  // the well-behaved client got /scan (10 Hz) all along
  const auto& scans = d["watcher"]["scans"];
  ASSERT_GT(scans.size(), 40u);
  double gap = 0;
  for (std::size_t i = 1; i < scans.size(); ++i) gap = std::max(gap, scans[i].get<double>() - scans[i - 1].get<double>());
  EXPECT_LT(gap, 1000.0) << "ms without a scan";

  // the slow client: warned, frames dropped (counted in the run's bridge line), memory bounded
  EXPECT_FALSE(d["slow"]["warnings"].empty());
  EXPECT_NE(d["slow"]["warnings"][0].get<std::string>().find("dropped"), std::string::npos);
  const BridgeLine b = bridge_line(sim.out());
  EXPECT_GT(b.dropped, 0) << sim.out();
  EXPECT_EQ(b.rejected, 12) << sim.out();  // the binary frames above that carried or claimed to carry commands
  EXPECT_EQ(b.received, 1) << sim.out();   // the one good json twist
  ASSERT_GT(rss.size(), 20u);
  const long baseline = rss[std::min<std::size_t>(10, rss.size() - 1)];  // after start-up (1 s)
  const long peak = *std::max_element(rss.begin(), rss.end());
  EXPECT_LT(peak - baseline, 64 * 1024) << "RSS grew from " << baseline << " kB to " << peak << " kB";
}

TEST_F(FoxgloveServer, TopicsAdvertisedDuringARunReachConnectedClients) {
  // the bridge in this process, on a simulation this test steps (this thread is the
  // simulation thread): a topic that appears mid-run is advertised to the connected client
  Simulation sim(testing::one_wall_room());
  FoxgloveOptions options;
  options.port = free_local_port();
  ASSERT_GT(options.port, 0);
  auto bridge = make_foxglove_bridge(options);
  bridge->start(sim);
  testing::CommandResult r;
  std::atomic<bool> done = false;
  std::thread client([&] {
    r = testing::node_script("late_topic_client.js", "ws://127.0.0.1:" + std::to_string(options.port) + " /late");
    done = true;
  });
  // step until the client is connected and receiving /clock ...
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (bridge->stats().sent == 0 && !done && std::chrono::steady_clock::now() < deadline) {
    sim.step();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  // ... then a new topic appears, and is published on until the client has one message
  const TopicId late = sim.bus().advertise("/late", "geometry_msgs/PoseStamped");
  while (!done && std::chrono::steady_clock::now() < deadline) {
    msg::PoseStamped p;
    p.header = {sim.time(), "map"};
    p.pose.p = Vec3(1, 2, 3);
    sim.bus().publish(late, p);
    sim.step();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  client.join();
  bridge->stop();
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const json d = last_json(r.out);
  const auto& first = d["channelsAtConnect"];
  EXPECT_EQ(std::find(first.begin(), first.end(), "/late"), first.end());
  EXPECT_TRUE(d["advertisedLater"].get<bool>());
  EXPECT_EQ(d["channel"]["schemaName"], "geometry_msgs/msg/PoseStamped");
  EXPECT_EQ(d["channel"]["encoding"], "cdr");
  EXPECT_EQ(d["message"]["value"]["header"]["frame_id"], "map");
  EXPECT_EQ(d["message"]["value"]["pose"]["position"]["z"], 3.0);
}

TEST_F(FoxgloveServer, JointCommandsInJsonAndCdrMoveAJointAndRefusalsSayWhy) {
  // the slider robot (tests/sim/slider_robot.h: "lift" prismatic, position-controlled,
  // [-0.1, 0.2] m) beside a rescue robot, whose moving joints are all wheels and head; the
  // bridge in this process, on a simulation this thread steps (a few steps first, so the
  // latched robot_description is out before the client connects)
  WorldSpec spec = testing::slider_room("slider");
  RobotPlacement rescue;
  rescue.name = "rescue";
  rescue.start = {1.5, 1.5, 0};
  spec.robots.push_back(rescue);
  std::map<std::string, RobotSpec> models = builtin_models();
  models["slider"] = testing::slider_robot();
  Simulation sim(compile_world(spec, models));
  const RobotIndex slider = sim.robot_index("slider");
  ASSERT_TRUE(slider.valid());
  const RobotSpec& slider_spec = sim.world().robot(slider).spec;
  const auto lift = static_cast<std::size_t>(slider_spec.joint_index("lift"));
  FoxgloveOptions options;
  options.port = free_local_port();
  ASSERT_GT(options.port, 0);
  auto bridge = make_foxglove_bridge(options);
  bridge->start(sim);
  for (int i = 0; i < 10; ++i) sim.step();
  testing::CommandResult r;
  std::atomic<bool> done = false;
  std::thread client([&] {
    r = testing::node_script("joint_command_client.js", "ws://127.0.0.1:" + std::to_string(options.port) + " /slider /rescue");
    done = true;
  });
  // step while the client commands; watch the lift joint in the simulation's own state
  bool held_json_target = false;  // at 0.15 m within 1 mm, with 0.15 as its target
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(45);
  while (!done && std::chrono::steady_clock::now() < deadline) {
    sim.step();
    const RobotState& rs = sim.state().robot(slider);
    if (lift < rs.joint_target.size() && rs.joint_target[lift] == 0.15 && std::abs(rs.q[lift] - 0.15) < 1e-3) held_json_target = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  client.join();
  bridge->stop();
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const json d = last_json(r.out);
  EXPECT_TRUE(d["errors"].empty()) << d["errors"];

  // json {"name":["lift"],"position":[0.15]}: the joint went there (seen in the state and on
  // joint_states); then cdr -0.05 m: it went there too
  EXPECT_TRUE(held_json_target);
  EXPECT_TRUE(d["phases"]["json"]["reached"].get<bool>()) << d["phases"];
  EXPECT_TRUE(d["phases"]["cdr"]["reached"].get<bool>()) << d["phases"];
  const RobotState& rs = sim.state().robot(slider);
  ASSERT_GT(rs.joint_target.size(), lift);
  EXPECT_EQ(rs.joint_target[lift], -0.05);
  EXPECT_NEAR(rs.q[lift], -0.05, 1e-3);

  // the description the layout's URDF layer reads: latched, so a client connecting after it was
  // published gets it
  EXPECT_EQ(d["description"]["schemaName"], "std_msgs/msg/String") << d["description"];
  EXPECT_EQ(d["description"]["encoding"], "cdr");
  EXPECT_EQ(d["description"]["data"], testing::kSliderDescription);

  // one status error per refusal, each in its phase, saying why
  std::map<std::string, std::vector<std::string>> statuses;
  for (const auto& s : d["statuses"]) {
    EXPECT_EQ(s["level"], 2) << s;
    statuses[s["phase"]].push_back(s["message"]);
  }
  ASSERT_EQ(statuses["advertise"].size(), 1u) << d["statuses"];
  const std::string& advertised = statuses["advertise"][0];
  EXPECT_NE(advertised.find("/rescue/joint_command"), std::string::npos) << advertised;
  EXPECT_NE(advertised.find("robot 'rescue' has no joints that joint_command can drive"), std::string::npos) << advertised;
  EXPECT_NE(advertised.find("it takes /rescue/cmd_vel (geometry_msgs/msg/Twist), /rescue/head/command (std_msgs/msg/Float64MultiArray)"),
            std::string::npos)
      << advertised;
  ASSERT_EQ(statuses["foreign"].size(), 1u) << d["statuses"];
  EXPECT_NE(
      statuses["foreign"][0].find("does not take this topic; it takes /slider/cmd_vel (geometry_msgs/msg/Twist), /slider/head/command "
                                  "(std_msgs/msg/Float64MultiArray), /slider/joint_command (sensor_msgs/msg/JointState), "
                                  "/rescue/cmd_vel (geometry_msgs/msg/Twist), /rescue/head/command (std_msgs/msg/Float64MultiArray)"),
      std::string::npos)
      << statuses["foreign"][0];
  ASSERT_EQ(statuses["wheel"].size(), 1u) << d["statuses"];
  EXPECT_NE(statuses["wheel"][0].find("/slider/joint_command: rejected: 'wheel' is a drive wheel"), std::string::npos)
      << statuses["wheel"][0];
  ASSERT_EQ(statuses["malformed"].size(), 1u) << d["statuses"];
  EXPECT_NE(statuses["malformed"][0].find("position[0]: expected a number"), std::string::npos) << statuses["malformed"][0];
  EXPECT_EQ(d["statuses"].size(), 4u) << d["statuses"];  // nothing about the json and cdr channels or commands

  // two commands applied, two refused (the failed advertisement is no command)
  const BridgeStats st = bridge->stats();
  EXPECT_EQ(st.received, 2u);
  EXPECT_EQ(st.rejected, 2u);
}

TEST_F(FoxgloveServer, AMissionsReportsAndDatagramsComeFromAClientToo) {
  // two robots 4 m apart in a 20 m room, a victim at (5, 0) (as the ROS 2 mission test); the
  // client reports it 0.5 m off (0.3, 0.4) in json and sends robot2 a datagram in cdr
  Simulation sim(compile_world(testing::two_robots_and_a_victim(), builtin_models()));
  Mission mission(MissionSpec{}, sim);  // ideal radio, RoboCup rules
  FoxgloveOptions options;
  options.port = free_local_port();
  ASSERT_GT(options.port, 0);
  auto bridge = make_foxglove_bridge(options);
  bridge->start(sim);
  const Vec3 at = sim.world().victims[0].centre + Vec3(0.3, 0.4, 0);
  testing::CommandResult r;
  std::atomic<bool> done = false;
  std::thread client([&] {
    r = testing::node_script("mission_client.js", "ws://127.0.0.1:" + std::to_string(options.port) + " /robot robot2 " +
                                                      fmt::format("{:.17g} {:.17g} {:.17g}", at.x(), at.y(), at.z()));
    done = true;
  });
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(45);
  while (!done && std::chrono::steady_clock::now() < deadline) {
    sim.step();
    mission.after_step();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  client.join();
  bridge->stop();
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const json d = last_json(r.out);
  EXPECT_TRUE(d["errors"].empty()) << d["errors"];

  // the report was judged: accepted, v1, 0.5 m off, +1
  ASSERT_EQ(d["answers"].size(), 1u) << d["answers"];
  EXPECT_EQ(d["answers"][0]["outcome"], "accepted") << d["answers"][0];
  EXPECT_EQ(d["answers"][0]["victim"], "v1");
  EXPECT_NEAR(d["answers"][0]["distance"].get<double>(), 0.5, 1e-9);
  EXPECT_EQ(mission.referee().score(), 1.0);
  EXPECT_EQ(mission.referee().counts()[ReportOutcome::accepted], 1u);
  // the datagram crossed the (ideal) radio to robot2's inbox
  ASSERT_EQ(d["inbox"].size(), 1u) << d["inbox"];
  EXPECT_EQ(d["inbox"][0]["from"], "robot");
  EXPECT_EQ(d["inbox"][0]["text"], fmt::format("victim near {:.17g},{:.17g}", at.x(), at.y()));
  // the malformed report: one status error naming the field; nothing charged for it
  ASSERT_EQ(d["statuses"].size(), 1u) << d["statuses"];
  EXPECT_EQ(d["statuses"][0]["phase"], "malformed");
  EXPECT_NE(d["statuses"][0]["message"].get<std::string>().find(
                "/robot/rescue/report: geometry_msgs/PoseStamped: pose.position.x: expected a number"),
            std::string::npos)
      << d["statuses"][0];
  EXPECT_EQ(mission.referee().counts()[ReportOutcome::false_report], 0u);
  const BridgeStats st = bridge->stats();
  EXPECT_EQ(st.received, 2u);
  EXPECT_EQ(st.rejected, 1u);
}

TEST(FoxgloveCli, PortFlagTakesAnOptionalValue) {
  const auto dir = testing::temp_dir("fox-cli");
  testing::write_room(dir);
  // --foxglove alone: the default port (listening there, or told it is taken)
  const auto plain = testing::rescuesim("--log-level info run room.yaml --foxglove --duration 0.2 --no-cameras --out out", dir);
  EXPECT_NE(plain.err.find("127.0.0.1:8765"), std::string::npos) << plain.err;
  // --foxglove 0 and --foxglove=0: a free port
  for (const char* flag : {"--foxglove 0", "--foxglove=0"}) {
    const auto r =
        testing::rescuesim(std::string("--log-level info run room.yaml ") + flag + " --duration 0.2 --no-cameras --out out", dir);
    EXPECT_EQ(r.exit_code, 0) << flag << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.err, m, std::regex(R"(listening on ws://127\.0\.0\.1:(\d+))"))) << flag << r.err;
    EXPECT_GT(std::stoi(m[1]), 0);
    EXPECT_NE(r.out.find("bridge foxglove:"), std::string::npos) << r.out;
  }
  // a bad host or port is a usage error that says which
  const auto host = testing::rescuesim("run room.yaml --foxglove=0 --foxglove-host not-an-ip --duration 0.2 --no-cameras --out out", dir);
  EXPECT_NE(host.exit_code, 0);
  EXPECT_NE(host.err.find("not-an-ip"), std::string::npos) << host.err;
  const auto port = testing::rescuesim("run room.yaml --foxglove=70000 --duration 0.2 --no-cameras --out out", dir);
  EXPECT_EQ(port.exit_code, 2);
  EXPECT_NE(port.err.find("--foxglove"), std::string::npos) << port.err;
}

TEST(FoxgloveProbe, TheBenchsClientReportsEveryScanWithItsStamp) {
  // `rescuesim bench`'s Foxglove client (bridges/foxglove/foxglove_probe.h) against a realtime
  // run of the room: the laser publishes at 10 Hz from sim time 0, so every stamp it reports is
  // a whole multiple of 0.1 s, each 0.1 s after the one before (none lost on loopback), and in
  // 3 s of wall time about 30 of them come
  const auto dir = testing::temp_dir("fox-probe");
  testing::write_room(dir);
  Background sim(dir, "run room.yaml --foxglove=0 --no-cameras --duration 60 --out out");
  ASSERT_GT(sim.port(), 0) << sim.err();
  const auto r = testing::run_command(std::string("'") + RESCUESIM_EXE + "' bench-probe --transport foxglove --port " +
                                      std::to_string(sim.port()) + " --topic /scan=sensor_msgs/LaserScan --seconds 3");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("probe ready"), std::string::npos) << r.err;
  std::vector<long long> stamps;
  std::istringstream lines(r.out);
  std::string topic;
  long long stamp = 0, wall = 0;
  while (lines >> topic >> stamp >> wall) {
    EXPECT_EQ(topic, "/scan");
    stamps.push_back(stamp);
  }
  ASSERT_GE(stamps.size(), 20u) << r.out << r.err;
  EXPECT_LE(stamps.size(), 40u);
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    EXPECT_EQ(stamps[i] % 100'000'000, 0) << stamps[i];
    if (i > 0) {
      EXPECT_EQ(stamps[i] - stamps[i - 1], 100'000'000) << i;
    }
  }
  // nothing listening: a clear error once its time to connect (here 1 s) has passed
  const auto none = testing::run_command(std::string("'") + RESCUESIM_EXE + "' bench-probe --transport foxglove --port " +
                                         std::to_string(free_local_port()) + " --topic /scan=sensor_msgs/LaserScan --seconds 1");
  EXPECT_NE(none.exit_code, 0);
  EXPECT_NE(none.err.find("cannot connect to the Foxglove server"), std::string::npos) << none.err;
}

}  // namespace
}  // namespace rescuesim
