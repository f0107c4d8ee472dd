// The built-in team's datagrams: what a robot tells its teammates and the base (where it is,
// where its camera looked, what its laser mapped), and how malformed ones are refused.

#include "team/team_datagrams.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <zlib.h>

#include "msgs/base64.h"

namespace rescuesim {
namespace {

std::vector<std::uint8_t> bytes_of(std::string_view text) { return {text.begin(), text.end()}; }

TEST(TeamDatagrams, TeamPositionsRoundTripAndOtherBytesAreNotOne) {
  const auto b = team_datagram({Vec2(1.5, -2.25), Vec2(4, 5), {}});
  EXPECT_EQ(std::string(b.begin(), b.end()), R"({"team":{"at":[1.5,-2.25],"going":[4.0,5.0]}})");
  const auto p = read_team_datagram(b);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->at, Vec2(1.5, -2.25));
  ASSERT_TRUE(p->going);
  EXPECT_EQ(*p->going, Vec2(4, 5));
  const auto idle = read_team_datagram(team_datagram({Vec2(1, 2), std::nullopt, {}}));
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
  // the victims it found, when it found any
  TeamPosition with;
  with.at = Vec2(1, 2);
  with.victims = {Vec2(3.5, -1), Vec2(0.25, 7)};
  const auto v = team_datagram(with);
  EXPECT_EQ(std::string(v.begin(), v.end()), R"({"team":{"at":[1.0,2.0],"going":null,"victims":[[3.5,-1.0],[0.25,7.0]]}})");
  EXPECT_EQ(read_team_datagram(v)->victims, with.victims);
  // one bad victim spoils the list, not the position
  for (const char* bad : {R"({"team": {"at": [1, 2], "victims": [[1, 2], [3]]}})", R"({"team": {"at": [1, 2], "victims": [[1, null]]}})",
                          R"({"team": {"at": [1, 2], "victims": {"a": [1, 2]}}})", R"({"team": {"at": [1, 2], "victims": [[1, "2"]]}})"}) {
    const auto p2 = read_team_datagram(bytes_of(bad));
    ASSERT_TRUE(p2) << bad;
    EXPECT_TRUE(p2->victims.empty()) << bad;
  }
}

TEST(TeamDatagrams, SeenSquaresAreABitmapOfTheirBox) {
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

TEST(TeamDatagrams, MalformedSeenDatagramsAreRefused) {
  const std::string ok = R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3],"size":[3,2]}})";
  ASSERT_TRUE(read_seen_datagram(bytes_of(ok)));
  for (const char* bad : {"", "{", R"({"team": {"at": [1, 2]}})", R"({"seen": []})",
                          R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3]}})",             // no size
                          R"({"seen":{"bits":"DQ==","cell":0,"origin":[2,3],"size":[3,2]}})",  // a cell of 0
                          R"({"seen":{"bits":"DQ==","cell":-0.5,"origin":[2,3],"size":[3,2]}})",
                          R"({"seen":{"bits":"DQ==","cell":1e300,"origin":[2,3],"size":[3,2]}})",
                          R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2.5,3],"size":[3,2]}})",  // not whole
                          R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3],"size":[0,2]}})",    // empty box
                          R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3],"size":[-3,2]}})",
                          R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2147483647,3],"size":[3,2]}})",  // far beyond any world
                          R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[18446744073709551615,3],"size":[3,2]}})",
                          R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3],"size":[3,30000]}})",  // too large
                          R"({"seen":{"bits":"AQ==","cell":0.5,"origin":[10000,3],"size":[2,1]}})",  // beyond the side
                          R"({"seen":{"bits":"DQ==","cell":0.5,"origin":[2,3],"size":[3,3]}})",      // 9 bits in one byte
                          R"({"seen":{"bits":"DQ=","cell":0.5,"origin":[2,3],"size":[3,2]}})",       // not base64
                          R"({"seen":{"bits":13,"cell":0.5,"origin":[2,3],"size":[3,2]}})"}) {
    EXPECT_FALSE(read_seen_datagram(bytes_of(bad))) << bad;
  }
}

MapSquares map_of(int w, int h, std::vector<std::uint8_t> states, std::pair<int, int> origin = {0, 0}) {
  MapSquares m;
  m.cell = 0.1;
  m.origin = origin;
  m.width = w;
  m.height = h;
  m.states = std::move(states);
  return m;
}

/// The "zlib" member of a map datagram's JSON, decoded from base64.
std::vector<std::uint8_t> zlib_of(const std::vector<std::uint8_t>& datagram) {
  const auto j = nlohmann::json::parse(datagram.begin(), datagram.end());
  return *msg::decode_base64(j["map"]["zlib"].get<std::string>());
}

/// A map datagram's text with `zlib` (raw zlib bytes) and `size` of our choosing.
std::vector<std::uint8_t> forged_map(const std::vector<std::uint8_t>& zlib, int w, int h) {
  std::string b64;
  msg::append_base64(b64, zlib.data(), zlib.size());
  nlohmann::json j;
  j["map"] = {{"cell", 0.1}, {"origin", {0, 0}}, {"size", {w, h}}, {"zlib", b64}};
  return bytes_of(j.dump());
}

std::vector<std::uint8_t> deflate(const std::vector<std::uint8_t>& raw) {
  uLongf n = compressBound(static_cast<uLong>(raw.size()));
  std::vector<std::uint8_t> out(n);
  EXPECT_EQ(compress2(out.data(), &n, raw.data(), static_cast<uLong>(raw.size()), 9), Z_OK);
  out.resize(n);
  return out;
}

