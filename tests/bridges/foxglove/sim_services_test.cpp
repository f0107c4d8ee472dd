// The Simulation Interfaces as Foxglove services without a network: what is advertised (names,
// types, JSON Schemas a Foxglove client can read), how requests decode and are refused (the
// message names the service and the field), the response texts with the standard's field
// names, and what a call does on a SimControl (the fake of fake_control.h).

#include "bridges/foxglove/sim_services.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

#include "bridges/foxglove/fake_control.h"
#include "core/error.h"

namespace rescuesim::foxglove {
namespace {

using json = nlohmann::json;

std::span<const std::uint8_t> bytes_of(const std::string& s) { return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()}; }

SimRequest decode(SimService s, const std::string& text) { return decode_sim_request(s, bytes_of(text)); }

/// The message of the Error decoding `text` throws ("" when it decodes).
std::string error_of(SimService s, const std::string& text) {
  try {
    decode(s, text);
  } catch (const Error& e) {
    return e.message();
  }
  return "";
}

/// Why Foxglove's JSON Schema reader (Lichtblick packages/mcap-support parseJsonSchema, the same
/// in Foxglove) would refuse `schema`, or "": an object with "properties", each property of one
/// type: boolean, string, number, integer, object (recursively), array of typed items.
std::string unreadable(const json& schema, const std::string& where) {
  if (!schema.is_object() || schema.value("type", "") != "object") return where + ": not \"type\": \"object\"";
  if (!schema.contains("properties") || !schema["properties"].is_object()) return where + ": no properties";
  for (const auto& [name, field] : schema["properties"].items()) {
    const std::string at = where + "." + name;
    if (!field.contains("type") || !field["type"].is_string()) return at + ": no single type";
    const std::string type = field["type"];
    if (type == "object") {
      if (auto why = unreadable(field, at); !why.empty()) return why;
    } else if (type == "array") {
      if (!field.contains("items") || !field["items"].contains("type")) return at + ": array without typed items";
      const std::string item = field["items"]["type"];
      if (item == "object") {
        if (auto why = unreadable(field["items"], at + "[]"); !why.empty()) return why;
      } else if (item != "boolean" && item != "string" && item != "number" && item != "integer") {
        return at + ": array of " + item;
      }
    } else if (type != "boolean" && type != "string" && type != "number" && type != "integer") {
      return at + ": type " + type;
    }
  }
  return "";
}

TEST(FoxgloveSimServices, AdvertisedWithRootLevelRos2NamesTypesAndJsonSchemas) {
  const auto& services = sim_services();
  ASSERT_EQ(services.size(), kSimServiceCount);
  const std::vector<std::pair<std::string, std::string>> want = {
      {"/reset_simulation", "ResetSimulation"},   {"/get_simulation_state", "GetSimulationState"},
      {"/set_simulation_state", "SetSimulationState"}, {"/step_simulation", "StepSimulation"},
      {"/get_entities", "GetEntities"},           {"/get_entity_state", "GetEntityState"},
      {"/set_entity_state", "SetEntityState"},    {"/get_simulator_features", "GetSimulatorFeatures"},
      {"/spawn_entity", "SpawnEntity"},           {"/delete_entity", "DeleteEntity"}};
  ASSERT_EQ(want.size(), kSimServiceCount);
  for (std::size_t i = 0; i < services.size(); ++i) {
    const Service& s = services[i];
    EXPECT_EQ(s.id, i + 1);
    EXPECT_EQ(s.name, want[i].first);
    EXPECT_EQ(s.type, "simulation_interfaces/srv/" + want[i].second);
    EXPECT_EQ(sim_service_of(s.id), static_cast<SimService>(i));
    for (const auto& [m, suffix] : {std::pair{&s.request, "_Request"}, std::pair{&s.response, "_Response"}}) {
      EXPECT_EQ(m->encoding, "json");
      EXPECT_EQ(m->schema_encoding, "jsonschema");
      EXPECT_EQ(m->schema_name, s.type + suffix);
      const json schema = json::parse(m->schema);
      EXPECT_EQ(unreadable(schema, m->schema_name), "");
    }
  }
  EXPECT_FALSE(sim_service_of(0));
  EXPECT_FALSE(sim_service_of(11));
  // the standard's field names, e.g. SetEntityState's request and GetEntityState's response
  const json set = json::parse(services[6].request.schema)["properties"];
  EXPECT_TRUE(set.contains("entity") && set.contains("state") && set.contains("set_pose"));
  EXPECT_TRUE(set["state"]["properties"]["pose"]["properties"]["orientation"]["properties"].contains("w"));
  const json got = json::parse(services[5].response.schema)["properties"];
  EXPECT_TRUE(got["result"]["properties"].contains("error_message"));
  EXPECT_TRUE(got["state"]["properties"]["header"]["properties"]["stamp"]["properties"].contains("nanosec"));
  EXPECT_TRUE(json::parse(services[7].response.schema)["properties"]["features"]["properties"].contains("spawn_formats"));
}

TEST(FoxgloveSimServices, DecodesEachRequestWithItsDefaults) {
  EXPECT_EQ(std::get<ResetRequest>(decode(SimService::reset_simulation, "{}")).scope, 0);
  EXPECT_EQ(std::get<ResetRequest>(decode(SimService::reset_simulation, R"({"scope": 6})")).scope, 6);
  EXPECT_EQ(std::get<SetSimulationStateRequest>(decode(SimService::set_simulation_state, R"({"state": {"state": 2}})")).state,
            control::RunState::paused);
  EXPECT_EQ(std::get<StepRequest>(decode(SimService::step_simulation, "{}")).steps, 1u);  // the .srv's default
  EXPECT_EQ(std::get<StepRequest>(decode(SimService::step_simulation, R"({"steps": 5})")).steps, 5u);
  EXPECT_EQ(std::get<StepRequest>(decode(SimService::step_simulation, R"({"steps": 18446744073709551615})")).steps, 18446744073709551615u);
  EXPECT_EQ(std::get<StepRequest>(decode(SimService::step_simulation, R"({"steps": 5.0})")).steps, 5u);
  EXPECT_EQ(std::get<GetEntityStateRequest>(decode(SimService::get_entity_state, R"({"entity": "robot"})")).entity, "robot");
  // an empty payload is {}, as a client with nothing to say may send it
  EXPECT_TRUE(std::holds_alternative<GetSimulationStateRequest>(decode(SimService::get_simulation_state, "")));
  EXPECT_TRUE(std::holds_alternative<GetSimulatorFeaturesRequest>(decode(SimService::get_simulator_features, "{}")));

  const auto f = std::get<GetEntitiesRequest>(decode(SimService::get_entities, R"({"filters": {"filter": "rob.*",
      "categories": [{"category": 1}, {"category": 2}], "tags": {"tags": ["red"], "filter_mode": 1},
      "bounds": {"type": 3, "points": [{"x": 1, "y": 2, "z": 0}, {"x": 0.5}]}}})")).filters;
  EXPECT_EQ(f.filter, "rob.*");
  EXPECT_EQ(f.categories, (std::vector<std::uint8_t>{1, 2}));
  EXPECT_EQ(f.tags.tags, std::vector<std::string>{"red"});
  EXPECT_EQ(f.tags.filter_mode, 1);
  EXPECT_EQ(f.bounds.type, control::Bounds::kSphere);
  ASSERT_EQ(f.bounds.points.size(), 2u);
  EXPECT_EQ(f.bounds.points[0], Vec3(1, 2, 0));
  EXPECT_EQ(f.bounds.points[1], Vec3(0.5, 0, 0));  // a sphere of radius 0.5
}

