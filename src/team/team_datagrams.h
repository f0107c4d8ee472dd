#pragma once
/// The built-in team's own datagrams (docs/missions.md, "The built-in team"), JSON text sent
/// through the mission's radio:
///   {"team": {"at": [x, y], "going": [x, y] | null, "victims": [[x, y], ...]}}
///                                where a robot is, the frontier it drives to, the victims it found
///   {"seen": {"cell": c, "origin": [i, j], "size": [w, h], "bits": "<base64>"}}   where its camera looked
///   {"map": {"cell": c, "origin": [i, j], "size": [w, h], "zlib": "<base64>"}}    what its laser mapped
/// Plain functions, no Bus and no network, so the readers of outside bytes are fuzzed on their
/// own (fuzz/datagram_request_fuzz.cpp): any node may send a built-in robot any bytes.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "core/pose.h"

namespace rescuesim {

/// A built-in robot's word to its teammates: where it is, the frontier it drives to and where
/// it believes the victims it found lie (world frame, m).
struct TeamPosition {
  Vec2 at = Vec2::Zero();
  std::optional<Vec2> going;
  std::vector<Vec2> victims;  ///< written only when not empty
};
/// Most victims a team datagram names (more are refused by the writer and the reader).
inline constexpr std::size_t kMaxTeamVictims = 1000;
std::vector<std::uint8_t> team_datagram(const TeamPosition& position);
/// The position in a team datagram; nothing for any other bytes, or a malformed or non-finite
/// position. A malformed destination or victim list is left out (read as none).
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

/// What a robot's laser has mapped, in squares of the world (side `cell`, m; square (i, j)
/// spans [i c, (i + 1) c) x [j c, (j + 1) c)): a box of `width` x `height` squares from
/// `origin`, each unknown, free or occupied.
struct MapSquares {
  enum State : std::uint8_t { unknown = 0, free = 1, occupied = 2 };
  double cell = 0.1;
  std::pair<int, int> origin{0, 0};
  int width = 0, height = 0;
  std::vector<std::uint8_t> states;  ///< width x height State values, row-major from the origin
};
/// Most squares a "map" datagram holds (a 200 m x 200 m world in 0.1 m squares): the reader
/// refuses larger boxes before inflating anything, so a few bytes cannot ask for gigabytes.
inline constexpr long kMaxMapSquares = 4L << 20;
/// A "map" datagram: the box as origin and size, then one byte per square (its State,
/// row-major from the origin), deflated with zlib (RFC 1950) and in base64. A 30 m maze mapped
/// whole in 0.1 m squares (90,000 of them) takes about 3 kB. The box must be non-empty, hold
/// at most kMaxMapSquares squares, lie within kMaxSeenSide of 0, and every state be a State.
std::vector<std::uint8_t> map_datagram(const MapSquares& map);
/// The squares of a "map" datagram; nothing for any other bytes, or a malformed one (cell not
/// in (0, 100) m, a box beyond kMaxSeenSide or larger than kMaxMapSquares, data that does not
/// inflate to exactly width x height bytes, a byte that is no State).
std::optional<MapSquares> read_map_datagram(const std::vector<std::uint8_t>& bytes);

}  // namespace rescuesim
