// The Foxglove WebSocket protocol pieces without a network: frame layouts byte by byte, the
// server's JSON messages, and how client requests and commands are parsed and refused.

#include "bridges/foxglove/protocol.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "msgs/serialize.h"

namespace rescuesim::foxglove {
namespace {

using json = nlohmann::json;

std::span<const std::uint8_t> bytes_of(const std::string& s) { return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()}; }

/// The message text of the Error `f` throws ("" when it does not throw).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.message();
  }
  return "";
}

TEST(FoxgloveProtocol, MessageDataHeaderIsOpcodeSubscriptionAndTimestampLittleEndian) {
  const auto h = message_data_header(0x04030201u, 0x0c0b0a0908070605ull);
  const std::vector<std::uint8_t> want = {0x01, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09, 0x0a, 0x0b, 0x0c};
  EXPECT_EQ(h, want);
}

TEST(FoxgloveProtocol, TimeFrameIsOpcodeTwoAndNanoseconds) {
  const auto t = time_frame(1'500'000'000ull);  // 1.5 s = 0x59682F00 ns
  const std::vector<std::uint8_t> want = {0x02, 0x00, 0x2f, 0x68, 0x59, 0, 0, 0, 0};
  EXPECT_EQ(t, want);
}

TEST(FoxgloveProtocol, ServerInfoAndAdvertiseAreTheSpecsJson) {
  const json info = json::parse(server_info("rescuesim", {"clientPublish", "time"}, {"cdr", "json"}, {{"world", "room"}}, "42"));
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["name"], "rescuesim");
  EXPECT_EQ(info["capabilities"], json({"clientPublish", "time"}));
  EXPECT_EQ(info["supportedEncodings"], json({"cdr", "json"}));
  EXPECT_EQ(info["metadata"]["world"], "room");
  EXPECT_EQ(info["sessionId"], "42");

  const json adv = json::parse(advertise({{7, "/scan", "cdr", "sensor_msgs/msg/LaserScan", "float32 angle_min\n", "ros2msg"}}));
  EXPECT_EQ(adv["op"], "advertise");
  ASSERT_EQ(adv["channels"].size(), 1u);
  EXPECT_EQ(adv["channels"][0]["id"], 7);
  EXPECT_EQ(adv["channels"][0]["topic"], "/scan");
  EXPECT_EQ(adv["channels"][0]["encoding"], "cdr");
  EXPECT_EQ(adv["channels"][0]["schemaName"], "sensor_msgs/msg/LaserScan");
  EXPECT_EQ(adv["channels"][0]["schemaEncoding"], "ros2msg");
}

TEST(FoxgloveProtocol, StatusSurvivesInvalidUtf8FromAClient) {
  const json s = json::parse(status(StatusLevel::error, std::string("bad \xff\xfe bytes")));
  EXPECT_EQ(s["op"], "status");
  EXPECT_EQ(s["level"], 2);
  EXPECT_NE(s["message"].get<std::string>().find("bad"), std::string::npos);
}

TEST(FoxgloveProtocol, ParsesSubscribeUnsubscribeAndClientAdvertise) {
  const auto sub =
      std::get<Subscribe>(parse_client_text(R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":1,"channelId":5}]})"));
  ASSERT_EQ(sub.subscriptions.size(), 2u);
  EXPECT_EQ(sub.subscriptions[1], std::make_pair(1u, 5u));
  const auto unsub = std::get<Unsubscribe>(parse_client_text(R"({"op":"unsubscribe","subscriptionIds":[0,1]})"));
  EXPECT_EQ(unsub.subscription_ids, (std::vector<std::uint32_t>{0, 1}));
  const auto adv = std::get<ClientAdvertise>(parse_client_text(
      R"({"op":"advertise","channels":[{"id":2,"topic":"/cmd_vel","encoding":"json","schemaName":"geometry_msgs/msg/Twist"}]})"));
  ASSERT_EQ(adv.channels.size(), 1u);
  EXPECT_EQ(adv.channels[0].topic, "/cmd_vel");
  EXPECT_EQ(adv.channels[0].encoding, "json");
  EXPECT_EQ(std::get<Unsupported>(parse_client_text(R"({"op":"setParameters","parameters":[]})")).op, "setParameters");
}

