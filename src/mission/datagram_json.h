#pragma once
/// Datagrams as JSON text, for transports that carry std_msgs/String (ROS 1, ROS 2, Foxglove):
///   /<robot>/rescue/comms/send   {"to": "base" | "<robot>" | "*", "data": "<base64>"}
///                                or {"to": ..., "text": "<UTF-8 text>"} (one of data / text)
///   /<robot>/rescue/comms/inbox  {"seq", "from", "to", "hops", "sent", "delivered", "bytes",
///                                 "data": "<base64>", "text": "..." when the bytes are text}
/// (the built-in team's own datagrams are team/team_datagrams.h).
/// Plain functions, no Bus and no network, so the parsers of outside bytes are fuzzed on their
/// own (fuzz/datagram_request_fuzz.cpp).

#include <cstddef>
#include <cstdint>
#include <string>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>


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

}  // namespace rescuesim
