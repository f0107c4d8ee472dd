// JSON of a message for Foxglove's `json` encoding: one compact object with ROS 1 field names,
// stamps as {"sec":..,"nsec":..}, uint8[] as base64 strings, and non-finite floats (REP-117's
// ±inf, NaN) as null because JSON has no literal for them.

#include <charconv>
#include <cmath>

#include "msgs/base64.h"
#include "msgs/message_fields.h"
#include "msgs/serialize.h"

namespace rescuesim::msg {

namespace {

using fields::Name;

void append_string(std::string& out, std::string_view s) {
  out += '"';
  for (const char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          static constexpr char kHex[] = "0123456789abcdef";
          out += "\\u00";
          out += kHex[(c >> 4) & 15];
          out += kHex[c & 15];
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

template <class T>
void append_number(std::string& out, T x) {
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(x)) {
      out += "null";
      return;
    }
  }
  char buf[32];
  // shortest text that reads back to the same value (floats as floats)
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

class JsonWriter {
 public:
  explicit JsonWriter(std::string& out) : out_(out) {}

  template <class T>
  void value(Name n, const T& x) {
    key(n);
    scalar(x);
  }
  void time(Name n, const SimTime& t) {
    key(n);
    out_ += "{\"sec\":";
    append_number(out_, t.sec_part());
    out_ += ",\"nsec\":";
    append_number(out_, t.nsec_part());
    out_ += '}';
  }
  void header(Name n, const Header& h) {
    key(n);
    out_ += '{';
    first_ = true;
    time("stamp", h.stamp);
    value("frame_id", h.frame_id);
    out_ += '}';
  }
  template <class T, std::size_t N>
  void array(Name n, const std::array<T, N>& a) {
    key(n);
    list(a.data(), N);
  }
  template <class T>
  void sequence(Name n, const std::vector<T>& s) {
    key(n);
    if constexpr (std::is_same_v<T, std::uint8_t>) {
      out_ += '"';
      append_base64(out_, s.data(), s.size());
      out_ += '"';
    } else {
      list(s.data(), s.size());
    }
  }
  template <class F>
  void message(Name n, const char*, F&& f) {
    key(n);
    out_ += '{';
    first_ = true;
    f(*this);
    out_ += '}';
    first_ = false;
  }
  template <class E, class F>
  void messages(Name n, const char*, const std::vector<E>& s, F&& f) {
    key(n);
    out_ += '[';
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (i) out_ += ',';
      out_ += '{';
      first_ = true;
      f(*this, s[i]);
      out_ += '}';
    }
    out_ += ']';
    first_ = false;
  }
  void constant(const char*, const char*, const char*) {}

 private:
  void key(Name n) {
    if (!first_) out_ += ',';
    first_ = false;
    out_ += '"';
    out_ += n.ros1;
    out_ += "\":";
  }
  template <class T>
  void scalar(const T& x) {
    if constexpr (std::is_same_v<T, std::string>) {
      append_string(out_, x);
    } else if constexpr (std::is_same_v<T, bool>) {
      out_ += x ? "true" : "false";
    } else if constexpr (sizeof(T) == 1) {
      append_number(out_, static_cast<int>(x));  // int8/uint8 as numbers, not characters
    } else {
      append_number(out_, x);
    }
  }
  template <class T>
  void list(const T* p, std::size_t n) {
    out_ += '[';
    for (std::size_t i = 0; i < n; ++i) {
      if (i) out_ += ',';
      scalar(p[i]);
    }
    out_ += ']';
  }

  std::string& out_;
  bool first_ = true;
};

}  // namespace

std::string to_json(const Message& m) {
  std::string out;
  std::visit(
      [&](const auto& x) {
        JsonWriter w(out);
        out += '{';
        fields::visit_fields(w, x);
        out += '}';
      },
      m);
  return out;
}

}  // namespace rescuesim::msg