TEST(FoxgloveSimServices, SetEntityStateSetsWhatIsGivenOrWhatTheFlagsSay) {
  // 1.x shape: no flags; a pose alone sets the pose (an orientation left out is the identity)
  auto r = std::get<SetEntityStateRequest>(decode(SimService::set_entity_state, R"({"entity": "robot",
      "state": {"header": {"stamp": {"sec": 3, "nanosec": 5}, "frame_id": "map"}, "pose": {"position": {"x": 2, "y": 1}}}})"));
  EXPECT_EQ(r.entity, "robot");
  EXPECT_TRUE(r.set_pose);
  EXPECT_FALSE(r.set_twist);
  EXPECT_FALSE(r.set_acceleration);
  EXPECT_EQ(r.state.frame_id, "map");
  EXPECT_EQ(r.state.stamp_ns, 3'000'000'005);
  EXPECT_EQ(r.state.pose.p, Vec3(2, 1, 0));
  EXPECT_EQ(r.state.pose.q.coeffs(), Quat::Identity().coeffs());
  // a twist too, and an orientation (z, w): both set
  r = std::get<SetEntityStateRequest>(decode(SimService::set_entity_state, R"({"entity": "robot", "state": {
      "pose": {"orientation": {"z": 0.6, "w": 0.8}}, "twist": {"linear": {"x": 0.3}, "angular": {"z": -0.5}}}})"));
  EXPECT_TRUE(r.set_pose && r.set_twist && !r.set_acceleration);
  EXPECT_EQ(r.state.pose.q.coeffs(), Quat(0.8, 0, 0, 0.6).coeffs());
  EXPECT_EQ(r.state.linear, Vec3(0.3, 0, 0));
  EXPECT_EQ(r.state.angular, Vec3(0, 0, -0.5));
  // 2.x flags: as given, a flag left out is false, whatever state holds
  r = std::get<SetEntityStateRequest>(decode(SimService::set_entity_state, R"({"entity": "robot",
      "state": {"pose": {}, "twist": {}}, "set_twist": true})"));
  EXPECT_FALSE(r.set_pose);
  EXPECT_TRUE(r.set_twist);
  // null in a float field is NaN, for SimControl to refuse (INVALID_POSE)
  r = std::get<SetEntityStateRequest>(
      decode(SimService::set_entity_state, R"({"entity": "robot", "state": {"pose": {"position": {"x": null}}}})"));
  EXPECT_TRUE(std::isnan(r.state.pose.p.x()));
  EXPECT_EQ(
      error_of(SimService::set_entity_state, R"({"entity": "robot", "state": {}})"),
      "/set_entity_state: nothing to set: give state.pose, state.twist or state.acceleration (or set_pose, set_twist, set_acceleration)");
}