TEST(FoxgloveProtocol, MalformedRequestsNameWhatIsWrong) {
  EXPECT_NE(error_of([] { parse_client_text("not json"); }).find("malformed JSON"), std::string::npos);
  EXPECT_NE(error_of([] { parse_client_text("42"); }).find("JSON object"), std::string::npos);
  EXPECT_NE(error_of([] { parse_client_text(R"({"op":7})"); }).find("'op'"), std::string::npos);
  EXPECT_NE(error_of([] { parse_client_text(R"({"op":"dance"})"); }).find("unknown op 'dance'"), std::string::npos);
  EXPECT_NE(error_of([] { parse_client_text(R"({"op":"subscribe"})"); }).find("missing 'subscriptions'"), std::string::npos);
  EXPECT_NE(error_of([] { parse_client_text(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":-3}]})"); })
                .find("subscriptions[0].channelId: expected an unsigned 32-bit integer"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_client_text(R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":1}]})"); })
                .find("subscriptions[0].id"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_client_text(R"({"op":"advertise","channels":[{"id":1,"encoding":"cdr"}]})"); }).find("missing 'topic'"),
            std::string::npos);
}

TEST(FoxgloveProtocol, ClientBinaryFramesAreCheckedBeforeUse) {
  const std::vector<std::uint8_t> good = {0x01, 0x2a, 0, 0, 0, 9, 8};
  const ClientMessage m = std::get<ClientMessage>(parse_client_binary(good));
  EXPECT_EQ(m.channel, 42u);
  ASSERT_EQ(m.payload.size(), 2u);
  EXPECT_EQ(m.payload[0], 9);
  EXPECT_NE(error_of([] { parse_client_binary({}); }).find("empty"), std::string::npos);
  const std::vector<std::uint8_t> short_frame = {0x01, 0x2a, 0};
  EXPECT_NE(error_of([&] { parse_client_binary(short_frame); }).find("at least 5 bytes"), std::string::npos);
  const std::vector<std::uint8_t> unknown = {0x7f, 0, 0, 0, 0};
  EXPECT_EQ(error_of([&] { parse_client_binary(unknown); }),
            "unknown binary opcode 0x7f (accepted: 0x01 client message data, 0x02 service call request)");
}

TEST(FoxgloveProtocol, ServiceCallRequestIsIdsEncodingAndPayload) {
  // 0x02 | service 7 | call 0x01020304 | encoding length 4 | "json" | {}
  const std::vector<std::uint8_t> frame = {0x02, 7, 0, 0, 0, 4, 3, 2, 1, 4, 0, 0, 0, 'j', 's', 'o', 'n', '{', '}'};
  const ServiceCallRequest r = std::get<ServiceCallRequest>(parse_client_binary(frame));
  EXPECT_EQ(r.service, 7u);
  EXPECT_EQ(r.call, 0x01020304u);
  EXPECT_EQ(r.encoding, "json");
  EXPECT_EQ(std::string(r.payload.begin(), r.payload.end()), "{}");
  // an empty encoding and payload are a well-formed frame (the service refuses the encoding)
  const std::vector<std::uint8_t> bare = {0x02, 1, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0};
  const ServiceCallRequest b = std::get<ServiceCallRequest>(parse_client_binary(bare));
  EXPECT_EQ(b.encoding, "");
  EXPECT_TRUE(b.payload.empty());
}

TEST(FoxgloveProtocol, MalformedServiceCallsKeepTheirIdsWhenTheyHaveThem) {
  // no call id: nobody to answer with a serviceCallFailure, a plain Error (a status reply)
  const std::vector<std::uint8_t> five = {0x02, 1, 0, 0, 0};
  try {
    parse_client_binary(five);
    ADD_FAILURE() << "no error";
  } catch (const ServiceCallError&) {
    ADD_FAILURE() << "ids from 5 bytes";
  } catch (const Error& e) {
    EXPECT_EQ(e.message(), "a service call request needs at least 13 bytes (opcode, service id, call id, encoding length), got 5");
  }
  // ids but no encoding length; an encoding length past the end (0xffffffff, 2 bytes left)
  const std::vector<std::uint8_t> ten = {0x02, 3, 0, 0, 0, 9, 0, 0, 0, 4};
  const std::vector<std::uint8_t> absurd = {0x02, 3, 0, 0, 0, 9, 0, 0, 0, 0xff, 0xff, 0xff, 0xff, '{', '}'};
  for (const auto* frame : {&ten, &absurd}) {
    try {
      parse_client_binary(*frame);
      ADD_FAILURE() << "no error";
    } catch (const ServiceCallError& e) {
      EXPECT_EQ(e.service, 3u);
      EXPECT_EQ(e.call, 9u);
      EXPECT_EQ(e.message(), frame == &ten
                                 ? "a service call request needs at least 13 bytes (opcode, service id, call id, encoding length), got 10"
                                 : "service call request: encoding length 4294967295 runs past the end (2 bytes left)");
    }
  }
}

