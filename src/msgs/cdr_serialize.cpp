// ROS 2 serialisation: CDR, XCDR1 little endian (what rmw_cyclonedds and rmw_fastrtps put on
// the wire for final structs). A 4-byte encapsulation header 00 01 00 00, then the fields with
// each primitive aligned to its size (8-byte types to 8), offsets counted from after the
// header; string = uint32 length including the NUL + bytes + NUL; sequence = uint32 count +
// elements (no element alignment when empty); builtin_interfaces/Time = int32 sec + uint32
// nanosec; std_msgs/Header = Time + frame_id (no seq).

#include <limits>

#include "msgs/message_fields.h"
#include "msgs/serialize.h"
#include "msgs/wire.h"

namespace rescuesim::msg {

namespace {

using fields::Name;

constexpr std::size_t kEncapsulationSize = 4;

// writes (kWrite) or only measures a message body (after the encapsulation header). kAlign
// false measures without padding: a lower bound on any element's size wherever it starts.
template <bool kWrite, bool kAlign = true>
class CdrWriter {
 public:
  explicit CdrWriter(std::uint8_t* origin) : origin_(origin) {}

  std::size_t size() const { return pos_; }

  template <class T>
  void value(Name n, const T& x) {
    if constexpr (std::is_same_v<T, std::string>) {
      string(n, x);
    } else if constexpr (std::is_same_v<T, bool>) {
      put<std::uint8_t>(x ? 1 : 0);
    } else {
      put<T>(x);
    }
  }
  void time(Name, const SimTime& t) {
    put<std::int32_t>(static_cast<std::int32_t>(t.sec_part()));
    put<std::uint32_t>(t.nsec_part());
  }
  void header(Name n, const Header& h) {
    time("stamp", h.stamp);
    string(n, h.frame_id);
  }
  template <class T, std::size_t N>
  void array(Name, const std::array<T, N>& a) {
    align(sizeof(T));
    bulk(a.data(), N);
  }
  template <class T>
  void sequence(Name n, const std::vector<T>& s) {
    put<std::uint32_t>(count(n, s.size()));
    if constexpr (std::is_same_v<T, std::string>) {
      for (const auto& x : s) string(n, x);
    } else if (!s.empty()) {
      align(sizeof(T));
      bulk(s.data(), s.size());
    }
  }
  template <class F>
  void message(Name, const char*, F&& f) {
    f(*this);
  }
  template <class E, class F>
  void messages(Name n, const char*, const std::vector<E>& s, F&& f) {
    put<std::uint32_t>(count(n, s.size()));
    for (const auto& e : s) f(*this, e);
  }
  void constant(const char*, const char*, const char*) {}

 private:
  static std::uint32_t count(Name n, std::size_t size) {
    if (size >= std::numeric_limits<std::uint32_t>::max()) {
      throw Error(std::string("CDR serialisation: ") + n.ros2 + ": " + std::to_string(size) +
                  " elements do not fit a uint32 length");
    }
    return static_cast<std::uint32_t>(size);
  }
  void align(std::size_t a) {
    if constexpr (kAlign) {
      const std::size_t pad = (a - pos_ % a) % a;
      if constexpr (kWrite) std::memset(origin_ + pos_, 0, pad);
      pos_ += pad;
    }
  }
  template <class T>
  void put(T x) {
    align(sizeof(T));
    if constexpr (kWrite) wire::store_le(origin_ + pos_, &x, 1);
    pos_ += sizeof(T);
  }
  template <class T>
  void bulk(const T* p, std::size_t n) {
    if constexpr (kWrite) wire::store_le(origin_ + pos_, p, n);
    pos_ += n * sizeof(T);
  }
  void string(Name n, const std::string& s) {
    put<std::uint32_t>(count(n, s.size() + 1));
    if constexpr (kWrite) {
      if (!s.empty()) std::memcpy(origin_ + pos_, s.data(), s.size());
      origin_[pos_ + s.size()] = 0;
    }
    pos_ += s.size() + 1;
  }

