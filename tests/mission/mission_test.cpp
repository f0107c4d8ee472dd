// The mission inside a running Simulation: robots' radios follow the robots, WSS received
// power through counted walls against the formula, a datagram beyond the cut-off never
// arrives, a dropped relay carries the link when its robot drives on, reports judged with the
// radio's contact, and what is published on the Bus.

#include "mission/mission.h"

#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "robots/rescue_robot.h"
#include "sim/simulation.h"

namespace rescuesim {
namespace {

/// A floor from x = −5 to 60, walls 0.1 m thick and 1 m high across the x axis (y from −5 to
/// 5) at each x of `wall_x`, robots "a", "b", ... on y = 0 at each x of `robot_x`, facing +x.
World line_world(const std::vector<double>& wall_x, const std::vector<double>& robot_x) {
  WorldSpec s;
  s.name = "mission_test";
  s.materials = default_materials();
  s.floor_min = {-5, -10};
  s.floor_max = {60, 10};
  for (double x : wall_x) s.walls.push_back(WallSpec{{x, -5}, {x, 5}, 0.1, 1.0, "wall", {}});
  for (std::size_t i = 0; i < robot_x.size(); ++i) {
    RobotPlacement r;
    r.name = std::string(1, static_cast<char>('a' + i));
    r.start = {robot_x[i], 0, 0};
    s.robots.push_back(r);
  }
  return compile_world(s, builtin_models());
}

/// WSS radio; the base 0.5 m above the floor at (−1, 0), below the tops of the walls.
MissionSpec wss_mission() {
  MissionSpec m;
  m.radio.model = radio_model("wss");
  m.bases.push_back({"base", {-1, 0, 0.5}});
  return m;
}

void steps(Simulation& sim, Mission& mission, double seconds) {
  const SimTime end = sim.time() + SimTime::from_seconds(seconds);
  while (sim.time() < end) {
    sim.step();
    mission.after_step();
  }
}

TEST(Mission, WssPowerBetweenTwoRobotsIsTheFormulasThroughTheWallsBetweenThem) {
  // 20 m apart, walls at x = 5 and 15 between them, one at 30 behind b:
  // P = −49.67 − 10·1·log10(20/2) − 2·6.325 = −49.67 − 10 − 12.65 = −72.32 dBm
  Simulation sim(line_world({5, 15, 30}, {0, 20}));
  Mission mission(wss_mission(), sim);
  steps(sim, mission, 0.5);
  const RadioLink& l = mission.network().link(mission.robot_node(RobotIndex(0)), mission.robot_node(RobotIndex(1)));
  EXPECT_EQ(l.walls, 2);
  EXPECT_NEAR(l.distance_m, 20.0, 0.01);
  EXPECT_NEAR(l.rssi_dbm, -72.32, 0.01);
  EXPECT_TRUE(l.connected);
  // the base, 1 m behind a: a hears it directly, b through the same two walls
  EXPECT_TRUE(mission.in_contact(RobotIndex(0)));
  EXPECT_TRUE(mission.in_contact(RobotIndex(1)));
  EXPECT_EQ(mission.status(RobotIndex(0)).hops_to_base, 1);
  EXPECT_EQ(mission.network().node(mission.base_nodes()[0]).id, "base");
}

TEST(Mission, BeyondTheCutOffADatagramNeverArrivesAndReportsAreOutOfContact) {
  // 40 m apart with five walls between: −49.67 − 10·log10(20) − 5·6.325 = −94.31 dBm < −93
  Simulation sim(line_world({5, 10, 15, 20, 25}, {0, 40}));
  Mission mission(wss_mission(), sim);
  const RadioLink& l = mission.network().link(mission.robot_node(RobotIndex(0)), mission.robot_node(RobotIndex(1)));
  EXPECT_EQ(l.walls, 5);
  EXPECT_NEAR(l.rssi_dbm, -94.31, 0.01);
  EXPECT_FALSE(l.connected);
  EXPECT_TRUE(mission.in_contact(RobotIndex(0)));
  EXPECT_FALSE(mission.in_contact(RobotIndex(1)));

  const SendResult sent = mission.send(RobotIndex(1), "a", {1, 2, 3});
  ASSERT_TRUE(sent.accepted) << sent.reason;
  steps(sim, mission, 1.0);  // ten link updates
  EXPECT_TRUE(mission.take_inbox(RobotIndex(0)).empty());
  EXPECT_EQ(mission.status(RobotIndex(1)).datagrams_dropped, 1u);
  EXPECT_EQ(mission.result().datagrams_dropped, 1u);

  // a's datagram to the base arrives at the next link update
  ASSERT_TRUE(mission.send(RobotIndex(0), "base", {7}).accepted);
  steps(sim, mission, 0.1);
  EXPECT_EQ(mission.network().inbox(mission.base_nodes()[0]).size(), 1u);
  // a base's inbox nobody takes keeps only the newest kInboxKeep (1,024): 1,100 more sent, the
  // oldest 77 are gone; take_base_inbox empties it
  for (int i = 0; i < 1100; ++i) ASSERT_TRUE(mission.send(RobotIndex(0), "base", {static_cast<std::uint8_t>(i % 256)}).accepted);
  steps(sim, mission, 0.1);
  const std::vector<Datagram> at_base = mission.take_base_inbox(0);
  ASSERT_EQ(at_base.size(), Mission::kInboxKeep);
  EXPECT_EQ(at_base.front().bytes, std::vector<std::uint8_t>{static_cast<std::uint8_t>((1100 - 1024) % 256)});
  EXPECT_EQ(at_base.back().bytes, std::vector<std::uint8_t>{static_cast<std::uint8_t>(1099 % 256)});
  EXPECT_TRUE(mission.network().inbox(mission.base_nodes()[0]).empty());

  // no victims here: a report in contact is false (−0.5), one out of contact is refused at no cost
  EXPECT_EQ(mission.report(RobotIndex(1), {40, 0, 0}).outcome, ReportOutcome::out_of_contact);
  EXPECT_EQ(mission.report(RobotIndex(0), {1, 0, 0}).outcome, ReportOutcome::false_report);
  EXPECT_EQ(mission.referee().score(), -0.5);

  EXPECT_FALSE(mission.send(RobotIndex(1), "nobody", {1}).accepted);
  EXPECT_FALSE(mission.send(RobotIndex(1), "a", std::vector<std::uint8_t>(70000)).accepted);  // over max_datagram_bytes
}

TEST(Mission, ADroppedRelayCarriesTheLinkWhenItsRobotDrivesOn) {
  // open floor, path-loss exponent 4: P = −49.67 − 40·log10(d/2) links up to d = 2·10^(43.33/40) = 24.2 m
  MissionSpec spec = wss_mission();
  spec.radio.model.wss.n = 4;
  Simulation sim(line_world({}, {20}));
  Mission mission(spec, sim);
  EXPECT_TRUE(mission.in_contact(RobotIndex(0)));  // 21 m from the base: −49.67 − 40·log10(10.5) = −90.5 dBm
  const RelayResult relay = mission.drop_relay(RobotIndex(0));
  ASSERT_TRUE(relay.ok()) << relay.reason;
  EXPECT_EQ(mission.network().node(relay.node).id, "a/relay_1");
  EXPECT_EQ(mission.network().relays_left(mission.robot_node(RobotIndex(0))), 11);

  // a drives on along +x at 1 m/s for 16 s: about 37 m from the base, out of its reach, 16 m from the relay
  const SimTime end = sim.time() + SimTime::from_seconds(16);
  while (sim.time() < end) {
    msg::Twist t;
    t.linear.x() = 1.0;
    sim.command_velocity(RobotIndex(0), t);
    steps(sim, mission, 0.1);
  }
  const double x = sim.state().robots[0].base.X_WB.p.x();
  ASSERT_GT(x, 33.0);
  const RadioNodeIndex base = mission.base_nodes()[0];
  EXPECT_FALSE(mission.network().link(mission.robot_node(RobotIndex(0)), base).connected);
  EXPECT_TRUE(mission.network().link(mission.robot_node(RobotIndex(0)), relay.node).connected);
  EXPECT_TRUE(mission.in_contact(RobotIndex(0)));
  EXPECT_EQ(mission.status(RobotIndex(0)).hops_to_base, 2);  // a → relay → base
  EXPECT_EQ(mission.network().route(mission.robot_node(RobotIndex(0)), base),
            (std::vector<RadioNodeIndex>{mission.robot_node(RobotIndex(0)), relay.node, base}));
  EXPECT_EQ(mission.result().relays_dropped, (std::vector<int>{1}));
}

TEST(Mission, ReportsAreAnsweredOnTheBusAndTheScoreIsLatched) {
  WorldSpec s;
  s.materials = default_materials();
  s.floor_min = {-5, -5};
  s.floor_max = {5, 5};
  RobotPlacement r;
  r.name = "a";
  s.robots.push_back(r);
  VictimSpec v;
  v.name = "v1";
  v.pose = {3, 0, 0};
  s.victims.push_back(v);
  Simulation sim(compile_world(s, builtin_models()));
  Mission mission(MissionSpec{}, sim);  // ideal radio, RoboCup rules
  std::vector<nlohmann::json> answers;
  sim.bus().subscribe("/rescue/report_result", [&](const Topic&, const msg::Message& m) {
    answers.push_back(nlohmann::json::parse(std::get<msg::String>(m).data));
  });
  steps(sim, mission, 1.0);
  const Vec3 c = sim.world().victims[0].centre;
  const ReportReply reply = mission.report(RobotIndex(0), c + Vec3(0.6, 0.8, 0));  // 1 m from the victim's centre
  EXPECT_EQ(reply.outcome, ReportOutcome::accepted);
  ASSERT_EQ(answers.size(), 1u);
  EXPECT_EQ(answers[0]["outcome"], "accepted");
  EXPECT_EQ(answers[0]["victim"], "v1");
  EXPECT_NEAR(answers[0]["distance"].get<double>(), 1.0, 1e-9);
  EXPECT_EQ(answers[0]["score"], 1.0);

  // a subscriber that comes late gets the latched score at once
  nlohmann::json score;
  sim.bus().subscribe("/rescue/score",
                      [&](const Topic&, const msg::Message& m) { score = nlohmann::json::parse(std::get<msg::String>(m).data); });
  EXPECT_EQ(score["score"], 1.0);
  EXPECT_EQ(score["victims_found"], 1);
  EXPECT_EQ(score["victims"], 1);
  EXPECT_EQ(score["reports"], 1);
  EXPECT_NEAR(score["elapsed"].get<double>(), 1.0, 1e-9);

  // NaN gets an answer with null coordinates, nothing is scored
  EXPECT_EQ(mission.report(RobotIndex(0), {std::nan(""), 0, 0}).outcome, ReportOutcome::invalid);
  ASSERT_EQ(answers.size(), 2u);
  EXPECT_TRUE(answers[1]["position"][0].is_null());
  EXPECT_EQ(mission.result().counts[ReportOutcome::invalid], 1u);
}

/// The index of input `topic` in sim.inputs() (what a bridge subscribes), or -1.
int input_index(const Simulation& sim, const std::string& topic) {
  const std::vector<HostInput> inputs = sim.inputs();
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    if (inputs[i].topic == topic) return static_cast<int>(i);
  }
  return -1;
}

TEST(Mission, ReportsDatagramsAndRelaysComeInThroughTopicsAsFromABridge) {
  // what the ROS bridges do with a message on these topics: submit_input, then the next step hands it over
  Simulation sim(line_world({}, {0, 5}));
  Mission mission(wss_mission(), sim);
  const std::vector<HostInput> inputs = sim.inputs();
  ASSERT_EQ(inputs.size(), 10u);  // per robot: lights (the simulation's), report, comms/send, drop_relay, report_image
  EXPECT_EQ(inputs[static_cast<std::size_t>(input_index(sim, "/a/rescue/report"))].type, "geometry_msgs/PoseStamped");
  EXPECT_EQ(inputs[static_cast<std::size_t>(input_index(sim, "/a/lights"))].type, "std_msgs/Bool");
  const int report = input_index(sim, "/a/rescue/report"), send = input_index(sim, "/a/rescue/comms/send"),
            relay = input_index(sim, "/a/rescue/drop_relay");
  ASSERT_GE(report, 0);
  ASSERT_GE(send, 0);
  ASSERT_GE(relay, 0);
  EXPECT_EQ(inputs[static_cast<std::size_t>(send)].type, "std_msgs/String");
  const auto on = [&](const char* topic, std::vector<nlohmann::json>& into) {
    sim.bus().subscribe(
        topic, [&into](const Topic&, const msg::Message& m) { into.push_back(nlohmann::json::parse(std::get<msg::String>(m).data)); });
  };
  std::vector<nlohmann::json> inbox_b, results_a, answers_a;
  on("/b/rescue/comms/inbox", inbox_b);
  on("/a/rescue/comms/result", results_a);
  on("/a/rescue/report_result", answers_a);
  const auto submit = [&](int index, msg::Message m) { return sim.submit_input(static_cast<std::size_t>(index), m); };

  // a datagram from a to b: answered at the next step, delivered at the next link update (0.1 s)
  ASSERT_TRUE(submit(send, msg::String{R"({"to": "b", "text": "hello"})"}));
  steps(sim, mission, 0.1);
  ASSERT_EQ(results_a.size(), 1u);
  EXPECT_EQ(results_a[0]["request"], "send");
  EXPECT_EQ(results_a[0]["accepted"], true);
  EXPECT_EQ(results_a[0]["seq"], 1);
  EXPECT_EQ(results_a[0]["bytes"], 5);
  ASSERT_EQ(inbox_b.size(), 1u);
  EXPECT_EQ(inbox_b[0]["from"], "a");
  EXPECT_EQ(inbox_b[0]["to"], "b");
  EXPECT_EQ(inbox_b[0]["text"], "hello");
  EXPECT_EQ(inbox_b[0]["data"], "aGVsbG8=");  // base64 of "hello"
  EXPECT_EQ(inbox_b[0]["hops"], 1);
  // still in b's inbox for whoever takes it in-process (the Python API)
  EXPECT_EQ(mission.take_inbox(RobotIndex(1)).size(), 1u);

  // bytes as base64, and three bad requests: each answered with the reason, nothing sent
  ASSERT_TRUE(submit(send, msg::String{R"({"to": "*", "data": "AAEC/w=="})"}));
  ASSERT_TRUE(submit(send, msg::String{"{to: b"}));
  ASSERT_TRUE(submit(send, msg::String{R"({"to": "nobody", "text": "x"})"}));
  ASSERT_TRUE(submit(send, msg::String{R"({"to": "b", "data": "not base64!"})"}));
  steps(sim, mission, 0.1);
  ASSERT_EQ(results_a.size(), 5u);
  EXPECT_EQ(results_a[1]["accepted"], true);
  EXPECT_EQ(results_a[1]["bytes"], 4);
  EXPECT_EQ(results_a[2]["accepted"], false);
  EXPECT_NE(results_a[2]["reason"].get<std::string>().find("not JSON"), std::string::npos) << results_a[2];
  EXPECT_NE(results_a[3]["reason"].get<std::string>().find("no radio called 'nobody'"), std::string::npos) << results_a[3];
  EXPECT_NE(results_a[4]["reason"].get<std::string>().find("not base64"), std::string::npos) << results_a[4];
  ASSERT_EQ(inbox_b.size(), 2u);  // the broadcast reached b, its neighbour
  EXPECT_EQ(inbox_b[1]["to"], "*");
  EXPECT_FALSE(inbox_b[1].contains("text"));  // 00 01 02 ff is not text
  EXPECT_EQ(mission.result().datagrams_sent, 2u);

  // a relay, from the budget of 12
  ASSERT_TRUE(submit(relay, msg::String{""}));
  sim.step();
  ASSERT_EQ(results_a.size(), 6u);
  EXPECT_EQ(results_a[5]["request"], "drop_relay");
  EXPECT_EQ(results_a[5]["accepted"], true);
  EXPECT_EQ(results_a[5]["relay"], "a/relay_1");
  EXPECT_EQ(results_a[5]["relays_left"], 11);

  // reports: the map frame is judged (no victims here: false, −0.5); another frame is refused uncharged
  msg::PoseStamped p;
  p.pose.p = {1, 0, 0};
  p.header.frame_id = "odom";
  ASSERT_TRUE(submit(report, p));
  p.header.frame_id = "map";
  ASSERT_TRUE(submit(report, p));
  sim.step();
  ASSERT_EQ(answers_a.size(), 2u);
  EXPECT_EQ(answers_a[0]["outcome"], "invalid");
  EXPECT_NE(answers_a[0]["message"].get<std::string>().find("frame_id 'odom'"), std::string::npos);
  EXPECT_EQ(answers_a[1]["outcome"], "false");
  EXPECT_EQ(mission.referee().score(), -0.5);
  EXPECT_EQ(mission.referee().counts().charged, 1u);

  // a message of another type is refused at once; a flood is cut at the queue's bound
  EXPECT_FALSE(submit(report, msg::String{"x"}));
  for (std::size_t i = 0; i < Simulation::kMaxQueuedInputs; ++i) ASSERT_TRUE(submit(relay, msg::String{}));
  const CommandOutcome full = submit(relay, msg::String{});
  EXPECT_FALSE(full);
  EXPECT_NE(full.reason.find("full"), std::string::npos) << full.reason;
  sim.step();  // 4096 drops against a budget of 11 left: 11 relays, the rest refused with a reason
  EXPECT_EQ(mission.result().relays_dropped, (std::vector<int>{12, 0}));
  EXPECT_EQ(results_a.back()["accepted"], false);
}

/// A w x h rgb8 picture stamped `stamp`, every pixel (r, g, b).
msg::Image picture(std::uint32_t w, std::uint32_t h, SimTime stamp, std::uint8_t r = 200, std::uint8_t g = 40, std::uint8_t b = 10) {
  msg::Image im;
  im.header.stamp = stamp;
  im.width = w;
  im.height = h;
  im.encoding = "rgb8";
  im.step = 3 * w;
  for (std::uint32_t i = 0; i < w * h; ++i) im.data.insert(im.data.end(), {r, g, b});
  return im;
}

TEST(Mission, AReportsPictureGoesWithTheReportOfItsStampInEitherOrder) {
  Simulation sim(line_world({}, {0, 5}));
  Mission mission(wss_mission(), sim);
  const int report = input_index(sim, "/a/rescue/report"), image = input_index(sim, "/a/rescue/report_image");
  ASSERT_GE(image, 0);
  EXPECT_EQ(sim.inputs()[static_cast<std::size_t>(image)].type, "sensor_msgs/Image");
  std::vector<nlohmann::json> answers;
  sim.bus().subscribe("/a/rescue/report_result", [&](const Topic&, const msg::Message& m) {
    answers.push_back(nlohmann::json::parse(std::get<msg::String>(m).data));
  });
  const auto submit = [&](int index, msg::Message m) { return sim.submit_input(static_cast<std::size_t>(index), m); };
  msg::PoseStamped p;
  p.header.frame_id = "map";

  // picture first (stamp 1 s), then its report: kept with report 1
  p.header.stamp = SimTime::from_seconds(1);
  p.pose.p = {1, 0, 0};
  ASSERT_TRUE(submit(image, picture(4, 2, p.header.stamp)));
  ASSERT_TRUE(submit(report, p));
  sim.step();
  ASSERT_EQ(answers.size(), 1u);
  EXPECT_EQ(answers[0]["id"], 1);
  EXPECT_NE(answers[0]["message"].get<std::string>().find("with its picture"), std::string::npos) << answers[0];
  // report first (stamp 2 s), then a picture of another stamp (kept waiting), then its own
  p.header.stamp = SimTime::from_seconds(2);
  p.pose.p = {2, 0, 0};
  ASSERT_TRUE(submit(report, p));
  ASSERT_TRUE(submit(image, picture(3, 3, SimTime::from_seconds(7))));
  ASSERT_TRUE(submit(image, picture(2, 5, p.header.stamp, 1, 2, 3)));
  sim.step();
  // the report (no picture yet); the picture of stamp 7 s waits, silently; its own is answered
  ASSERT_EQ(answers.size(), 3u);
  EXPECT_EQ(answers[1]["id"], 2);
  EXPECT_EQ(answers[1]["message"].get<std::string>().find("picture"), std::string::npos) << answers[1];
  EXPECT_EQ(answers[2], nlohmann::json::parse(R"({"request": "report_image", "accepted": true, "id": 2, "stamp": )" +
                                              answers[2]["stamp"].dump() + "}"));
  const auto& pictures = mission.report_images();
  ASSERT_EQ(pictures.size(), 2u);
  EXPECT_EQ(pictures[0].about.report, 1u);
  EXPECT_EQ(pictures[0].image.width, 4u);
  EXPECT_EQ(pictures[0].about.outcome, ReportOutcome::false_report);  // no victims in this world
  EXPECT_EQ(pictures[1].about.report, 2u);
  EXPECT_EQ(pictures[1].image.height, 5u);
  EXPECT_EQ(pictures[1].image.data[0], 1);
  EXPECT_EQ(mission.result().pictures.size(), 2u);
  // a second picture for report 2 is not taken: it waits for a report of its stamp
  ASSERT_TRUE(submit(image, picture(2, 2, p.header.stamp)));
  sim.step();
  EXPECT_EQ(mission.report_images().size(), 2u);
  EXPECT_EQ(answers.size(), 3u);
}

TEST(Mission, APictureThatIsNoPictureIsRefusedWithTheReasonAndTheReportStillCounts) {
  Simulation sim(line_world({}, {0, 5}));
  Mission mission(wss_mission(), sim);
  const int image = input_index(sim, "/a/rescue/report_image");
  std::vector<nlohmann::json> answers;
  sim.bus().subscribe("/a/rescue/report_result", [&](const Topic&, const msg::Message& m) {
    answers.push_back(nlohmann::json::parse(std::get<msg::String>(m).data));
  });
  msg::Image depth = picture(2, 2, SimTime{});
  depth.encoding = "32FC1";
  msg::Image short_data = picture(4, 4, SimTime{});
  short_data.data.resize(40);
  msg::Image huge = picture(1, 1, SimTime{});
  huge.width = 5000;
  msg::Image narrow = picture(4, 1, SimTime{});
  narrow.step = 8;
  for (const msg::Image& bad : {depth, short_data, huge, narrow}) ASSERT_TRUE(sim.submit_input(static_cast<std::size_t>(image), bad));
  sim.step();
  ASSERT_EQ(answers.size(), 4u);
  const char* why[] = {"encoding '32FC1': a report's picture is rgb8, bgr8, rgba8, bgra8 or mono8",
                       "40 bytes of data, expected step x height = 48",
                       "a picture of 5000 x 1 pixels: each side must be 1 to 4096",
                       "step 8 is shorter than a row of 4 rgb8 pixels"};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(answers[i]["request"], "report_image");
    EXPECT_EQ(answers[i]["accepted"], false);
    EXPECT_EQ(answers[i]["reason"], why[i]) << answers[i];
  }
  // in-process (the built-in robots, Python): the report is judged, its bad picture left out
  const ReportReply r = mission.report(RobotIndex(0), {1, 0, 0}, depth);
  EXPECT_EQ(r.outcome, ReportOutcome::false_report);
  EXPECT_NE(r.message.find("its picture was not kept: encoding '32FC1'"), std::string::npos) << r.message;
  EXPECT_TRUE(mission.report_images().empty());
  EXPECT_EQ(mission.referee().counts().charged, 1u);
}

