#pragma once
/// The body of the CDR and ROS 1 decoder targets: the first input byte picks the message type
/// (modulo the number of types), the rest are the message bytes. Decoding may only fail with
/// rescuesim::Error; a message that decodes must encode again, and its encoding must decode to
/// a message that encodes to the same bytes (a round trip is stable after one pass: padding
/// and dropped fields such as Header.seq are normalised by the first).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

#include "core/error.h"
#include "msgs/serialize.h"

namespace rescuesim::fuzz {

/// Runs one input through `decode` / `encode` (from_cdr / to_cdr or from_ros1 / to_ros1).
template <typename Decode, typename Encode>
int decode_round_trip(const std::uint8_t* data, std::size_t size, Decode decode, Encode encode) {
  if (size == 0) return 0;
  const auto& types = msg::all_types();
  const msg::TypeSupport& type = types[data[0] % types.size()];
  const std::span<const std::uint8_t> bytes(data + 1, size - 1);
  msg::Message m;
  try {
    m = decode(type, bytes);
  } catch (const Error&) {
    return 0;
  }
  std::vector<std::uint8_t> once, twice;
  encode(m, once);
  encode(decode(type, std::span<const std::uint8_t>(once)), twice);
  if (once != twice) {
    std::fprintf(stderr, "%s: re-encoding is not stable (%zu bytes, then %zu)\n", type.ros1_name.c_str(),
                 once.size(), twice.size());
    std::abort();
  }
  return 0;
}

}  // namespace rescuesim::fuzz
