#pragma once
/// Little-endian byte helpers and the field path shared by the ROS 1 and CDR codecs of msgs/
/// (the byte helpers also serve bridges/common/cdr_stream). Both wire formats are little endian; on a little-endian host (every platform we
/// build for) arrays move with one memcpy, elsewhere they are byte-swapped element by element.

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.h"

namespace rescuesim::msg::wire {

/// True when the host stores numbers in wire order, so arrays can be copied as they are.
inline constexpr bool kHostIsLittle = std::endian::native == std::endian::little;
static_assert(std::endian::native == std::endian::little || std::endian::native == std::endian::big,
              "mixed-endian hosts are not supported");

/// `x` with its bytes reversed.
template <class T>
T byteswap(T x) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &x, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  std::memcpy(&x, b, sizeof(T));
  return x;
}

/// Writes `n` values from `src` to `dst` in little-endian order.
template <class T>
void store_le(std::uint8_t* dst, const T* src, std::size_t n) {
  static_assert(std::is_arithmetic_v<T>);
  if constexpr (kHostIsLittle || sizeof(T) == 1) {
    if (n != 0) std::memcpy(dst, src, n * sizeof(T));
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      const T s = byteswap(src[i]);
      std::memcpy(dst + i * sizeof(T), &s, sizeof(T));
    }
  }
}

/// Reads `n` little-endian values from `src` into `dst`.
template <class T>
void load_le(T* dst, const std::uint8_t* src, std::size_t n) {
  static_assert(std::is_arithmetic_v<T>);
  if constexpr (kHostIsLittle || sizeof(T) == 1) {
    if (n != 0) std::memcpy(dst, src, n * sizeof(T));
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      std::memcpy(&dst[i], src + i * sizeof(T), sizeof(T));
      dst[i] = byteswap(dst[i]);
    }
  }
}

/// Where a decoder is inside a message ("transforms[2].header.frame_id"), so that its errors
/// name the field. Entering a field is a push of a pointer: cheap on the good path.
class FieldPath {
 public:
  /// `type` is the ROS name of the message being decoded, the first word of every error.
  explicit FieldPath(const char* type) : type_(type) {}

  void push(const char* name, std::int64_t index = -1) { segments_.push_back({name, index}); }
  void pop() { segments_.pop_back(); }

  /// Throws Error("<type>: <path>.<field>: <what>").
  [[noreturn]] void fail(const char* field, const std::string& what) const {
    std::string path;
    for (const auto& s : segments_) {
      if (!path.empty()) path += '.';
      path += s.name;
      if (s.index >= 0) path += '[' + std::to_string(s.index) + ']';
    }
    if (field != nullptr && *field != '\0') {
      if (!path.empty()) path += '.';
      path += field;
    }
    throw Error(std::string(type_) + ": " + (path.empty() ? "" : path + ": ") + what);
  }

 private:
  struct Segment {
    const char* name;
    std::int64_t index;
  };
  const char* type_;
  std::vector<Segment> segments_;
};

}  // namespace rescuesim::msg::wire