TEST(Mission, ATeamMapIsScoredAgainstTheWallsTheRobotsCouldSee) {
  // one wall 4 m long across x = 3 (y from -2 to 2), robot "a" at the origin facing it
  WorldSpec spec;
  spec.name = "map_scoring";
  spec.materials = default_materials();
  spec.floor_min = {-5, -5};
  spec.floor_max = {5, 5};
  spec.walls.push_back(WallSpec{{3, -2}, {3, 2}, 0.1, 1.0, "wall", {}});
  RobotPlacement r;
  r.name = "a";
  spec.robots.push_back(r);
  Simulation sim(compile_world(spec, builtin_models()));
  Mission mission(MissionSpec{}, sim);
  mission.enable_map_scoring(spec);
  ASSERT_EQ(input_index(sim, "/rescue/map"), static_cast<int>(sim.inputs().size()) - 1);
  nlohmann::json published;
  sim.bus().subscribe("/rescue/map_score",
                      [&](const Topic&, const msg::Message& m) { published = nlohmann::json::parse(std::get<msg::String>(m).data); });
  steps(sim, mission, 0.5);

  // the truth itself as a map (100 on the wall's cells, 0 elsewhere): every occupied cell is a
  // wall (precision 1) and every wall cell the laser saw is in it (recall 1); the laser saw the
  // face towards the robot: 4 m / 0.05 m = 80 cells, one more for the grown outline's ends
  const map_eval::Grid truth = map_eval::true_occupancy(spec, 0.05, 0.3);
  msg::OccupancyGrid map;
  map.header.frame_id = "map";
  map.resolution = 0.05f;
  map.width = static_cast<std::uint32_t>(truth.width);
  map.height = static_cast<std::uint32_t>(truth.height);
  map.origin.p = {truth.origin.x(), truth.origin.y(), 0};
  for (std::uint8_t c : truth.cells) map.data.push_back(c ? 100 : 0);
  MapScoreResult s = mission.score_map(map);
  EXPECT_EQ(s.error, "");
  EXPECT_EQ(s.precision, 1.0);
  EXPECT_EQ(s.recall, 1.0);
  EXPECT_GE(s.visible, 80);
  EXPECT_LE(s.visible, 84);
  EXPECT_EQ(published["precision"], 1.0);

  // the same map 1 m off in x: nothing lines up
  map.origin.p.x() += 1.0;
  s = mission.score_map(map);
  EXPECT_EQ(s.precision, 0.0);
  EXPECT_EQ(s.recall, 0.0);

  // not a map, or another frame: answered with the reason; the last score stays
  map.data.pop_back();
  s = mission.score_map(map);
  EXPECT_NE(s.error.find("cells of data"), std::string::npos) << s.error;
  EXPECT_EQ(s.maps, 3);
  EXPECT_NE(published["error"].get<std::string>().find("cells of data"), std::string::npos);
  map.data.push_back(0);
  map.header.frame_id = "odom";
  s = mission.score_map(map);
  EXPECT_NE(s.error.find("frame_id 'odom'"), std::string::npos) << s.error;
  ASSERT_TRUE(mission.result().map);
  EXPECT_EQ(mission.result().map->maps, 4);
}