TEST(FoxgloveProtocol, ServiceFramesAreTheSpecsLayout) {
  // 0x03 | service 2 | call 0x0a0b0c0d | length 4 | "json" | {"a":1}
  const std::vector<std::uint8_t> want = {0x03, 2,   0,   0,   0,   0x0d, 0x0c, 0x0b, 0x0a, 4,   0,   0,  0,
                                          'j',  's', 'o', 'n', '{', '"',  'a',  '"',  ':',  '1', '}'};
  EXPECT_EQ(service_call_response(2, 0x0a0b0c0d, "json", R"({"a":1})"), want);

  const json failure = json::parse(service_call_failure(4, 11, "unknown service id 4"));
  EXPECT_EQ(failure, json::parse(R"({"op": "serviceCallFailure", "serviceId": 4, "callId": 11, "message": "unknown service id 4"})"));
  // a message quoting a client's bytes that are not UTF-8 is still sent (the byte replaced)
  EXPECT_EQ(json::parse(service_call_failure(4, 11, "encoding '\xff'"))["message"], "encoding '\xef\xbf\xbd'");

  Service s;
  s.id = 3;
  s.name = "/set_simulation_state";
  s.type = "simulation_interfaces/srv/SetSimulationState";
  s.request = {"json", s.type + "_Request", "jsonschema", R"({"type":"object","properties":{}})"};
  s.response = {"json", s.type + "_Response", "jsonschema", "{}"};
  const json adv = json::parse(advertise_services({s}));
  EXPECT_EQ(adv["op"], "advertiseServices");
  ASSERT_EQ(adv["services"].size(), 1u);
  const json& j = adv["services"][0];
  EXPECT_EQ(j["id"], 3);
  EXPECT_EQ(j["name"], "/set_simulation_state");
  EXPECT_EQ(j["type"], "simulation_interfaces/srv/SetSimulationState");
  EXPECT_EQ(j["request"], json::parse(R"({"encoding": "json", "schemaName": "simulation_interfaces/srv/SetSimulationState_Request",
      "schemaEncoding": "jsonschema", "schema": "{\"type\":\"object\",\"properties\":{}}"})"));
  EXPECT_EQ(j["response"]["schemaName"], "simulation_interfaces/srv/SetSimulationState_Response");
  // the older string form is not sent: clients would read it in the wrong encoding
  EXPECT_FALSE(j.contains("requestSchema"));
  EXPECT_FALSE(j.contains("responseSchema"));
}

TEST(FoxgloveProtocol, DecodesTwistFromCdrAndJson) {
  msg::Twist t;
  t.linear = Vec3(0.3, 0, 0);
  t.angular = Vec3(0, 0, -0.5);
  std::vector<std::uint8_t> cdr;
  msg::to_cdr(msg::Message{t}, cdr);
  ASSERT_EQ(cdr.size(), 4u + 6 * 8);  // encapsulation + six float64
  const msg::Twist from_cdr = decode_twist("cdr", cdr);
  EXPECT_EQ(from_cdr.linear, t.linear);
  EXPECT_EQ(from_cdr.angular, t.angular);

  const msg::Twist from_json = decode_twist("json", bytes_of(R"({"linear":{"x":0.3,"y":0,"z":0},"angular":{"x":0,"y":0,"z":-0.5}})"));
  EXPECT_EQ(from_json.linear, t.linear);
  EXPECT_EQ(from_json.angular, t.angular);
  // fields left out are zero, as a teleop panel that sets only some would mean
  EXPECT_EQ(decode_twist("json", bytes_of(R"({"angular":{"z":1}})")).angular.z(), 1.0);
}

TEST(FoxgloveProtocol, MalformedCommandsAreErrorsNotCrashes) {
  std::vector<std::uint8_t> cdr;
  msg::to_cdr(msg::Message{msg::Twist{}}, cdr);
  cdr.resize(20);
  EXPECT_NE(error_of([&] { decode_twist("cdr", cdr); }), "");
  EXPECT_NE(error_of([] { decode_twist("json", bytes_of("{")); }).find("not valid JSON"), std::string::npos);
  EXPECT_NE(error_of([] { decode_twist("json", bytes_of(R"({"linear":{"x":"fast"}})")); }).find("linear.x"), std::string::npos);
  EXPECT_NE(error_of([] { decode_twist("json", bytes_of(R"({"linear":[1,2,3]})")); }).find("linear"), std::string::npos);
  EXPECT_NE(error_of([] { decode_twist("protobuf", bytes_of("")); }).find("encoding"), std::string::npos);
  EXPECT_NE(error_of([] { decode_multi_array("json", bytes_of(R"({"data":[1,"two"]})")); }).find("data[1]"), std::string::npos);
  EXPECT_NE(error_of([] { decode_multi_array("json", bytes_of(R"({"layout":{}})")); }).find("missing 'data'"), std::string::npos);
}