TEST(FoxgloveSimServices, MalformedRequestsNameTheServiceAndTheField) {
  EXPECT_EQ(error_of(SimService::set_simulation_state, "{state:"), "/set_simulation_state: the request is not valid JSON (7 bytes)");
  EXPECT_EQ(error_of(SimService::set_simulation_state, "[1]"), "/set_simulation_state: request: expected an object, got [1]");
  EXPECT_EQ(error_of(SimService::set_simulation_state, R"({"state": 2})"),
            "/set_simulation_state: state: expected an object {\"state\": N} (a SimulationState), got 2");
  EXPECT_EQ(error_of(SimService::set_simulation_state, "{}"),
            "/set_simulation_state: state: missing (a SimulationState: {\"state\": 2} pauses)");
  EXPECT_EQ(error_of(SimService::set_simulation_state, R"({"state": {"state": "paused"}})"),
            "/set_simulation_state: state.state: expected an integer 0..5 (a SimulationState: 0 STOPPED, 1 PLAYING, 2 PAUSED, 3 QUITTING, "
            "4 NO_WORLD, 5 LOADING_WORLD), got \"paused\"");
  EXPECT_NE(error_of(SimService::set_simulation_state, R"({"state": {"state": 6}})").find("expected an integer 0..5"), std::string::npos);
  EXPECT_EQ(error_of(SimService::step_simulation, R"({"stepz": 5})"), "/step_simulation: request: unknown field 'stepz' (fields: steps)");
  EXPECT_EQ(error_of(SimService::step_simulation, R"({"steps": -1})"),
            "/step_simulation: steps: expected an integer 0..18446744073709551615, got -1");
  EXPECT_EQ(error_of(SimService::step_simulation, R"({"steps": 1.5})"),
            "/step_simulation: steps: expected an integer 0..18446744073709551615, got 1.5");
  EXPECT_EQ(error_of(SimService::reset_simulation, R"({"scope": 256})"),
            "/reset_simulation: scope: expected an integer 0..255 (a bit field), got 256");
  EXPECT_EQ(error_of(SimService::get_simulation_state, R"({"x": 1})"),
            "/get_simulation_state: request: unknown field 'x' (it has no fields)");
  EXPECT_EQ(error_of(SimService::get_entity_state, "{}"), "/get_entity_state: entity: missing (a string)");
  EXPECT_EQ(error_of(SimService::get_entity_state, R"({"entity": 7})"), "/get_entity_state: entity: expected a string, got 7");
  EXPECT_EQ(error_of(SimService::get_entities, R"({"filters": {"categories": [1]}})"),
            "/get_entities: filters.categories[0]: expected an object, got 1");
  EXPECT_EQ(error_of(SimService::set_entity_state, R"({"entity": "robot", "state": {"pose": {"position": {"x": "far"}}}})"),
            "/set_entity_state: state.pose.position.x: expected a number, got \"far\"");
  EXPECT_EQ(error_of(SimService::set_entity_state, R"({"entity": "robot", "state": {"pose": {}}, "set_pose": 1})"),
            "/set_entity_state: set_pose: expected true or false, got 1");
}