TEST(Mission, StatusIsPublishedOncePerSimSecond) {
  Simulation sim(line_world({}, {0, 5}));
  Mission mission(wss_mission(), sim);
  std::vector<nlohmann::json> status;
  sim.bus().subscribe("/b/rescue/comms/status", [&](const Topic&, const msg::Message& m) {
    status.push_back(nlohmann::json::parse(std::get<msg::String>(m).data));
  });
  steps(sim, mission, 3.0);
  ASSERT_EQ(status.size(), 4u);  // at the first step, then at 1, 2 and 3 s
  EXPECT_EQ(status.back()["in_contact"], true);
  // the widest path: b hears a (5 m, −53.65 dBm) better than the base (6 m, −54.44 dBm), and a
  // the base at 1 m, so b's route goes through a
  EXPECT_EQ(status.back()["hops_to_base"], 2);
  ASSERT_EQ(status.back()["neighbours"].size(), 2u);  // robot a and the base
  EXPECT_EQ(status.back()["neighbours"][0]["id"], "a");
  EXPECT_EQ(status.back()["relays_left"], 12);
  EXPECT_EQ(mission.network().update_count(), 31u);  // at set-up and every 0.1 s to 3 s
}

TEST(Mission, SameSeedSameLinksAndARestoredMemoryReplaysThem) {
  // SubT's shadowing draws from the run seed: two missions of one seed see the same margins
  MissionSpec spec;
  spec.radio.model = radio_model("subt");
  spec.radio.model.subt.max_range_m = 1e9;
  SimOptions o;
  o.seed = 7;
  Simulation s1(line_world({}, {0, 30}), o), s2(line_world({}, {0, 30}), o);
  Mission m1(spec, s1), m2(spec, s2);
  // both take a snapshot (a synchronisation point of the physics engine), so both step alike
  const State state = s1.snapshot();
  s2.snapshot();
  const Mission::Memory saved = m1.save();
  std::vector<double> margins1, margins2, margins3;
  for (int i = 0; i < 20; ++i) {
    steps(s1, m1, 0.1);
    steps(s2, m2, 0.1);
    margins1.push_back(m1.network().link(RadioNodeIndex(0), RadioNodeIndex(1)).margin_db);
    margins2.push_back(m2.network().link(RadioNodeIndex(0), RadioNodeIndex(1)).margin_db);
  }
  EXPECT_EQ(margins1, margins2);
  EXPECT_NE(margins1[0], margins1[1]);  // a new draw per update
  // the simulation and the mission back to set-up: the same links again, bitwise
  s1.restore(state);
  m1.load(saved);
  EXPECT_EQ(m1.network().update_count(), 1u);
  for (int i = 0; i < 20; ++i) {
    steps(s1, m1, 0.1);
    margins3.push_back(m1.network().link(RadioNodeIndex(0), RadioNodeIndex(1)).margin_db);
  }
  EXPECT_EQ(margins3, margins1);
}

}  // namespace
}  // namespace rescuesim
