// Datagram requests and inbox entries as JSON: what a ROS user publishes on comms/send and
// reads on comms/inbox.

#include "mission/datagram_json.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "msgs/base64.h"

namespace rescuesim {
namespace {

std::string error_of(std::string_view json) {
  try {
    parse_send_request(json);
  } catch (const Error& e) {
    return e.message();
  }
  return {};
}

TEST(DatagramJson, TextAndBase64RequestsAndTheirRoundTrip) {
  const SendRequest t = parse_send_request(R"({"to": "base", "text": "victim at 3,4"})");
  EXPECT_EQ(t.to, "base");
  EXPECT_EQ(std::string(t.bytes.begin(), t.bytes.end()), "victim at 3,4");
  const SendRequest d = parse_send_request(R"({"to": "robot2", "data": "AP8="})");
  EXPECT_EQ(d.bytes, (std::vector<std::uint8_t>{0x00, 0xff}));
  const SendRequest back = parse_send_request(send_request_json(d));
  EXPECT_EQ(back.to, d.to);
  EXPECT_EQ(back.bytes, d.bytes);
}

TEST(DatagramJson, BadRequestsSayWhatIsWrong) {
  EXPECT_NE(error_of("hello").find("not JSON"), std::string::npos);
  EXPECT_NE(error_of("[1, 2]").find("not a JSON object"), std::string::npos);
  EXPECT_NE(error_of(R"({"text": "x"})").find("'to' is missing"), std::string::npos);
  EXPECT_NE(error_of(R"({"to": 3, "text": "x"})").find("'to' must be"), std::string::npos);
  EXPECT_NE(error_of(R"({"to": "b"})").find("exactly one"), std::string::npos);
  EXPECT_NE(error_of(R"({"to": "b", "text": "x", "data": "AA=="})").find("exactly one"), std::string::npos);
  EXPECT_NE(error_of(R"({"to": "b", "data": "A"})").find("not base64"), std::string::npos);
  EXPECT_NE(error_of(R"({"to": "b", "text": "x", "ttl": 3})").find("unknown key 'ttl'"), std::string::npos);
  EXPECT_NE(error_of(std::string(kMaxSendRequestBytes + 1, ' ')).find("at most"), std::string::npos);
}

TEST(DatagramJson, InboxEntriesCarryBase64AndTextWhenTheBytesAreText) {
  const std::vector<std::uint8_t> text{'h', 'i', '\n'}, binary{0x68, 0x00, 0x69}, utf8{0xc3, 0xa9}, cut{0xc3};
  InboxEntry e;
  e.seq = 4;
  e.from = "robot";
  e.to = "*";
  e.hops = 1;
  e.sent = 1.5;
  e.delivered = 1.6;
  e.bytes = &text;
  auto j = nlohmann::json::parse(inbox_json(e));
  EXPECT_EQ(j["data"], "aGkK");
  EXPECT_EQ(j["text"], "hi\n");
  EXPECT_EQ(j["bytes"], 3);
  EXPECT_EQ(j["seq"], 4);
  e.bytes = &binary;
  j = nlohmann::json::parse(inbox_json(e));
  EXPECT_FALSE(j.contains("text"));
  EXPECT_EQ(j["data"], "aABp");
  EXPECT_TRUE(is_text(utf8));   // é
  EXPECT_FALSE(is_text(cut));   // a lead byte without its continuation
}

}  // namespace
}  // namespace rescuesim
