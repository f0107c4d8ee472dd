// Datagram requests and inbox entries as JSON: what a ROS user publishes on comms/send and
// reads on comms/inbox.

#include "mission/datagram_json.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/error.h"

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

std::vector<std::uint8_t> bytes_of(std::string_view text) { return {text.begin(), text.end()}; }

TEST(DatagramJson, TeamPositionsRoundTripAndOtherBytesAreNotOne) {
  const auto b = team_datagram({Vec2(1.5, -2.25), Vec2(4, 5)});
  EXPECT_EQ(std::string(b.begin(), b.end()), R"({"team":{"at":[1.5,-2.25],"going":[4.0,5.0]}})");
  const auto p = read_team_datagram(b);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->at, Vec2(1.5, -2.25));
  ASSERT_TRUE(p->going);
  EXPECT_EQ(*p->going, Vec2(4, 5));
  const auto idle = read_team_datagram(team_datagram({Vec2(1, 2), std::nullopt}));
  ASSERT_TRUE(idle);
  EXPECT_FALSE(idle->going);
  for (const char* bad : {"", "hello", "[1, 2]", R"({"team": 1})", R"({"team": {"at": [1]}})", R"({"team": {"at": [null, 1]}})",
                          R"({"team": {"at": ["1", 2]}})", R"({"team": {"going": [1, 2]}})", R"({"seen": {}})"}) {
    EXPECT_FALSE(read_team_datagram(bytes_of(bad))) << bad;
  }
  // a bad destination alone is left out, the position still counts
  const auto half = read_team_datagram(bytes_of(R"({"team": {"at": [1, 2], "going": "there"}})"));
  ASSERT_TRUE(half);
  EXPECT_FALSE(half->going);
}

TEST(DatagramJson, SeenSquaresAreABitmapOfTheirBox) {
  // squares (2, 3), (4, 3) and (2, 4): the box from (2, 3), 3 x 2; bits 0, 2 and 3 of one byte,
  // 0b00001101 = 0x0D, "DQ==" in base64
  SeenSquares s;
  s.cell = 0.5;
  s.squares = {{2, 3}, {4, 3}, {2, 4}};
  const auto b = seen_datagram(s);
  EXPECT_EQ(std::string(b.begin(), b.end()), R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3],"size":[3,2]}})");
  const auto back = read_seen_datagram(b);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->cell, 0.5);
  EXPECT_EQ(back->squares, s.squares);
  // squares left of and below the origin, and one alone
  s.squares = {{-3, -1}, {-1, -1}};
  EXPECT_EQ(read_seen_datagram(seen_datagram(s))->squares, s.squares);
  s.squares = {{7, -9}};
  const auto one = seen_datagram(s);
  EXPECT_EQ(std::string(one.begin(), one.end()), R"({"seen":{"bits":"AQ==","cell":0.5,"origin":[7,-9],"size":[1,1]}})");
}

TEST(DatagramJson, MalformedSeenDatagramsAreRefused) {
  const std::string ok = R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3],"size":[3,2]}})";
  ASSERT_TRUE(read_seen_datagram(bytes_of(ok)));
  for (const char* bad : {
           "", "{", R"({"team": {"at": [1, 2]}})", R"({"seen": []})",
           R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3]}})",                     // no size
           R"({"seen":{"bits":"DQ==","cell":0,"origin":[2,3],"size":[3,2]}})",          // a cell of 0
           R"({"seen":{"bits":"DQ==","cell":-0.5,"origin":[2,3],"size":[3,2]}})",
           R"({"seen":{"bits":"DQ==","cell":1e300,"origin":[2,3],"size":[3,2]}})",
           R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2.5,3],"size":[3,2]}})",      // not whole
           R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3],"size":[0,2]}})",        // empty box
           R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3],"size":[-3,2]}})",
           R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2147483647,3],"size":[3,2]}})",  // far beyond any world
           R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[18446744073709551615,3],"size":[3,2]}})",
           R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3],"size":[3,30000]}})",    // too large
           R"({"seen":{"bits":"AQ==","cell":0.5,"origin":[10000,3],"size":[2,1]}})",    // beyond the side
           R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3],"size":[3,3]}})",        // 9 bits in one byte
           R"({"seen":{"bits":"DQ=","cell":0.5,"origin":[2,3],"size":[3,2]}})",         // not base64
           R"({"seen":{"bits":13,"cell":0.5,"origin":[2,3],"size":[3,2]}})"}) {
    EXPECT_FALSE(read_seen_datagram(bytes_of(bad))) << bad;
  }
}

}  // namespace
}  // namespace rescuesim
