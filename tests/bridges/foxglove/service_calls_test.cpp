// The Simulation Interfaces services end to end: the bridge in this process on a Simulation this
// thread steps, a fake SimControl (fake_control.h) whose posted tasks run on this thread between
// steps, and the reference client (@foxglove/ws-protocol) calling as Foxglove's Service Call
// panel does (services_client.js). Expected values are the fake's, set by hand.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <thread>

#include "bridges/foxglove/fake_control.h"
#include "bridges/foxglove/foxglove_bridge.h"
#include "bridges/foxglove/server_rig.h"
#include "core/local_ports.h"
#include "sim/simulation.h"

namespace rescuesim {
namespace {

using json = nlohmann::json;

/// What a run of the client saw, and what the bridge counted.
struct Served {
  testing::CommandResult r;
  json out;
  BridgeStats stats;
};

/// Serves `services_client.js MODE` from a bridge on a simulation stepped here, with `fake` as
/// its control (none: nullptr), until the client is done.
Served serve(testing::FakeControl* fake, const std::string& mode) {
  Simulation sim(testing::one_wall_room());
  if (fake) sim.set_control(fake);
  FoxgloveOptions options;
  options.port = free_local_port();
  EXPECT_GT(options.port, 0);
  auto bridge = make_foxglove_bridge(options);
  bridge->start(sim);
  Served s;
  std::atomic<bool> done = false;
  std::thread client([&] {
    s.r = testing::node_script("services_client.js", "ws://127.0.0.1:" + std::to_string(options.port) + " " + mode);
    done = true;
  });
  // the simulation thread: posted tasks at the step boundary, then a step (the client gives up
  // after 30 s, so this ends)
  while (!done) {
    if (fake) fake->run_posted();
    sim.step();
    if (fake) fake->stepped();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  client.join();
  bridge->stop();
  s.stats = bridge->stats();
  const auto end = s.r.out.find_last_not_of('\n');
  const auto start = s.r.out.rfind('\n', end);
  s.out = json::parse(s.r.out.substr(start == std::string::npos ? 0 : start + 1), nullptr, false);
  return s;
}

/// The result code of a response (-1 when it is none).
int code(const json& answer) {
  if (answer.value("kind", "") != "response") return -1;
  return answer["value"]["result"]["result"].get<int>();
}

class FoxgloveServices : public testing::NodeClientTest {};

TEST_F(FoxgloveServices, PanelCallsPauseStepReadAndTeleportThroughSimControl) {
  testing::FakeControl fake;
  const Served s = serve(&fake, "calls");
  ASSERT_EQ(s.r.exit_code, 0) << s.r.out << s.r.err;
  const json& d = s.out;
  ASSERT_TRUE(d.is_object()) << s.r.out;
  EXPECT_TRUE(d["errors"].empty()) << d["errors"];

  // offered: capability services, json among the encodings, the eight services in json
  const auto& caps = d["serverInfo"]["capabilities"];
  EXPECT_NE(std::find(caps.begin(), caps.end(), "services"), caps.end()) << caps;
  const auto& encodings = d["serverInfo"]["supportedEncodings"];
  EXPECT_NE(std::find(encodings.begin(), encodings.end(), "json"), encodings.end());
  ASSERT_EQ(d["services"].size(), 10u) << d["services"];
  const std::vector<std::string> names = {"/reset_simulation", "/get_simulation_state", "/set_simulation_state", "/step_simulation",
                                          "/get_entities",     "/get_entity_state",     "/set_entity_state",     "/get_simulator_features"};
  for (std::size_t i = 0; i < names.size(); ++i) {
    const json& svc = d["services"][i];
    EXPECT_EQ(svc["id"], i + 1);
    EXPECT_EQ(svc["name"], names[i]);
    EXPECT_EQ(svc["type"].get<std::string>().rfind("simulation_interfaces/srv/", 0), 0u) << svc["type"];
    EXPECT_EQ(svc["request"]["encoding"], "json");
    EXPECT_EQ(svc["request"]["schemaEncoding"], "jsonschema");
    EXPECT_EQ(svc["response"]["schemaName"], svc["type"].get<std::string>() + "_Response");
    EXPECT_EQ(svc["schemaTypes"], json({{"request", "object"}, {"response", "object"}}));
    EXPECT_TRUE(svc["requestSchema"].is_null());
  }

  const json& r = d["results"];
  // playing at first; paused: OK (1), then ALREADY_IN_TARGET_STATE (101); 5 steps: OK
  EXPECT_EQ(r["stateBefore"]["value"]["state"]["state"], 1) << r["stateBefore"];
  EXPECT_EQ(code(r["pause"]), 1) << r["pause"];
  EXPECT_EQ(code(r["pauseAgain"]), 101) << r["pauseAgain"];
  EXPECT_EQ(r["pauseAgain"]["value"]["result"]["error_message"], "already in that state");
  EXPECT_EQ(code(r["step"]), 1) << r["step"];
  EXPECT_EQ(r["step"]["encoding"], "json");
  EXPECT_EQ(r["stateAfter"]["value"]["state"]["state"], 2);
  // the robot's state as the fake has it, exactly
  const json& robot = r["robot"]["value"];
  EXPECT_EQ(code(r["robot"]), 1) << r["robot"];
  EXPECT_EQ(robot["state"]["header"]["stamp"], json::parse(R"({"sec": 2, "nanosec": 500000000})"));
  EXPECT_EQ(robot["state"]["header"]["frame_id"], "");
  EXPECT_EQ(robot["state"]["pose"]["position"], json::parse(R"({"x": 1.25, "y": -0.5, "z": 0.1})"));
  EXPECT_EQ(robot["state"]["pose"]["orientation"], json::parse(R"({"x": 0.0, "y": 0.0, "z": 0.6, "w": 0.8})"));
  EXPECT_EQ(robot["state"]["twist"]["linear"]["x"], 0.3);
  EXPECT_EQ(robot["state"]["twist"]["angular"]["z"], 0.5);
  EXPECT_EQ(code(r["nobody"]), 2);
  EXPECT_EQ(r["nobody"]["value"]["result"]["error_message"], "no entity 'nobody'");
  EXPECT_EQ(r["entities"]["value"]["entities"], json({"robot"}));
  EXPECT_EQ(code(r["teleport"]), 1);
  EXPECT_EQ(fake.last_set.pose.p, Vec3(2, 1, 0));
  EXPECT_EQ(code(r["reset"]), 1);
  EXPECT_EQ(r["features"]["value"]["features"]["spawn_formats"], json({"urdf", "sdf"}));
  EXPECT_EQ(r["features"]["value"]["features"]["features"].size(), 8u);
  EXPECT_EQ(code(r["afterShort"]), 1);

  // bad calls: serviceCallFailure naming the problem, with the call's ids
  const std::map<std::string, std::string> failures = {
      {"badJson", "/set_simulation_state: the request is not valid JSON (7 bytes)"},
      {"wrongShape", "/set_simulation_state: state: expected an object {\"state\": N} (a SimulationState), got 2"},
      {"unknownField", "/step_simulation: request: unknown field 'stepz' (fields: steps)"},
      {"unknownId", "unknown service id 99 (offered: 1 /reset_simulation, 2 /get_simulation_state, 3 /set_simulation_state, "
                    "4 /step_simulation, 5 /get_entities, 6 /get_entity_state, 7 /set_entity_state, 8 /get_simulator_features, 9 "
                    "/spawn_entity, 10 /delete_entity)"},
      {"wrongEncoding", "/get_simulation_state: encoding 'cdr' is not supported (its requests are json)"},
      {"truncated", "service call request: encoding length 4294967295 runs past the end (2 bytes left)"},
  };
  for (const auto& [label, message] : failures) {
    EXPECT_EQ(r[label]["kind"], "failure") << label << ": " << r[label];
    EXPECT_EQ(r[label]["message"], message) << label;
  }
  EXPECT_EQ(r["unknownId"]["serviceId"], 99);
  EXPECT_EQ(r["truncated"]["callId"], 77);
  // five bytes carry no call id: a status error instead
  EXPECT_EQ(r["shortStatus"],
            json({"a service call request needs at least 13 bytes (opcode, service id, call id, encoding length), got 5"}));

  // every control call came on the simulation thread, in the client's order; the bad calls
  // never reached it
  EXPECT_EQ(fake.foreign_thread_calls, 0);
  EXPECT_EQ(fake.calls, (std::vector<std::string>{"run_state", "set_run_state 2", "set_run_state 2", "start_steps 5", "run_state",
                                                  "entity_state robot", "entity_state nobody", "entities 'rob.*' 1",
                                                  "set_entity_state robot pose", "reset 0", "features", "run_state"}));
  EXPECT_EQ(fake.steps_run, 5u);
  // counted: 12 calls answered, 7 refused (6 failures and the 5-byte frame)
  EXPECT_EQ(s.stats.received, 12u);
  EXPECT_EQ(s.stats.rejected, 7u);
}

TEST_F(FoxgloveServices, AHostWithoutControlOffersNoServicesAndRefusesCalls) {
  const Served s = serve(nullptr, "nocontrol");
  ASSERT_EQ(s.r.exit_code, 0) << s.r.out << s.r.err;
  const json& d = s.out;
  ASSERT_TRUE(d.is_object()) << s.r.out;
  EXPECT_TRUE(d["errors"].empty()) << d["errors"];
  const auto& caps = d["serverInfo"]["capabilities"];
  EXPECT_EQ(std::find(caps.begin(), caps.end(), "services"), caps.end()) << caps;
  EXPECT_TRUE(d["services"].is_null()) << d["services"];  // no advertiseServices before the answer
  EXPECT_EQ(d["results"]["call"]["kind"], "failure");
  EXPECT_EQ(d["results"]["call"]["message"], std::string("no services: ") + control::kNoControl);
  EXPECT_EQ(s.stats.rejected, 1u);
}

TEST_F(FoxgloveServices, AnAnswerForAClientThatLeftIsDropped) {
  // the fake keeps both calls until the second connection's has come, so the first client is
  // gone when its answer is ready
  testing::FakeControl fake;
  fake.hold_until = 2;
  const Served s = serve(&fake, "vanish");
  ASSERT_EQ(s.r.exit_code, 0) << s.r.out << s.r.err;
  ASSERT_TRUE(s.out.is_object()) << s.r.out;
  EXPECT_TRUE(s.out["errors"].empty()) << s.out["errors"];
  EXPECT_EQ(s.out["results"]["second"]["value"]["state"]["state"], 1) << s.out["results"];
  EXPECT_EQ(fake.calls, (std::vector<std::string>{"run_state", "run_state"}));
  EXPECT_EQ(s.stats.received, 1u);  // only the answer that was sent
  EXPECT_EQ(s.stats.rejected, 0u);
}

}  // namespace
}  // namespace rescuesim
