#pragma once
/// CRC-32 as MCAP uses it (IEEE 802.3 / zlib: reflected polynomial 0xEDB88320, initial value
/// and final xor 0xFFFFFFFF), so crc32("123456789") == 0xCBF43926.

#include <cstdint>
#include <span>

namespace rescuesim::mcap {

/// A running CRC-32 over bytes fed in pieces.
class Crc32 {
 public:
  /// Adds bytes to the checksum.
  void update(std::span<const std::uint8_t> bytes);
  /// The CRC-32 of everything added so far (adding more afterwards is allowed).
  std::uint32_t value() const { return ~state_; }

 private:
  std::uint32_t state_ = 0xFFFFFFFFu;
};

/// The CRC-32 of one run of bytes.
std::uint32_t crc32(std::span<const std::uint8_t> bytes);

}  // namespace rescuesim::mcap
