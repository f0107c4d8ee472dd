#pragma once
/// MD5 (RFC 1321), for ROS 1 message checksums. Not for security: MD5 is broken as a
/// cryptographic hash; ROS 1 only uses it to tell message layouts apart.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace rescuesim::msg {

/// The 16-byte MD5 digest of `data`.
std::array<std::uint8_t, 16> md5(std::string_view data);
/// The MD5 digest of `data` as 32 lowercase hex digits (as `md5sum` and `rosmsg md5` print it).
std::string md5_hex(std::string_view data);

}  // namespace rescuesim::msg