TEST(FoxgloveSimServices, ResponsesUseTheStandardsFieldNames) {
  SimResponse r;
  r.service = SimService::get_simulation_state;
  r.state = control::RunState::paused;
  EXPECT_EQ(json::parse(encode_sim_response(r)), json::parse(R"({"state": {"state": 2}, "result": {"result": 1, "error_message": ""}})"));

  r = {};
  r.service = SimService::set_simulation_state;
  r.result = control::Result::fail(control::code::kAlreadyInTargetState, "already paused");
  EXPECT_EQ(json::parse(encode_sim_response(r)), json::parse(R"({"result": {"result": 101, "error_message": "already paused"}})"));

  r = {};
  r.service = SimService::get_entity_state;
  r.entity_state.stamp_ns = -1'500'000'000;  // -1.5 s = -2 s + 0.5 s
  r.entity_state.frame_id = "map";
  r.entity_state.pose.p = Vec3(1, 2, 3);
  r.entity_state.pose.q = Quat(0.8, 0, 0, 0.6);
  r.entity_state.linear = Vec3(0.25, 0, 0);
  r.entity_state.angular_acc = Vec3(0, 0, -1);
  EXPECT_EQ(json::parse(encode_sim_response(r)), json::parse(R"({"result": {"result": 1, "error_message": ""}, "state": {
      "header": {"stamp": {"sec": -2, "nanosec": 500000000}, "frame_id": "map"},
      "pose": {"position": {"x": 1.0, "y": 2.0, "z": 3.0}, "orientation": {"x": 0.0, "y": 0.0, "z": 0.6, "w": 0.8}},
      "twist": {"linear": {"x": 0.25, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.0}},
      "acceleration": {"linear": {"x": 0.0, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": -1.0}}}})"));

  r = {};
  r.service = SimService::get_entities;
  r.entities = {"robot", "alice"};
  EXPECT_EQ(json::parse(encode_sim_response(r))["entities"], json({"robot", "alice"}));

  // GetSimulatorFeatures has no Result
  r = {};
  r.service = SimService::get_simulator_features;
  r.features = {{20, 24}, {"urdf"}, "rescuesim"};
  EXPECT_EQ(json::parse(encode_sim_response(r)),
            json::parse(R"({"features": {"features": [20, 24], "spawn_formats": ["urdf"], "custom_info": "rescuesim"}})"));

  // a message quoting bytes that are not UTF-8 is still sent
  r = {};
  r.service = SimService::get_entity_state;
  r.result = control::Result::fail(control::code::kNotFound, "no entity '\xff'");
  EXPECT_NE(encode_sim_response(r).find("no entity"), std::string::npos);
}

TEST(FoxgloveSimServices, CallsRunOnTheControlAndStepsAnswerWhenDone) {
  testing::FakeControl fake;
  std::vector<SimResponse> replies;
  const auto reply = [&](SimResponse r) { replies.push_back(std::move(r)); };

  // stepping while playing is refused at once with OPERATION_FAILED (the service's code)
  run_sim_request(StepRequest{3}, fake, reply);
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].service, SimService::step_simulation);
  EXPECT_EQ(replies[0].result.result, control::code::kOperationFailed);

  run_sim_request(SetSimulationStateRequest{control::RunState::paused}, fake, reply);
  EXPECT_EQ(replies.back().result.result, control::code::kOk);
  // accepted: no answer until its three steps have run
  run_sim_request(StepRequest{3}, fake, reply);
  EXPECT_EQ(replies.size(), 2u);
  fake.stepped();
  fake.stepped();
  EXPECT_EQ(replies.size(), 2u);
  fake.stepped();
  ASSERT_EQ(replies.size(), 3u);
  EXPECT_EQ(replies[2].service, SimService::step_simulation);
  EXPECT_EQ(replies[2].result.result, control::code::kOk);

  run_sim_request(GetEntityStateRequest{"robot"}, fake, reply);
  EXPECT_EQ(replies.back().entity_state.pose.p, fake.robot.pose.p);
  run_sim_request(GetEntityStateRequest{"nobody"}, fake, reply);
  EXPECT_EQ(replies.back().result.result, control::code::kNotFound);
  EXPECT_EQ(replies.back().result.error_message, "no entity 'nobody'");
  run_sim_request(GetSimulationStateRequest{}, fake, reply);
  EXPECT_EQ(replies.back().state, control::RunState::paused);
  run_sim_request(ResetRequest{2}, fake, reply);
  run_sim_request(GetSimulatorFeaturesRequest{}, fake, reply);
  EXPECT_EQ(replies.back().features.spawn_formats, (std::vector<std::string>{"urdf", "sdf"}));
  SetEntityStateRequest set;
  set.entity = "robot";
  set.set_twist = true;
  set.state.linear = Vec3(0.1, 0, 0);
  run_sim_request(set, fake, reply);
  EXPECT_EQ(fake.last_set.linear, Vec3(0.1, 0, 0));
  EXPECT_EQ(replies.size(), 9u);
  EXPECT_EQ(fake.calls,
            (std::vector<std::string>{"start_steps 3", "set_run_state 2", "start_steps 3", "entity_state robot", "entity_state nobody",
                                      "run_state", "reset 2", "features", "set_entity_state robot twist"}));
}


