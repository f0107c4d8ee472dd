#pragma once
/// A small CDR writer and a bounds-checked CDR reader for messages that are not msg::Message
/// alternatives (the control services of bridges/common/control_cdr.h), with the conventions of
/// msgs/serialize.h: XCDR1 little endian behind the 4-byte encapsulation header 00 01 00 00;
/// every primitive aligned to its size (8-byte types to 8), offsets counted from after the
/// header; a nested struct adds no alignment of its own (its members align themselves); string =
/// uint32 length including the NUL, the bytes, the NUL; sequence = uint32 count, then the
/// elements, a sequence of primitives aligning its first element only when it has one (as
/// rmw_cyclonedds's serialize_many, Fast-CDR and Cyclone do); a bounded sequence like an
/// unbounded one; builtin_interfaces/Time = int32 sec + uint32 nanosec.
///
/// The writer writes little endian; the reader reads little endian, or (Encapsulations::
/// either_endian, for the ROS 2 transport's own action_msgs and TwistStamped) also big endian
/// behind 00 00, every number in that order. The reader never reads out of bounds, checks
/// every count against the bytes left before it allocates, and names the field in its errors:
/// it throws rescuesim::Error
/// ("simulation_interfaces/srv/SetEntityState_Request: state.pose.orientation.w: 8 bytes
/// needed, 2 left"). Trailing bytes after the message are refused, but for (a) the padding the
/// encapsulation options announce (their two low bits, DDS-XTypes 7.6.3.1.2) and (b) up to 3
/// zero bytes that end the message on a multiple of 4: rmw_cyclonedds rounds every serialized
/// sample up to 4 bytes with zeros and announces nothing (rmw_cyclonedds_cpp/src/serdata.cpp,
/// serdata_rmw::resize, jazzy 2ec6f21), so a 1-byte ResetSimulation request arrives as 1 + 3.

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "msgs/wire.h"

namespace rescuesim::cdr {

/// Bytes of the encapsulation header (00 01 00 00) before a CDR body.
inline constexpr std::size_t kEncapsulationSize = 4;
/// A sequence without a bound.
inline constexpr std::uint32_t kUnbounded = std::numeric_limits<std::uint32_t>::max();

/// The primitive at `src` in byte order `order` (XCDR1: 00 01 little endian, 00 00 big endian).
template <class T>
T load(const std::uint8_t* src, std::endian order) {
  T x;
  msg::wire::load_le(&x, src, 1);
  return order == std::endian::little ? x : msg::wire::byteswap(x);
}
/// Writes the primitive `x` at `dst` in byte order `order`.
template <class T>
void store(std::uint8_t* dst, T x, std::endian order) {
  if (order != std::endian::little) x = msg::wire::byteswap(x);
  msg::wire::store_le(dst, &x, 1);
}
/// The byte order the XCDR1 encapsulation header at the start of `cdr` names (00 01 little,
/// 00 00 big endian), or nullopt when `cdr` is shorter than the header or has another one.
std::optional<std::endian> xcdr1_byte_order(std::span<const std::uint8_t> cdr);

/// The encapsulations a Reader takes.
enum class Encapsulations {
  little_endian,  ///< 00 01 only: what every Writer writes
  either_endian,  ///< 00 01, and 00 00 read big endian
};

/// Writes one CDR message, or measures a body without writing it. The field names only serve
/// the errors (a sequence longer than a uint32 count or its bound: rescuesim::Error).
class Writer {
 public:
  static constexpr bool kWrites = true;

  /// Appends to `out`: the encapsulation header 00 01 00 00 now, the body through the calls
  /// below. `type` names the message in errors.
  Writer(std::vector<std::uint8_t>& out, const char* type);
  /// Counts the bytes of a body without writing it; `align` false leaves out the alignment
  /// padding, which gives the fewest bytes the body can take wherever it starts.
  static Writer measure(bool align) { return Writer(align); }

  /// Body bytes so far (without the encapsulation header).
  std::size_t size() const { return pos_; }

  /// A primitive, aligned to its size; bool as one byte 0 or 1.
  template <class T>
  void value(const char*, const T& x) {
    if constexpr (std::is_same_v<T, bool>) {
      put<std::uint8_t>(x ? 1 : 0);
    } else {
      put<T>(x);
    }
  }
  void string(const char* name, const std::string& s);
  /// builtin_interfaces/Time from nanoseconds: sec = floor(ns / 1e9) (clamped to int32, the
  /// wire's range), nanosec = the rest.
  void stamp(const char* name, std::int64_t ns);
  /// A fixed array of bytes (uint8[N]): no count, no alignment.
  template <std::size_t N>
  void octets(const char*, const std::array<std::uint8_t, N>& a) {
    if (out_ != nullptr) std::memcpy(reserve(N), a.data(), N);
    pos_ += N;
  }
  /// A sequence of primitives, bools or strings (`bound`: at most that many elements).
  template <class T>
  void sequence(const char* name, const std::vector<T>& s, std::uint32_t bound = kUnbounded) {
    put<std::uint32_t>(count(name, s.size(), bound));
    if constexpr (std::is_same_v<T, std::string>) {
      for (const auto& x : s) string(name, x);
    } else if constexpr (std::is_same_v<T, bool>) {
      for (const bool b : s) put<std::uint8_t>(b ? 1 : 0);
    } else {
      for (const T& x : s) put<T>(x);  // the first aligns, the others follow aligned
    }
  }
  /// A nested message: `f()` writes its members.
  template <class F>
  void scope(const char*, F&& f) {
    f();
  }
  /// A sequence of messages: the count, then `f(element)` for each.
  template <class E, class F>
  void elements(const char* name, const std::vector<E>& s, std::size_t /*min_size*/, std::uint32_t bound, F&& f) {
    put<std::uint32_t>(count(name, s.size(), bound));
    for (const E& e : s) f(e);
  }

