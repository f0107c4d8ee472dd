// JSON of a message for Foxglove's `json` encoding: one compact object with ROS 1 field names,
// stamps as {"sec":..,"nsec":..}, uint8[] as base64 strings, and non-finite floats (REP-117's
// ±inf, NaN) as null because JSON has no literal for them. And the way back (from_json), for
// what Foxglove clients publish: the same field list read with nlohmann::json.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "msgs/base64.h"
#include "msgs/message_fields.h"
#include "msgs/serialize.h"
#include "msgs/wire.h"

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


/// Reads a message out of a parsed JSON object by the field list: keys are ROS 1 field names (a
/// differing ROS 2 name is taken too), a field left out keeps its default (Foxglove's publish
/// panels and teleop send only what they set, as rosbridge allows), and a key that is no field
/// is an error, so that a misspelt field is not silently zero.
class JsonReader {
 public:
  JsonReader(const nlohmann::json& root, const char* type) : path_(type) { enter(root, nullptr); }

  template <class T>
  void value(Name n, T& x) {
    if (const nlohmann::json* j = field(n)) scalar(n.ros1, *j, x);
  }
  void time(Name n, SimTime& t) {
    const nlohmann::json* j = field(n);
    if (j == nullptr) return;
    enter(*j, n.ros1);
    std::int64_t sec = 0;
    std::uint32_t nsec = 0;
    if (const nlohmann::json* s = field("sec")) scalar("sec", *s, sec);
    // ROS 2's builtin_interfaces/Time says nanosec; ROS 1's JSON (and ours) nsec
    for (const char* key : {"nsec", "nanosec"}) {
      if (const nlohmann::json* ns = field(key)) scalar(key, *ns, nsec);
    }
    if (nsec >= 1'000'000'000u) path_.fail("nsec", "expected fewer than 1e9 nanoseconds, got " + std::to_string(nsec));
    if (sec < -(std::int64_t{1} << 31) || sec >= (std::int64_t{1} << 32)) path_.fail("sec", "out of range: " + std::to_string(sec));
    leave();
    t.ns = sec * 1'000'000'000 + nsec;
  }
  void header(Name n, Header& h) {
    const nlohmann::json* j = field(n);
    if (j == nullptr) return;
    enter(*j, n.ros1);
    time("stamp", h.stamp);
    value("frame_id", h.frame_id);
    std::uint32_t seq = 0;  // ROS 1's header has it; it is the transport's, not the message's
    value("seq", seq);
    leave();
  }
  template <class T, std::size_t N>
  void array(Name n, std::array<T, N>& a) {
    const nlohmann::json* j = field(n);
    if (j == nullptr) return;
    if (!j->is_array() || j->size() != N) path_.fail(n.ros1, "expected an array of " + std::to_string(N) + " numbers, got " + shown(*j));
    for (std::size_t i = 0; i < N; ++i) element(n.ros1, i, (*j)[i], a[i]);
  }
  template <class T>
  void sequence(Name n, std::vector<T>& s) {
    const nlohmann::json* j = field(n);
    if (j == nullptr) return;
    if constexpr (std::is_same_v<T, std::uint8_t>) {
      if (j->is_string()) {  // uint8[] as to_json writes it
        auto bytes = decode_base64(j->get_ref<const std::string&>());
        if (!bytes) path_.fail(n.ros1, "a string here must be base64 (RFC 4648, padded)");
        s = std::move(*bytes);
        return;
      }
    }
    if (!j->is_array()) path_.fail(n.ros1, "expected an array, got " + shown(*j));
    s.assign(j->size(), T{});
    for (std::size_t i = 0; i < j->size(); ++i) {
      T x{};
      element(n.ros1, i, (*j)[i], x);
      s[i] = std::move(x);
    }
  }
  template <class F>
  void message(Name n, const char*, F&& f) {
    const nlohmann::json* j = field(n);
    if (j == nullptr) return;
    enter(*j, n.ros1);
    f(*this);
    leave();
  }
  template <class E, class F>
  void messages(Name n, const char*, std::vector<E>& s, F&& f) {
    const nlohmann::json* j = field(n);
    if (j == nullptr) return;
    if (!j->is_array()) path_.fail(n.ros1, "expected an array of objects, got " + shown(*j));
    s.assign(j->size(), E{});
    for (std::size_t i = 0; i < j->size(); ++i) {
      enter((*j)[i], n.ros1, static_cast<std::int64_t>(i));
      f(*this, s[i]);
      leave();
    }
  }
  void constant(const char*, const char*, const char*) {}

  /// The top-level object's keys must all have been fields too.
  void finish() { leave(); }

 private:
  struct Level {
    const nlohmann::json* object;
    std::vector<std::string_view> read;  ///< keys of `object` read as fields
    bool named = false;                  ///< pushed on path_
  };

  static std::string shown(const nlohmann::json& j) {
    std::string s = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    return s.size() > 40 ? s.substr(0, 37) + "..." : s;
  }
  void enter(const nlohmann::json& j, const char* name, std::int64_t index = -1) {
    if (name != nullptr) path_.push(name, index);
    if (!j.is_object()) path_.fail(nullptr, "expected an object, got " + shown(j));
    levels_.push_back({&j, {}, name != nullptr});
  }
  void leave() {
    const Level& l = levels_.back();
    if (l.read.size() < l.object->size()) {
      for (const auto& item : l.object->items()) {
        if (std::find(l.read.begin(), l.read.end(), item.key()) == l.read.end()) path_.fail(item.key().c_str(), "no such field");
      }
    }
    if (l.named) path_.pop();
    levels_.pop_back();
  }
  /// The member of the current object for field n (ROS 1 name, else ROS 2), or nullptr.
  const nlohmann::json* field(Name n) {
    Level& l = levels_.back();
    auto it = l.object->find(n.ros1);
    if (it == l.object->end() && std::string_view(n.ros1) != n.ros2) it = l.object->find(n.ros2);
    if (it == l.object->end()) return nullptr;
    l.read.push_back(it.key());
    return &*it;
  }
  template <class T>
  void element(const char* name, std::size_t i, const nlohmann::json& j, T& x) {
    path_.push(name, static_cast<std::int64_t>(i));
    scalar(nullptr, j, x);
    path_.pop();
  }
  template <class T>
  void scalar(const char* name, const nlohmann::json& j, T& x) {
    if constexpr (std::is_same_v<T, std::string>) {
      if (!j.is_string()) path_.fail(name, "expected a string, got " + shown(j));
      x = j.get<std::string>();
    } else if constexpr (std::is_same_v<T, bool>) {
      if (!j.is_boolean()) path_.fail(name, "expected true or false, got " + shown(j));
      x = j.get<bool>();
    } else if constexpr (std::is_floating_point_v<T>) {
      if (j.is_null()) {  // to_json writes non-finite values as null
        x = std::numeric_limits<T>::quiet_NaN();
        return;
      }
      if (!j.is_number()) path_.fail(name, "expected a number, got " + shown(j));
      x = static_cast<T>(j.get<double>());
    } else {
      static_assert(std::is_integral_v<T>);
      bool fits = false;
      if (j.is_number_unsigned()) {
        fits = j.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<T>::max());
      } else if (j.is_number_integer()) {
        const std::int64_t v = j.get<std::int64_t>();
        fits = v >= static_cast<std::int64_t>(std::numeric_limits<T>::min()) &&
               (v < 0 || static_cast<std::uint64_t>(v) <= static_cast<std::uint64_t>(std::numeric_limits<T>::max()));
      } else {
        path_.fail(name, "expected an integer, got " + shown(j));
      }
      if (!fits) {
        path_.fail(name, "expected an integer from " + std::to_string(std::numeric_limits<T>::min()) + " to " +
                             std::to_string(std::numeric_limits<T>::max()) + ", got " + shown(j));
      }
      x = j.is_number_unsigned() ? static_cast<T>(j.get<std::uint64_t>()) : static_cast<T>(j.get<std::int64_t>());
    }
  }

  wire::FieldPath path_;
  std::vector<Level> levels_;
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

Message from_json(const TypeSupport& type, std::string_view text) {
  if (type.variant_index >= std::variant_size_v<Message>) {
    throw Error("from_json: " + type.ros1_name + ": not a msg::Message type (variant index " + std::to_string(type.variant_index) + ")");
  }
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte says where; the library's own text repeats it with its error id
    throw Error(type.ros1_name + ": not valid JSON at byte " + std::to_string(e.byte) + " of " + std::to_string(text.size()));
  } catch (const nlohmann::json::exception&) {
    // a number beyond a double's range (out_of_range 406), found by fuzzing
    throw Error(type.ros1_name + ": not valid JSON: a number out of range");
  }
  return fields::with_alternative(type.variant_index, [&](auto id) -> Message {
    using T = typename decltype(id)::type;
    T m;
    JsonReader r(root, type.ros1_name.c_str());
    fields::visit_fields(r, m);
    r.finish();
    return m;
  });
}

}  // namespace rescuesim::msg
