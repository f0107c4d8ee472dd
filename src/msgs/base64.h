#pragma once
/// Base64 (RFC 4648, standard alphabet, with padding): uint8[] fields in Foxglove's json
/// encoding, datagram payloads in JSON. Written here rather than taken from a library: Debian's
/// libb64 would be a new dependency for forty lines, and Boost.Beast's codec is in its detail
/// namespace.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rescuesim::msg {

/// Appends the base64 text of n bytes at p to `out`.
void append_base64(std::string& out, const std::uint8_t* p, std::size_t n);
/// The bytes of base64 text `text` (padding required, no whitespace), or nullopt when it is not
/// base64 (a length that is not a multiple of 4, a character outside the alphabet, bad padding).
std::optional<std::vector<std::uint8_t>> decode_base64(std::string_view text);

}  // namespace rescuesim::msg