TEST(FoxgloveProtocol, DecodesHeadCommandFromCdrAndJson) {
  msg::Float64MultiArray a;
  a.data = {0.1, -0.2, 0.3, 0.0};
  std::vector<std::uint8_t> cdr;
  msg::to_cdr(msg::Message{a}, cdr);
  EXPECT_EQ(decode_multi_array("cdr", cdr).data, a.data);
  EXPECT_EQ(decode_multi_array("json", bytes_of(R"({"layout":{"dim":[],"data_offset":0},"data":[0.1,-0.2,0.3,0]})")).data, a.data);
}

TEST(FoxgloveProtocol, DecodesJointStateFromCdrAndJson) {
  msg::JointState js;
  js.header = {SimTime::from_seconds(1.5), "base_footprint"};
  js.name = {"lift", "spin"};
  js.position = {0.15, 0.0};
  js.velocity = {0.0, -1.25};
  std::vector<std::uint8_t> cdr;
  msg::to_cdr(msg::Message{js}, cdr);
  const msg::JointState from_cdr = decode_joint_state("cdr", cdr);
  EXPECT_EQ(from_cdr.name, js.name);
  EXPECT_EQ(from_cdr.position, js.position);
  EXPECT_EQ(from_cdr.velocity, js.velocity);
  EXPECT_TRUE(from_cdr.effort.empty());

  // JSON as Foxglove writes it (header and all), or just the fields that matter
  const msg::JointState full = decode_joint_state(
      "json", bytes_of(R"({"header":{"stamp":{"sec":1,"nsec":500000000},"frame_id":""},"name":["lift","spin"],)"
                       R"("position":[0.15,0],"velocity":[0,-1.25],"effort":[]})"));
  EXPECT_EQ(full.name, js.name);
  EXPECT_EQ(full.position, js.position);
  EXPECT_EQ(full.velocity, js.velocity);
  const msg::JointState brief = decode_joint_state("json", bytes_of(R"({"name":["lift"],"position":[0.15]})"));
  EXPECT_EQ(brief.name, std::vector<std::string>{"lift"});
  EXPECT_EQ(brief.position, std::vector<double>{0.15});
  EXPECT_TRUE(brief.velocity.empty());
  EXPECT_TRUE(brief.effort.empty());
}

TEST(FoxgloveProtocol, MalformedJointStatesAreErrorsThatSayWhere) {
  msg::JointState js;
  js.name = {"lift"};
  js.position = {0.15};
  std::vector<std::uint8_t> cdr;
  msg::to_cdr(msg::Message{js}, cdr);
  // every truncation of the CDR bytes is an error, never a read past the end
  for (std::size_t n = 0; n < cdr.size(); ++n) {
    const std::vector<std::uint8_t> cut(cdr.begin(), cdr.begin() + static_cast<std::ptrdiff_t>(n));
    EXPECT_NE(error_of([&] { decode_joint_state("cdr", cut); }), "") << n << " bytes";
  }
  EXPECT_NE(error_of([] { decode_joint_state("json", bytes_of("[1]")); }).find("JSON object"), std::string::npos);
  EXPECT_NE(error_of([] { decode_joint_state("json", bytes_of(R"({"position":[0.1]})")); }).find("missing 'name'"), std::string::npos);
  EXPECT_NE(error_of([] { decode_joint_state("json", bytes_of(R"({"name":"lift"})")); }).find("name: expected an array"),
            std::string::npos);
  EXPECT_NE(error_of([] { decode_joint_state("json", bytes_of(R"({"name":[3]})")); }).find("name[0]: expected a string"),
            std::string::npos);
  EXPECT_NE(error_of([] { decode_joint_state("json", bytes_of(R"({"name":["lift"],"position":["high"]})")); })
                .find("sensor_msgs/JointState: position[0]: expected a number"),
            std::string::npos);
  // null is how to_json writes a non-finite value: it reads as NaN, which the command gate refuses
  EXPECT_TRUE(std::isnan(decode_joint_state("json", bytes_of(R"({"name":["lift"],"velocity":[null]})")).velocity.at(0)));
  EXPECT_NE(error_of([] { decode_joint_state("json", bytes_of(R"({"name":["lift"],"effort":{}})")); }).find("effort: expected an array"),
            std::string::npos);
  EXPECT_NE(error_of([] { decode_joint_state("json", bytes_of(R"({"header":7,"name":[]})")); }).find("header"), std::string::npos);
  EXPECT_NE(error_of([] { decode_joint_state("protobuf", bytes_of("")); }).find("encoding"), std::string::npos);
}

}  // namespace
}  // namespace rescuesim::foxglove