TEST(TeamDatagrams, MapSquaresAreDeflatedStatesOfTheirBox) {
  // 3 x 2 squares from (-1, 4): free, free, occupied / unknown, unknown, free
  const MapSquares m = map_of(3, 2, {1, 1, 2, 0, 0, 1}, {-1, 4});
  const auto b = map_datagram(m);
  const auto j = nlohmann::json::parse(b.begin(), b.end());
  EXPECT_EQ(j["map"]["origin"], nlohmann::json({-1, 4}));
  EXPECT_EQ(j["map"]["size"], nlohmann::json({3, 2}));
  EXPECT_EQ(j["map"]["cell"], 0.1);
  // RFC 1950 by hand: the header of a default-level stream (CMF 0x78: deflate, 32 kB window;
  // FLG 0x9C: level 6, and 0x789C divisible by 31), and at the
  // end the Adler-32 of the six bytes, big-endian. A = 1 + (1+1+2+0+0+1) = 6; B is the sum of
  // A after each byte: 2 + 3 + 5 + 5 + 5 + 6 = 26 = 0x1A.
  const auto z = zlib_of(b);
  ASSERT_GE(z.size(), 6u);
  EXPECT_EQ(z[0], 0x78);
  EXPECT_EQ(z[1], 0x9C);
  EXPECT_EQ(std::vector<std::uint8_t>(z.end() - 4, z.end()), (std::vector<std::uint8_t>{0x00, 0x1A, 0x00, 0x06}));
  const auto back = read_map_datagram(b);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->cell, 0.1);
  EXPECT_EQ(back->origin, std::make_pair(-1, 4));
  EXPECT_EQ(back->width, 3);
  EXPECT_EQ(back->height, 2);
  EXPECT_EQ(back->states, m.states);
  // a maze-like map of long runs (300 x 300 squares: corridors of free between occupied walls,
  // half of it unknown) deflates to a small fraction of its 90,000 bytes, and reads back whole
  std::vector<std::uint8_t> maze(300 * 300, MapSquares::unknown);
  for (int y = 0; y < 150; ++y) {
    for (int x = 0; x < 300; ++x)
      maze[static_cast<std::size_t>(y * 300 + x)] = (x % 25 == 0 || y % 25 == 0) ? MapSquares::occupied : MapSquares::free;
  }
  const auto big = map_datagram(map_of(300, 300, maze));
  EXPECT_LT(big.size(), 9000u);  // 1/10 of the raw states; zlib does far better, this only checks it deflated
  EXPECT_EQ(read_map_datagram(big)->states, maze);
  // and it is not taken for the other datagrams, nor they for it
  EXPECT_FALSE(read_seen_datagram(b));
  EXPECT_FALSE(read_team_datagram(b));
  EXPECT_FALSE(read_map_datagram(team_datagram({Vec2(1, 2), std::nullopt, {}})));
}

TEST(TeamDatagrams, MalformedMapDatagramsAreRefused) {
  const std::vector<std::uint8_t> six{1, 1, 2, 0, 0, 1};
  ASSERT_TRUE(read_map_datagram(forged_map(deflate(six), 3, 2)));
  EXPECT_FALSE(read_map_datagram(forged_map(deflate(six), 2, 2)));  // inflates to more than the box: Z_BUF_ERROR, not an overrun
  EXPECT_FALSE(read_map_datagram(forged_map(deflate(six), 7, 1)));  // to fewer than the box
  EXPECT_FALSE(read_map_datagram(forged_map(deflate({1, 1, 3, 0, 0, 1}), 3, 2)));  // 3 is no state
  auto cut = deflate(six);
  cut.pop_back();  // the Adler-32 cut short
  EXPECT_FALSE(read_map_datagram(forged_map(cut, 3, 2)));
  auto flipped = deflate(six);
  flipped[flipped.size() - 1] ^= 1;  // the Adler-32 wrong
  EXPECT_FALSE(read_map_datagram(forged_map(flipped, 3, 2)));
  EXPECT_FALSE(read_map_datagram(forged_map({1, 2, 3}, 3, 2)));  // not zlib
  // a box of 2^22 + 1 squares is refused before anything is inflated (a bomb: 4 MB of zeros
  // deflate to a few kB)
  EXPECT_FALSE(read_map_datagram(forged_map(deflate(six), 4097, 1024)));
  for (const char* bad : {R"({"map": {}})", R"({"map": []})",
                          R"({"map":{"cell":0.1,"origin":[0,0],"size":[3,2]}})",                // no data
                          R"({"map":{"cell":0.1,"origin":[0,0],"size":[3,2],"zlib":"eNo="}})",  // a header alone
                          R"({"map":{"cell":0.1,"origin":[0,0],"size":[3,2],"zlib":"***"}})",   // not base64
                          R"({"map":{"cell":0,"origin":[0,0],"size":[3,2],"zlib":"eNo="}})",
                          R"({"map":{"cell":0.1,"origin":[9999,0],"size":[3,2],"zlib":"eNo="}})"}) {
    EXPECT_FALSE(read_map_datagram(bytes_of(bad))) << bad;
  }
  // what the writer is never asked to write (a bug in the caller: RS_DEMAND aborts)
  EXPECT_DEATH(map_datagram(map_of(0, 2, {})), "an empty box");
  EXPECT_DEATH(map_datagram(map_of(3, 2, {1, 1, 2})), "do not fill the box");
  EXPECT_DEATH(map_datagram(map_of(3, 2, {1, 1, 2, 0, 0, 7})), "no MapSquares::State");
  EXPECT_DEATH(map_datagram(map_of(3, 2, six, {9999, 0})), "beyond kMaxSeenSide");
}
}  // namespace
}  // namespace rescuesim
