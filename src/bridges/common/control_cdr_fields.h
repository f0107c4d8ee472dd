#pragma once
/// Internal to the control codecs (control_cdr*.cpp): one field list per message type,
/// Fields<T>::visit(io, m, version), written once for both directions: `io` is a cdr::Writer
/// (and the message const) or a cdr::Reader, so that encoder and decoder cannot drift apart.
/// Field names are the ROS ones; the reader puts them in its errors. This header has the
/// helpers, the types every family uses (geometry_msgs, Result) and the codec templates; each
/// family's .cpp adds its own types' field lists and instantiates the codecs of its tags with
/// RS_CONTROL_CDR_SERVICE / RS_CONTROL_CDR_TOPIC.

#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "bridges/common/cdr_stream.h"
#include "bridges/common/control_cdr.h"
#include "core/error.h"

namespace rescuesim::control {

namespace wire {

// ---- helpers shared by the field lists ----

template <class T>
struct Fields;  // Fields<T>::visit(io, m, version): T's members in wire order

/// A nested message: its members under `name` in the field path.
template <class IO, class M>
void message(IO& io, const char* name, M& m, WireVersion v) {
  io.scope(name, [&] { Fields<std::remove_const_t<M>>::visit(io, m, v); });
}

/// The fewest bytes an E takes on the wire (empty strings and sequences, no padding): a
/// decoder checks a count against it before allocating.
template <class E>
std::size_t min_size(WireVersion v) {
  cdr::Writer w = cdr::Writer::measure(false);
  const E e{};
  Fields<E>::visit(w, e, v);
  return w.size();
}

/// A sequence of messages (`bound`: a bounded sequence's bound).
template <class IO, class V>
void messages(IO& io, const char* name, V& s, WireVersion v, std::uint32_t bound = cdr::kUnbounded) {
  using E = typename std::remove_const_t<V>::value_type;
  std::size_t least = 0;
  if constexpr (!IO::kWrites) least = min_size<E>(v);
  io.elements(name, s, least, bound, [&](auto& e) { Fields<E>::visit(io, e, v); });
}

/// An enum carried as a uint8.
template <class IO, class E>
void enum8(IO& io, const char* name, E& e) {
  if constexpr (IO::kWrites) {
    io.value(name, static_cast<std::uint8_t>(e));
  } else {
    std::uint8_t x = 0;
    io.value(name, x);
    e = static_cast<E>(x);
  }
}

/// simulation_interfaces/msg/Resource (uri, resource_string) under `name`.
template <class IO, class S>
void resource(IO& io, const char* name, S& uri, S& resource_string) {
  io.scope(name, [&] {
    io.string("uri", uri);
    io.string("resource_string", resource_string);
  });
}

// ---- geometry_msgs, std_msgs ----

/// geometry_msgs/Vector3 and Point.
template <>
struct Fields<Vec3> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.value("x", m.x());
    io.value("y", m.y());
    io.value("z", m.z());
  }
};

/// geometry_msgs/Quaternion.
template <>
struct Fields<Quat> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.value("x", m.x());
    io.value("y", m.y());
    io.value("z", m.z());
    io.value("w", m.w());
  }
};

/// geometry_msgs/Pose.
template <>
struct Fields<Pose3> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "position", m.p, v);
    message(io, "orientation", m.q, v);
  }
};

// ---- simulation_interfaces/msg ----

template <>
struct Fields<Result> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.value("result", m.result);
    io.string("error_message", m.error_message);
  }
};
// ---- whole bodies ----

/// A body: the struct's members, or the struct as the one member `field` when it is named.
template <class IO, class T>
void body(IO& io, T& value, const char* field, WireVersion v) {
  if (field != nullptr) {
    message(io, field, value, v);
  } else {
    Fields<std::remove_const_t<T>>::visit(io, value, v);
  }
}

template <class T>
Decoded<T> decode_body(std::span<const std::uint8_t> cdr, const std::string& type, const char* field,
                       WireVersion v) {
  try {
    cdr::Reader r(cdr, type.c_str());
    T value{};
    body(r, value, field, v);
    r.finish();
    return {std::move(value), {}};
  } catch (const Error& e) {
    return {std::nullopt, e.message()};
  }
}

template <class T>
void encode_body(const T& value, const std::string& type, const char* field, WireVersion v,
                 std::vector<std::uint8_t>& out) {
  cdr::Writer w(out, type.c_str());
  body(w, value, field, v);
}

enum class Part { request, response, message };

/// "<ros type>_Request", "<ros type>_Response" or the topic's type: the first word of every
/// error about the body.
template <class S>
const std::string& type_name(Part part) {
  static const std::string names[] = {std::string(info(S::id).ros_type) + "_Request",
                                      std::string(info(S::id).ros_type) + "_Response", info(S::id).ros_type};
  return names[static_cast<int>(part)];
}

}  // namespace wire

template <class S>
Decoded<typename S::Request> decode_request(std::span<const std::uint8_t> cdr, WireVersion version) {
  return wire::decode_body<typename S::Request>(cdr, wire::type_name<S>(wire::Part::request), S::request_field, version);
}
template <class S>
void encode_request(const typename S::Request& request, WireVersion version, std::vector<std::uint8_t>& out) {
  wire::encode_body(request, wire::type_name<S>(wire::Part::request), S::request_field, version, out);
}
template <class S>
Decoded<typename S::Response> decode_response(std::span<const std::uint8_t> cdr, WireVersion version) {
  return wire::decode_body<typename S::Response>(cdr, wire::type_name<S>(wire::Part::response), S::response_field, version);
}
template <class S>
void encode_response(const typename S::Response& response, WireVersion version, std::vector<std::uint8_t>& out) {
  wire::encode_body(response, wire::type_name<S>(wire::Part::response), S::response_field, version, out);
}
template <class M>
Decoded<typename M::Message> decode_message(std::span<const std::uint8_t> cdr, WireVersion version) {
  return wire::decode_body<typename M::Message>(cdr, wire::type_name<M>(wire::Part::message), nullptr, version);
}
template <class M>
void encode_message(const typename M::Message& message, WireVersion version, std::vector<std::uint8_t>& out) {
  wire::encode_body(message, wire::type_name<M>(wire::Part::message), nullptr, version, out);
}

/// Instantiates the four codecs of a service tag (in the .cpp that has its field lists).
#define RS_CONTROL_CDR_SERVICE(Tag)                                                                              \
  template Decoded<iface::Tag::Request> decode_request<iface::Tag>(std::span<const std::uint8_t>, WireVersion);   \
  template void encode_request<iface::Tag>(const iface::Tag::Request&, WireVersion, std::vector<std::uint8_t>&);   \
  template Decoded<iface::Tag::Response> decode_response<iface::Tag>(std::span<const std::uint8_t>, WireVersion); \
  template void encode_response<iface::Tag>(const iface::Tag::Response&, WireVersion, std::vector<std::uint8_t>&);
/// Instantiates the two codecs of a topic tag.
#define RS_CONTROL_CDR_TOPIC(Tag)                                                                              \
  template Decoded<iface::Tag::Message> decode_message<iface::Tag>(std::span<const std::uint8_t>, WireVersion); \
  template void encode_message<iface::Tag>(const iface::Tag::Message&, WireVersion, std::vector<std::uint8_t>&);

}  // namespace rescuesim::control