  std::uint8_t* origin_;
  std::size_t pos_ = 0;
};

// the fewest bytes an element of a message sequence can take (see the ROS 1 reader)
template <class E, class F>
std::size_t min_cdr_size(F& f) {
  CdrWriter<false, false> w(nullptr);
  E e{};
  f(w, e);
  return w.size();
}

class CdrReader {
 public:
  // `bytes` starts after the encapsulation header; up to `padding` bytes may follow the message
  CdrReader(std::span<const std::uint8_t> bytes, const char* type, std::size_t padding)
      : p_(bytes.data()), n_(bytes.size()), padding_(padding), path_(type) {}

  template <class T>
  void value(Name n, T& x) {
    if constexpr (std::is_same_v<T, std::string>) {
      string(n.ros2, x);
    } else if constexpr (std::is_same_v<T, bool>) {
      x = get<std::uint8_t>(n.ros2) != 0;
    } else {
      x = get<T>(n.ros2);
    }
  }
  void time(Name n, SimTime& t) {
    path_.push(n.ros2);
    const std::int32_t sec = get<std::int32_t>("sec");
    const std::uint32_t nanosec = get<std::uint32_t>("nanosec");
    path_.pop();
    t.ns = static_cast<std::int64_t>(sec) * 1'000'000'000 + nanosec;
  }
  void header(Name n, Header& h) {
    path_.push(n.ros2);
    time("stamp", h.stamp);
    string("frame_id", h.frame_id);
    path_.pop();
  }
  template <class T, std::size_t N>
  void array(Name n, std::array<T, N>& a) {
    align(n.ros2, sizeof(T));
    need(n.ros2, N * sizeof(T), "array of " + std::to_string(N) + " elements");
    wire::load_le(a.data(), p_ + pos_, N);
    pos_ += N * sizeof(T);
  }
  template <class T>
  void sequence(Name n, std::vector<T>& s) {
    const std::uint32_t count = get<std::uint32_t>(n.ros2);
    if constexpr (std::is_same_v<T, std::string>) {
      check_count(n.ros2, count, 5, false);  // length + NUL
      s.assign(count, std::string());
      for (std::uint32_t i = 0; i < count; ++i) {
        path_.push(n.ros2, i);
        string("", s[i]);
        path_.pop();
      }
    } else {
      if (count != 0) align(n.ros2, sizeof(T));
      check_count(n.ros2, count, sizeof(T), true);
      s.resize(count);
      wire::load_le(s.data(), p_ + pos_, count);
      pos_ += std::size_t(count) * sizeof(T);
    }
  }
  template <class F>
  void message(Name n, const char*, F&& f) {
    path_.push(n.ros2);
    f(*this);
    path_.pop();
  }
  template <class E, class F>
  void messages(Name n, const char*, std::vector<E>& s, F&& f) {
    const std::uint32_t count = get<std::uint32_t>(n.ros2);
    check_count(n.ros2, count, std::max<std::size_t>(1, min_cdr_size<E>(f)), false);
    s.assign(count, E{});
    for (std::uint32_t i = 0; i < count; ++i) {
      path_.push(n.ros2, i);
      f(*this, s[i]);
      path_.pop();
    }
  }
  void constant(const char*, const char*, const char*) {}

  /// Every byte must belong to the message, but for the padding the header announced.
  void finish() const {
    if (n_ - pos_ > padding_) {
      path_.fail(nullptr, std::to_string(n_ - pos_) + " trailing bytes after the message" +
                              (padding_ ? " (the encapsulation options allow " + std::to_string(padding_) + ")" : ""));
    }
  }

