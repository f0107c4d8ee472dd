// ROS 1 (TCPROS) serialisation: little endian, no alignment, time = uint32 sec + uint32 nsec,
// string = uint32 length + bytes, variable arrays = uint32 count + elements, fixed arrays =
// elements only, std_msgs/Header = uint32 seq + time + string.

#include <limits>

#include "msgs/message_fields.h"
#include "msgs/serialize.h"
#include "msgs/wire.h"

namespace rescuesim::msg {

namespace {

using fields::Name;

// writes (kWrite) or only measures (!kWrite) a message; measuring first lets to_ros1 size
// the output once and then write into it with plain copies
template <bool kWrite>
class Ros1Writer {
 public:
  Ros1Writer(std::uint8_t* base, std::uint32_t seq) : base_(base), seq_(seq) {}

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
    // ROS 1 time is unsigned: stamps before the epoch do not exist there
    put<std::uint32_t>(static_cast<std::uint32_t>(t.sec_part()));
    put<std::uint32_t>(t.nsec_part());
  }
  void header(Name n, const Header& h) {
    put<std::uint32_t>(depth_ == 0 ? seq_ : 0);  // seq only in the message's own header
    time("stamp", h.stamp);
    string(n, h.frame_id);
  }
  template <class T, std::size_t N>
  void array(Name, const std::array<T, N>& a) {
    bulk(a.data(), N);
  }
  template <class T>
  void sequence(Name n, const std::vector<T>& s) {
    put<std::uint32_t>(count(n, s.size()));
    if constexpr (std::is_same_v<T, std::string>) {
      for (const auto& x : s) string(n, x);
    } else {
      bulk(s.data(), s.size());
    }
  }
  template <class F>
  void message(Name, const char*, F&& f) {
    ++depth_;
    f(*this);
    --depth_;
  }
  template <class E, class F>
  void messages(Name n, const char*, const std::vector<E>& s, F&& f) {
    put<std::uint32_t>(count(n, s.size()));
    ++depth_;
    for (const auto& e : s) f(*this, e);
    --depth_;
  }
  void constant(const char*, const char*, const char*) {}

 private:
  static std::uint32_t count(Name n, std::size_t size) {
    if (size > std::numeric_limits<std::uint32_t>::max()) {
      throw Error(std::string("ROS 1 serialisation: ") + n.ros1 + ": " + std::to_string(size) +
                  " elements do not fit a uint32 length");
    }
    return static_cast<std::uint32_t>(size);
  }
  template <class T>
  void put(T x) {
    if constexpr (kWrite) wire::store_le(base_ + pos_, &x, 1);
    pos_ += sizeof(T);
  }
  template <class T>
  void bulk(const T* p, std::size_t n) {
    if constexpr (kWrite) wire::store_le(base_ + pos_, p, n);
    pos_ += n * sizeof(T);
  }
  void string(Name n, const std::string& s) {
    put<std::uint32_t>(count(n, s.size()));
    if constexpr (kWrite) {
      if (!s.empty()) std::memcpy(base_ + pos_, s.data(), s.size());
    }
    pos_ += s.size();
  }

  std::uint8_t* base_;
  std::uint32_t seq_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};

// the smallest number of bytes an element of a message sequence takes (empty strings and
// sequences): a count claiming more elements than the bytes left can hold is rejected before
// anything is allocated
template <class E, class F>
std::size_t min_ros1_size(F& f) {
  Ros1Writer<false> w(nullptr, 0);
  E e{};
  f(w, e);
  return w.size();
}

class Ros1Reader {
 public:
  Ros1Reader(std::span<const std::uint8_t> bytes, const char* type) : p_(bytes.data()), n_(bytes.size()), path_(type) {}

