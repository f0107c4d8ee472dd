#pragma once
/// Datagrams as JSON text, for transports that carry std_msgs/String (ROS 1, ROS 2, Foxglove):
///   /<robot>/rescue/comms/send   {"to": "base" | "<robot>" | "*", "data": "<base64>"}
///                                or {"to": ..., "text": "<UTF-8 text>"} (one of data / text)
///   /<robot>/rescue/comms/inbox  {"seq", "from", "to", "hops", "sent", "delivered", "bytes",
///                                 "data": "<base64>", "text": "..." when the bytes are text}
/// and the built-in team's own datagrams (docs/missions.md, "The built-in team"):
///   {"team": {"at": [x, y], "going": [x, y] | null}}      where a robot is and the frontier it drives to
///   {"seen": {"cell": c, "origin": [i, j], "size": [w, h], "bits": "<base64>"}}   where its camera looked
/// Plain functions, no Bus and no network, so the parsers of outside bytes are fuzzed on their
/// own (fuzz/datagram_request_fuzz.cpp): any node may send a built-in robot any bytes.

#include <cstddef>
#include <cstdint>
#include <string>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "core/pose.h"

namespace rescuesim {

/// A send request read from JSON.
struct SendRequest {
  std::string to;                   ///< "base", a robot's name, "*"
  std::vector<std::uint8_t> bytes;  ///< the payload
};

/// Most bytes of request text read (larger is refused before parsing): 4 MiB, above any
/// model's datagram limit in base64.
inline constexpr std::size_t kMaxSendRequestBytes = std::size_t{4} << 20;

/// Reads a send request. Throws rescuesim::Error saying what is wrong ("not JSON: ...",
/// "'to' is missing", "'data' is not base64", "give 'data' or 'text', not both").
SendRequest parse_send_request(std::string_view json);
/// The JSON of a send request (the inverse of parse_send_request; bytes as "data").
std::string send_request_json(const SendRequest& request);

/// A delivered datagram as published on the inbox topic. `to` is the destination's id, or
/// "*" for a broadcast; times in s.
struct InboxEntry {
  std::uint64_t seq = 0;
  std::string from, to;
  int hops = 0;
  double sent = 0, delivered = 0;
  const std::vector<std::uint8_t>* bytes = nullptr;  ///< not owned
};
std::string inbox_json(const InboxEntry& entry);

/// True when `bytes` are printable UTF-8 text (no control characters but tab, CR and LF), as
/// inbox_json decides whether to add "text".
bool is_text(const std::vector<std::uint8_t>& bytes);

/// A built-in robot's word to its teammates: where it is and the frontier it drives to (world
/// frame, m).
struct TeamPosition {
  Vec2 at = Vec2::Zero();
  std::optional<Vec2> going;
};
std::vector<std::uint8_t> team_datagram(const TeamPosition& position);
/// The position in a team datagram; nothing for any other bytes, or a malformed or non-finite one.
std::optional<TeamPosition> read_team_datagram(const std::vector<std::uint8_t>& bytes);

/// Squares of the world (side `cell`, m; square (i, j) spans [i c, (i + 1) c) x [j c, (j + 1) c))
/// where a robot's camera has looked.
struct SeenSquares {
  double cell = 0.5;
  std::vector<std::pair<int, int>> squares;  ///< (i, j), in row-major order from the lowest j
};
/// Most squares a "seen" datagram spans on a side, and farthest square index from the origin
/// it may name: a 5 km world of 0.5 m squares.
inline constexpr int kMaxSeenSide = 10000;
/// A "seen" datagram: the bounding box of the squares as origin and size, then one bit per
/// square of the box (row-major from the origin, least significant bit first) in base64. About
/// 450 bytes for a 30 m maze. The squares must not be empty, and lie within kMaxSeenSide of 0.
std::vector<std::uint8_t> seen_datagram(const SeenSquares& seen);
/// The squares of a "seen" datagram, row-major; nothing for any other bytes, or a malformed one
/// (cell not in (0, 100) m, a box reaching beyond kMaxSeenSide, bits of the wrong length).
std::optional<SeenSquares> read_seen_datagram(const std::vector<std::uint8_t>& bytes);

}  // namespace rescuesim