 private:
  std::size_t left() const { return n_ - pos_; }
  void need(const char* field, std::size_t bytes, const std::string& what) const {
    if (bytes > left()) {
      path_.fail(field, "truncated: " + what + " needs " + std::to_string(bytes) + " bytes, " +
                            std::to_string(left()) + " left");
    }
  }
  void align(const char* field, std::size_t a) {
    const std::size_t pad = (a - pos_ % a) % a;
    need(field, pad, "alignment padding");
    pos_ += pad;
  }
  void check_count(const char* field, std::uint32_t count, std::size_t min_size, bool exact) const {
    const std::uint64_t bytes = std::uint64_t(count) * min_size;
    if (bytes > left()) {
      path_.fail(field, "sequence of " + std::to_string(count) + " elements needs " +
                            (exact ? "" : "at least ") +
                            std::to_string(bytes) + " bytes, " + std::to_string(left()) + " left");
    }
  }
  template <class T>
  T get(const char* field) {
    align(field, sizeof(T));
    need(field, sizeof(T), std::string(sizeof(T) == 1 ? "a byte" : "a value"));
    T x;
    wire::load_le(&x, p_ + pos_, 1);
    pos_ += sizeof(T);
    return x;
  }
  void string(const char* field, std::string& s) {
    const std::uint32_t len = get<std::uint32_t>(field);
    if (len == 0) path_.fail(field, "string length 0 (a CDR string counts its terminating NUL)");
    need(field, len, "string of " + std::to_string(len) + " bytes");
    if (p_[pos_ + len - 1] != 0) path_.fail(field, "string of " + std::to_string(len) + " bytes does not end in NUL");
    s.assign(reinterpret_cast<const char*>(p_ + pos_), len - 1);
    pos_ += len;
  }

  const std::uint8_t* p_;
  std::size_t n_;
  std::size_t padding_;
  std::size_t pos_ = 0;
  wire::FieldPath path_;
};

}  // namespace

void to_cdr(const Message& m, std::vector<std::uint8_t>& out) {
  std::visit(
      [&](const auto& x) {
        CdrWriter<false> measure(nullptr);
        fields::visit_fields(measure, x);
        const std::size_t start = out.size();
        out.resize(start + kEncapsulationSize + measure.size());
        std::uint8_t* p = out.data() + start;
        p[0] = 0x00;  // CDR_LE: representation identifier 0x0001, big-endian on the wire
        p[1] = 0x01;
        p[2] = 0x00;  // options: no padding announced
        p[3] = 0x00;
        CdrWriter<true> w(p + kEncapsulationSize);
        fields::visit_fields(w, x);
        RS_DEMAND(w.size() == measure.size(), "CDR writer wrote a different size than it measured");
      },
      m);
}

Message from_cdr(const TypeSupport& type, std::span<const std::uint8_t> bytes) {
  if (type.variant_index >= std::variant_size_v<Message>) {
    throw Error("from_cdr: " + type.ros2_name + ": not a msg::Message type (variant index " +
                std::to_string(type.variant_index) + ")");
  }
  const std::string& name = type.ros2_name;
  if (bytes.size() < kEncapsulationSize) {
    throw Error(name + ": CDR data of " + std::to_string(bytes.size()) +
                " bytes is shorter than the 4-byte encapsulation header");
  }
  if (bytes[0] != 0x00 || bytes[1] != 0x01) {
    char id[8];
    std::snprintf(id, sizeof id, "%02x %02x", bytes[0], bytes[1]);
    const bool big = bytes[0] == 0x00 && bytes[1] == 0x00;
    throw Error(name + ": encapsulation " + id + (big ? " (big-endian CDR) is not supported" : " is not supported") +
                "; expected 00 01 (XCDR1 little endian)");
  }
  // the options' two low bits count padding bytes appended after the message (DDS-XTypes 7.6.3.1.2)
  const std::size_t padding = bytes[3] & 0x03u;
  return fields::with_alternative(type.variant_index, [&](auto id) -> Message {
    using T = typename decltype(id)::type;
    T m;
    CdrReader r(bytes.subspan(kEncapsulationSize), name.c_str(), padding);
    fields::visit_fields(r, m);
    r.finish();
    return m;
  });
}

}  // namespace rescuesim::msg
