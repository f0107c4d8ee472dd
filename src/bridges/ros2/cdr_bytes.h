#pragma once
/// Hand-written XCDR1 for the few layouts the ROS 2 bridge encodes itself (the service request
/// header, action_msgs and unique_identifier_msgs, TwistStamped): alignment is counted from the
/// end of the 4-byte encapsulation header, as in every XCDR1 message. The writer writes little
/// endian (encapsulation 00 01 00 00); the reader follows the encapsulation it finds (00 01
/// little endian, 00 00 big endian) and throws Error naming the field when the bytes end early.

#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/error.h"

namespace rescuesim::ros2::cdr {

/// Bytes of the encapsulation header before every XCDR1 payload.
inline constexpr std::size_t kEncapsulation = 4;

/// The number `v` with its bytes in the other order.
template <class T>
T swapped(T v) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  std::memcpy(&v, b, sizeof(T));
  return v;
}

/// Builds one little-endian XCDR1 message, encapsulation header included.
class Writer {
 public:
  Writer() : bytes_{0x00, 0x01, 0x00, 0x00} {}

  /// Payload offset (after the encapsulation header).
  std::size_t offset() const { return bytes_.size() - kEncapsulation; }
  void align(std::size_t n) {
    while (offset() % n != 0) bytes_.push_back(0);
  }
  /// A primitive, aligned to its size.
  template <class T>
  void put(T v) {
    static_assert(std::is_arithmetic_v<T>);
    align(sizeof(T));
    if constexpr (std::endian::native == std::endian::big && sizeof(T) > 1) v = swapped(v);
    const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  /// Raw bytes (uint8 arrays: no alignment).
  void bytes(std::span<const std::uint8_t> b) { bytes_.insert(bytes_.end(), b.begin(), b.end()); }
  /// A string: uint32 length with the NUL, the characters, the NUL.
  void string(std::string_view s) {
    put(static_cast<std::uint32_t>(s.size() + 1));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    bytes_.push_back(0);
  }
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<std::uint8_t> bytes_;
};

/// Reads one XCDR1 message (encapsulation header included) field by field.
class Reader {
 public:
  /// `what` names the message in errors ("action_msgs/CancelGoal request"). Throws Error when
  /// `message` has no XCDR1 encapsulation header.
  Reader(std::span<const std::uint8_t> message, std::string what) : what_(std::move(what)) {
    if (message.size() < kEncapsulation) {
      throw Error(what_ + ": " + std::to_string(message.size()) + " bytes is shorter than the 4-byte encapsulation header");
    }
    if (message[0] != 0x00 || message[1] > 0x01) {
      throw Error(what_ + ": encapsulation " + std::to_string(message[0]) + " " + std::to_string(message[1]) +
                  " is not XCDR1 (00 00 big endian or 00 01 little endian)");
    }
    swap_ = (message[1] == 0x01) != (std::endian::native == std::endian::little);
    payload_ = message.subspan(kEncapsulation);
  }

  std::size_t offset() const { return pos_; }
  std::size_t remaining() const { return payload_.size() - pos_; }
  /// True when the message is little endian.
  bool little_endian() const { return swap_ != (std::endian::native == std::endian::little); }

  void align(std::size_t n, const char* field) {
    const std::size_t pad = (n - pos_ % n) % n;
    need(pad, field);
    pos_ += pad;
  }
  template <class T>
  T get(const char* field) {
    static_assert(std::is_arithmetic_v<T>);
    align(sizeof(T), field);
    need(sizeof(T), field);
    T v;
    std::memcpy(&v, payload_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return swap_ ? swapped(v) : v;
  }
  std::span<const std::uint8_t> bytes(std::size_t n, const char* field) {
    need(n, field);
    const auto out = payload_.subspan(pos_, n);
    pos_ += n;
    return out;
  }
  std::string string(const char* field) {
    const std::uint32_t n = get<std::uint32_t>(field);
    if (n == 0) fail(field, "string length 0 (a CDR string counts its terminating NUL)");
    const auto b = bytes(n, field);
    if (b[n - 1] != 0) fail(field, "string is not NUL-terminated");
    return std::string(reinterpret_cast<const char*>(b.data()), n - 1);
  }
  /// Fails unless at most `allowed` bytes (padding) are left.
  void finish(std::size_t allowed = 3) const {
    if (remaining() > allowed) fail(nullptr, std::to_string(remaining()) + " trailing bytes after the message");
  }
  [[noreturn]] void fail(const char* field, const std::string& why) const {
    throw Error(what_ + (field ? std::string(": ") + field : std::string()) + ": " + why);
  }

 private:
  void need(std::size_t n, const char* field) const {
    if (n > remaining()) {
      fail(field, "truncated: needs " + std::to_string(n) + " bytes at offset " + std::to_string(pos_) + ", " +
                      std::to_string(remaining()) + " left");
    }
  }

  std::string what_;
  std::span<const std::uint8_t> payload_;
  std::size_t pos_ = 0;
  bool swap_ = false;
};

}  // namespace rescuesim::ros2::cdr