  template <class T>
  void value(Name n, T& x) {
    if constexpr (std::is_same_v<T, std::string>) {
      string(n.ros1, x);
    } else if constexpr (std::is_same_v<T, bool>) {
      x = get<std::uint8_t>(n.ros1) != 0;
    } else {
      x = get<T>(n.ros1);
    }
  }
  void time(Name n, SimTime& t) {
    path_.push(n.ros1);
    const std::uint32_t sec = get<std::uint32_t>("sec");
    const std::uint32_t nsec = get<std::uint32_t>("nsec");
    path_.pop();
    t.ns = static_cast<std::int64_t>(sec) * 1'000'000'000 + nsec;
  }
  void header(Name n, Header& h) {
    path_.push(n.ros1);
    (void)get<std::uint32_t>("seq");
    time("stamp", h.stamp);
    string("frame_id", h.frame_id);
    path_.pop();
  }
  template <class T, std::size_t N>
  void array(Name n, std::array<T, N>& a) {
    need(n.ros1, N * sizeof(T), "array of " + std::to_string(N) + " elements");
    wire::load_le(a.data(), p_ + pos_, N);
    pos_ += N * sizeof(T);
  }
  template <class T>
  void sequence(Name n, std::vector<T>& s) {
    const std::uint32_t count = get<std::uint32_t>(n.ros1);
    if constexpr (std::is_same_v<T, std::string>) {
      check_count(n.ros1, count, 4, false);
      s.assign(count, std::string());
      for (std::uint32_t i = 0; i < count; ++i) {
        path_.push(n.ros1, i);
        string("", s[i]);
        path_.pop();
      }
    } else {
      check_count(n.ros1, count, sizeof(T), true);
      s.resize(count);
      wire::load_le(s.data(), p_ + pos_, count);
      pos_ += std::size_t(count) * sizeof(T);
    }
  }
  template <class F>
  void message(Name n, const char*, F&& f) {
    path_.push(n.ros1);
    f(*this);
    path_.pop();
  }
  template <class E, class F>
  void messages(Name n, const char*, std::vector<E>& s, F&& f) {
    const std::uint32_t count = get<std::uint32_t>(n.ros1);
    check_count(n.ros1, count, std::max<std::size_t>(1, min_ros1_size<E>(f)), false);
    s.assign(count, E{});
    for (std::uint32_t i = 0; i < count; ++i) {
      path_.push(n.ros1, i);
      f(*this, s[i]);
      path_.pop();
    }
  }
  void constant(const char*, const char*, const char*) {}

  /// Every byte must belong to the message.
  void finish() const {
    if (pos_ != n_) path_.fail(nullptr, std::to_string(n_ - pos_) + " trailing bytes after the message");
  }

 private:
  std::size_t left() const { return n_ - pos_; }
  void need(const char* field, std::size_t bytes, const std::string& what) const {
    if (bytes > left()) {
      path_.fail(field, "truncated: " + what + " needs " + std::to_string(bytes) + " bytes, " +
                            std::to_string(left()) + " left");
    }
  }
  // a sequence of `count` elements of at least `min_size` bytes each must fit what is left
  void check_count(const char* field, std::uint32_t count, std::size_t min_size, bool exact) const {
    const std::uint64_t bytes = std::uint64_t(count) * min_size;
    if (bytes > left()) {
      path_.fail(field, "sequence of " + std::to_string(count) + " elements needs " +
                            (exact ? "" : "at least ") + std::to_string(bytes) + " bytes, " +
                            std::to_string(left()) + " left");
    }
  }
  template <class T>
  T get(const char* field) {
    need(field, sizeof(T), std::string(sizeof(T) == 1 ? "a byte" : "a value"));
    T x;
    wire::load_le(&x, p_ + pos_, 1);
    pos_ += sizeof(T);
    return x;
  }
  void string(const char* field, std::string& s) {
    const std::uint32_t len = get<std::uint32_t>(field);
    need(field, len, "string of " + std::to_string(len) + " bytes");
    s.assign(reinterpret_cast<const char*>(p_ + pos_), len);
    pos_ += len;
  }

  const std::uint8_t* p_;
  std::size_t n_;
  std::size_t pos_ = 0;
  wire::FieldPath path_;
};

}  // namespace

std::size_t ros1_size(const Message& m) {
  return std::visit(
      [](const auto& x) {
        Ros1Writer<false> measure(nullptr, 0);
        fields::visit_fields(measure, x);
        return measure.size();
      },
      m);
}

void write_ros1(const Message& m, std::span<std::uint8_t> out, std::uint32_t seq) {
  std::visit(
      [&](const auto& x) {
        Ros1Writer<false> measure(nullptr, seq);
        fields::visit_fields(measure, x);
        RS_DEMAND(out.size() == measure.size(), "write_ros1: the buffer does not hold exactly the message");
        Ros1Writer<true> w(out.data(), seq);
        fields::visit_fields(w, x);
        RS_DEMAND(w.size() == measure.size(), "ROS 1 writer wrote a different size than it measured");
      },
      m);
}

void to_ros1(const Message& m, std::vector<std::uint8_t>& out, std::uint32_t seq) {
  const std::size_t start = out.size();
  out.resize(start + ros1_size(m));
  write_ros1(m, std::span(out).subspan(start), seq);
}

Message from_ros1(const TypeSupport& type, std::span<const std::uint8_t> bytes) {
  if (type.variant_index >= std::variant_size_v<Message>) {
    throw Error("from_ros1: " + type.ros1_name + ": not a msg::Message type (variant index " +
                std::to_string(type.variant_index) + ")");
  }
  return fields::with_alternative(type.variant_index, [&](auto id) -> Message {
    using T = typename decltype(id)::type;
    T m;
    Ros1Reader r(bytes, type_name_of<T>());
    fields::visit_fields(r, m);
    r.finish();
    return m;
  });
}

}  // namespace rescuesim::msg