 private:
  explicit Writer(bool align) : align_(align) {}
  std::uint8_t* reserve(std::size_t n) {
    out_->resize(out_->size() + n);
    return out_->data() + base_ + pos_;
  }
  void align(std::size_t a) {
    if (!align_) return;
    const std::size_t pad = (a - pos_ % a) % a;
    if (out_ != nullptr && pad != 0) std::memset(reserve(pad), 0, pad);
    pos_ += pad;
  }
  template <class T>
  void put(T x) {
    align(sizeof(T));
    if (out_ != nullptr) store(reserve(sizeof(T)), x, std::endian::little);
    pos_ += sizeof(T);
  }
  std::uint32_t count(const char* name, std::size_t n, std::uint32_t bound) const;

  std::vector<std::uint8_t>* out_ = nullptr;
  std::size_t base_ = 0;  ///< index in *out_ of the body's first byte
  std::size_t pos_ = 0;
  bool align_ = true;
  const char* type_ = "";
};

/// Reads one CDR message, checking every byte; see the file comment for the errors.
class Reader {
 public:
  static constexpr bool kWrites = false;

  /// Checks the encapsulation (00 01: XCDR1 little endian; with `accept` either_endian also 00 00,
  /// then every number is read big endian) and takes the padding its options announce. `type`
  /// names the message in every error and must outlive the reader.
  Reader(std::span<const std::uint8_t> cdr, const char* type, Encapsulations accept = Encapsulations::little_endian);

  template <class T>
  void value(const char* name, T& x) {
    if constexpr (std::is_same_v<T, bool>) {
      x = get<std::uint8_t>(name) != 0;
    } else {
      x = get<T>(name);
    }
  }
  void string(const char* name, std::string& s);
  /// builtin_interfaces/Time as nanoseconds (sec * 1e9 + nanosec; nanosec is not judged).
  void stamp(const char* name, std::int64_t& ns);
  template <std::size_t N>
  void octets(const char* name, std::array<std::uint8_t, N>& a) {
    need(name, N, 0);
    std::memcpy(a.data(), p_ + pos_, N);
    pos_ += N;
  }
  template <class T>
  void sequence(const char* name, std::vector<T>& s, std::uint32_t bound = kUnbounded) {
    if constexpr (std::is_same_v<T, std::string>) {
      const std::uint32_t n = count(name, 5, bound, false);  // length + NUL at least
      s.assign(n, std::string());
      for (std::uint32_t i = 0; i < n; ++i) {
        path_.push_back({name, i});
        string(nullptr, s[i]);
        path_.pop_back();
      }
    } else {
      constexpr std::size_t size = std::is_same_v<T, bool> ? 1 : sizeof(T);
      const std::uint32_t n = count(name, size, bound, true);
      if (n == 0) {
        s.clear();
        return;
      }
      // the first element aligns; the count check above left out that padding
      const std::size_t pad = (size - pos_ % size) % size;
      need(name, std::size_t{n} * size + pad, pad);
      pos_ += pad;
      s.resize(n);
      for (std::uint32_t i = 0; i < n; ++i) {
        if constexpr (std::is_same_v<T, bool>) {
          s[i] = p_[pos_ + i] != 0;
        } else {
          s[i] = load<T>(p_ + pos_ + std::size_t{i} * size, order_);
        }
      }
      pos_ += std::size_t{n} * size;
    }
  }
  template <class F>
  void scope(const char* name, F&& f) {
    path_.push_back({name, -1});
    f();
    path_.pop_back();
  }
  /// A sequence of messages whose elements take at least `min_size` bytes each: the count is
  /// checked against the bytes left and `bound` before anything is allocated.
  template <class E, class F>
  void elements(const char* name, std::vector<E>& s, std::size_t min_size, std::uint32_t bound, F&& f) {
    const std::uint32_t n = count(name, min_size == 0 ? 1 : min_size, bound, false);
    s.assign(n, E{});
    for (std::uint32_t i = 0; i < n; ++i) {
      path_.push_back({name, i});
      f(s[i]);
      path_.pop_back();
    }
  }

  /// Every byte must belong to the message, but for the padding allowed (file comment).
  void finish() const;
  /// Throws Error("<type>: <path>.<field>: <what>"); `field` may be null.
  [[noreturn]] void fail(const char* field, const std::string& what) const;

 private:
  struct Segment {
    const char* name;
    std::int64_t index;  ///< -1: not an element
  };
  std::size_t left() const { return n_ - pos_; }
  /// `bytes` (of which `pad` are alignment padding) must be left.
  void need(const char* field, std::size_t bytes, std::size_t pad) const;
  /// Reads a sequence count; `exact`: its elements take exactly `min_size` bytes each.
  std::uint32_t count(const char* field, std::size_t min_size, std::uint32_t bound, bool exact);
  template <class T>
  T get(const char* field) {
    const std::size_t pad = (sizeof(T) - pos_ % sizeof(T)) % sizeof(T);
    need(field, pad + sizeof(T), pad);
    pos_ += pad;
    const T x = load<T>(p_ + pos_, order_);
    pos_ += sizeof(T);
    return x;
  }

  const std::uint8_t* p_;  ///< the body (after the encapsulation header)
  std::size_t n_;
  std::size_t pos_ = 0;
  std::size_t padding_ = 0;  ///< announced by the encapsulation options
  std::endian order_ = std::endian::little;
  const char* type_;
  std::vector<Segment> path_;
};

}  // namespace rescuesim::cdr