TEST(FoxgloveSimServices, SpawnTakesBothWireVersionsAndDeleteNamesItsEntity) {
  const auto bytes = [](const std::string& text) { return std::vector<std::uint8_t>(text.begin(), text.end()); };
  // 1.x: uri at the top; a PoseStamped whose frame is an entity
  const SimRequest one = decode_sim_request(
      SimService::spawn_entity,
      bytes(R"({"name": "p3at", "uri": "rescue_robot", "allow_renaming": true, "entity_namespace": "/team/p3at",)"
            R"( "initial_pose": {"header": {"frame_id": "robot"}, "pose": {"position": {"x": 3.0, "y": 1.0}}}})"));
  const control::SpawnRequest& a = std::get<SpawnEntityRequest>(one).spawn;
  EXPECT_EQ(a.name, "p3at");
  EXPECT_EQ(a.uri, "rescue_robot");
  EXPECT_TRUE(a.allow_renaming);
  EXPECT_EQ(a.entity_namespace, "/team/p3at");
  EXPECT_EQ(a.frame_id, "robot");
  EXPECT_EQ(a.pose.p, Vec3(3, 1, 0));
  EXPECT_EQ(a.pose.q.w(), 1.0);  // the orientation left out is the identity
  // 2.x: a Resource
  const SimRequest two =
      decode_sim_request(SimService::spawn_entity, bytes(R"({"name": "b", "resource": {"resource_string": "<robot/>"}})"));
  EXPECT_EQ(std::get<SpawnEntityRequest>(two).spawn.resource_string, "<robot/>");
  EXPECT_TRUE(std::get<SpawnEntityRequest>(two).spawn.uri.empty());
  try {
    decode_sim_request(SimService::spawn_entity, bytes(R"({"name": "b", "pose": {}})"));
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/spawn_entity: request: unknown field 'pose'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(decode_sim_request(SimService::delete_entity, bytes("{}")), Error);

  testing::FakeControl fake;
  std::vector<SimResponse> replies;
  run_sim_request(one, fake, [&](SimResponse r) { replies.push_back(std::move(r)); });
  run_sim_request(DeleteEntityRequest{"p3at_1"}, fake, [&](SimResponse r) { replies.push_back(std::move(r)); });
  ASSERT_EQ(replies.size(), 2u);
  EXPECT_EQ(fake.calls, (std::vector<std::string>{"spawn p3at rescue_robot robot 3", "remove p3at_1"}));
  EXPECT_EQ(json::parse(encode_sim_response(replies[0])),
            json::parse(R"({"result": {"result": 1, "error_message": ""}, "entity_name": "p3at_1"})"));
  EXPECT_EQ(json::parse(encode_sim_response(replies[1])), json::parse(R"({"result": {"result": 1, "error_message": ""}})"));
}

}  // namespace
}  // namespace rescuesim::foxglove
