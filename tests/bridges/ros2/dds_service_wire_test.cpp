// rmw_cyclonedds's service wire worked out by hand: the 16-byte request header after the
// encapsulation, the body as a message of its own, the names and the client/service ids.

#include "bridges/ros2/dds_service_wire.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace rescuesim::ros2 {
namespace {

using Bytes = std::vector<std::uint8_t>;

// simulation_interfaces/srv/ResetSimulation request {uint8 scope = 2} from client guid
// 0x0102030405060708, sequence number 5, little endian
const Bytes kRequest = {0x00, 0x01, 0x00, 0x00,                          // encapsulation CDR_LE
                        0x08, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01,  // uint64 guid
                        0x05, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // int64 seq
                        0x02};                                           // uint8 scope

TEST(ServiceWire, ARequestSplitsIntoItsHeaderAndAStandaloneBody) {
  std::string why;
  const auto s = split_service_sample(kRequest, &why);
  ASSERT_TRUE(s) << why;
  EXPECT_EQ(s->header.guid, 0x0102030405060708u);
  EXPECT_EQ(s->header.seq, 5);
  EXPECT_EQ(s->body, (Bytes{0x00, 0x01, 0x00, 0x00, 0x02}));
}

TEST(ServiceWire, AReplyEchoesTheHeaderBeforeItsBodyWithTheBodysAlignment) {
  // ResetSimulation response {Result {uint8 result = 1; string error_message = ""}} on its own:
  // result at 0, padding to 4, the string's length 1 at 4, its NUL at 8
  const Bytes body = {0x00, 0x01, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00};
  const Bytes reply = join_service_sample({0x0102030405060708u, 5}, body);
  // in the reply the result sits at 16 and the length at 20: both offsets 16 further, so the
  // same padding, because 16 is a multiple of 8
  const Bytes expected = {0x00, 0x01, 0x00, 0x00,                          //
                          0x08, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01,  // guid echoed
                          0x05, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // seq echoed
                          0x01, 0x00, 0x00, 0x00,                          // result, padding
                          0x01, 0x00, 0x00, 0x00, 0x00};                   // "" (length 1, NUL)
  EXPECT_EQ(reply, expected);
  const auto back = split_service_sample(reply);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->body, body);
}

TEST(ServiceWire, ABigEndianRequestIsReadInItsOwnByteOrder) {
  const Bytes request = {0x00, 0x00, 0x00, 0x00,                          // CDR_BE
                         0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08,  //
                         0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x07};
  const auto s = split_service_sample(request);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->header, (RequestHeader{0x0102030405060708u, 7}));
  EXPECT_EQ(s->body, (Bytes{0x00, 0x00, 0x00, 0x00}));
  // and a big-endian body gets a big-endian header
  EXPECT_EQ(join_service_sample({0x0102030405060708u, 7}, s->body), request);
}

TEST(ServiceWire, ShortAndNonXcdr1SamplesAreRefusedWithAReason) {
  std::string why;
  EXPECT_FALSE(split_service_sample(Bytes(kRequest.begin(), kRequest.begin() + 19), &why));
  EXPECT_NE(why.find("19 bytes, shorter than the encapsulation and request headers"), std::string::npos) << why;
  Bytes xcdr2 = kRequest;
  xcdr2[1] = 0x07;
  EXPECT_FALSE(split_service_sample(xcdr2, &why));
  EXPECT_NE(why.find("is not XCDR1"), std::string::npos) << why;
  EXPECT_FALSE(split_service_sample({}, &why));
  // a header and no body is a request of an empty body: the codec above judges that
  EXPECT_TRUE(split_service_sample(Bytes(kRequest.begin(), kRequest.begin() + 20)));
  EXPECT_THROW(join_service_sample({}, Bytes{0x01, 0x02}), Error);
}

TEST(ServiceWire, NamesAndTypesFollowRmw) {
  const ServiceTopics t = service_topics("/reset_simulation", "simulation_interfaces/srv/ResetSimulation");
  EXPECT_EQ(t.name, "/reset_simulation");
  EXPECT_EQ(t.request_topic, "rq/reset_simulationRequest");
  EXPECT_EQ(t.reply_topic, "rr/reset_simulationReply");
  EXPECT_EQ(t.request_type, "simulation_interfaces::srv::dds_::ResetSimulation_Request_");
  EXPECT_EQ(t.reply_type, "simulation_interfaces::srv::dds_::ResetSimulation_Response_");
  EXPECT_EQ(service_topics("gzserver/step_simulation", "simulation_interfaces/srv/StepSimulation").request_topic,
            "rq/gzserver/step_simulationRequest");
  EXPECT_EQ(dds_type_name("action_msgs/msg/GoalStatusArray"), "action_msgs::msg::dds_::GoalStatusArray_");
  const EndpointQos q = service_qos();
  EXPECT_EQ(q.reliability, Reliability::reliable);
  EXPECT_EQ(q.durability, Durability::volatile_local);
  EXPECT_EQ(q.depth, 10);
}

TEST(ServiceWire, BadNamesAndTypesSayWhatIsWrong) {
  const auto message = [](auto f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([] { service_topics("/a b", "pkg/srv/T"); }).find("character ' '"), std::string::npos);
  EXPECT_NE(message([] { service_topics("/a//b", "pkg/srv/T"); }).find("contains '//'"), std::string::npos);
  EXPECT_NE(message([] { service_topics("/", "pkg/srv/T"); }).find("empty"), std::string::npos);
  EXPECT_NE(message([] { service_topics("/a/", "pkg/srv/T"); }).find("ends with '/'"), std::string::npos);
  EXPECT_NE(message([] { service_topics("/a", "pkg/T"); }).find("expected package/kind/Name"), std::string::npos);
  EXPECT_NE(message([] { service_topics("/a", "pkg/msg/T"); }).find("expected package/srv/Name"), std::string::npos);
}

TEST(ServiceWire, ClientAndServiceIdsArePrefixAndBigEndianCounterInRmwsHex) {
  // rmw_cyclonedds: the first byte through std::setw(2) (space filled), then "." and each byte
  // in hex without leading zeros; the last four bytes are the counter, big endian
  const Guid p = {0x01, 0x0f, 0xa2, 0x3b, 0x00, 0x10, 0x20, 0x30, 0xff, 0x0a, 0x0b, 0x0c, 0x00, 0x00, 0x01, 0xc1};
  EXPECT_EQ(client_service_id(p, 0x01020304u), " 1.f.a2.3b.0.10.20.30.ff.a.b.c.1.2.3.4");
  Guid q = p;
  q[0] = 0xab;
  EXPECT_EQ(client_service_id(q, 2), "ab.f.a2.3b.0.10.20.30.ff.a.b.c.0.0.0.2");
  EXPECT_EQ(service_user_data("x"), "serviceid=x;");
  EXPECT_EQ(client_user_data("x"), "clientid=x;");
}

TEST(ServiceWire, UserDataValuesAreFoundByKey) {
  const std::string ud = "clientid= 1.f.0.0.0.0.0.0.0.0.0.0.0.0.0.3;typehash=RIHS01_00;";
  EXPECT_EQ(user_data_value(ud, "clientid"), " 1.f.0.0.0.0.0.0.0.0.0.0.0.0.0.3");
  EXPECT_EQ(user_data_value(ud, "typehash"), "RIHS01_00");
  EXPECT_EQ(user_data_value(ud, "serviceid"), std::nullopt);
  EXPECT_EQ(user_data_value("enclave=/", "enclave"), "/");
  EXPECT_EQ(user_data_value("", "enclave"), std::nullopt);
}

}  // namespace
}  // namespace rescuesim::ros2
