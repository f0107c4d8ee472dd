#pragma once
/// rescuesim's messages on roscpp without generated message headers: a message already in ROS 1
/// wire format (msg::to_ros1), with the type it claims to be, which roscpp sends and receives like
/// a generated message (the trick of topic_tools::ShapeShifter). Used by the ROS 1 bridge and by
/// ROS 1 nodes built on rescuesim's messages (examples/ros1/nav). Include it only from .cpp files:
/// it brings roscpp's headers with it.

#include <ros/message_traits.h>
#include <ros/serialization.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "msgs/serialize.h"

namespace rescuesim::ros1_wire {

/// A message already in ROS 1 wire format (without the 4-byte length roscpp adds), with the type
/// it claims to be. roscpp sends and receives it like a generated message (the same trick as
/// topic_tools::ShapeShifter): the traits below report the type's MD5, name and definition from
/// rescuesim's TypeSupport, and the serializer copies the bytes.
struct RawMessage {
  const msg::TypeSupport* type = nullptr;
  std::vector<std::uint8_t> bytes;
};

/// A rescuesim message on its way out, serialised by roscpp's own call into roscpp's own send
/// buffer (msg::write_ros1): one pass over an image's bytes, where a RawMessage costs a buffer
/// filled with zeros, the serialisation into it and roscpp's copy out of it. Publish only: it
/// borrows `message`, which must outlive the publish() call.
struct OutgoingMessage {
  const msg::TypeSupport* type = nullptr;
  const msg::Message* message = nullptr;
  std::uint32_t seq = 0;   ///< std_msgs/Header.seq
  std::uint32_t size = 0;  ///< msg::ros1_size(*message)
};

}  // namespace rescuesim::ros1_wire

namespace ros::message_traits {

// the static forms are what a subscription asks before it has a message: the user (bridge or
// node) gives the real MD5 and type in its SubscribeOptions and AdvertiseOptions
template <>
struct MD5Sum<rescuesim::ros1_wire::RawMessage> {
  static const char* value() { return "*"; }
  static const char* value(const rescuesim::ros1_wire::RawMessage& m) { return m.type ? m.type->ros1_md5.c_str() : "*"; }
};
template <>
struct DataType<rescuesim::ros1_wire::RawMessage> {
  static const char* value() { return "*"; }
  static const char* value(const rescuesim::ros1_wire::RawMessage& m) { return m.type ? m.type->ros1_name.c_str() : "*"; }
};
template <>
struct Definition<rescuesim::ros1_wire::RawMessage> {
  static const char* value() { return ""; }
  static const char* value(const rescuesim::ros1_wire::RawMessage& m) { return m.type ? m.type->ros1_definition.c_str() : ""; }
};

template <>
struct MD5Sum<rescuesim::ros1_wire::OutgoingMessage> {
  static const char* value(const rescuesim::ros1_wire::OutgoingMessage& m) { return m.type->ros1_md5.c_str(); }
};
template <>
struct DataType<rescuesim::ros1_wire::OutgoingMessage> {
  static const char* value(const rescuesim::ros1_wire::OutgoingMessage& m) { return m.type->ros1_name.c_str(); }
};
template <>
struct Definition<rescuesim::ros1_wire::OutgoingMessage> {
  static const char* value(const rescuesim::ros1_wire::OutgoingMessage& m) { return m.type->ros1_definition.c_str(); }
};

}  // namespace ros::message_traits

namespace ros::serialization {

template <>
struct Serializer<rescuesim::ros1_wire::RawMessage> {
  template <typename Stream>
  static void write(Stream& stream, const rescuesim::ros1_wire::RawMessage& m) {
    const auto n = static_cast<std::uint32_t>(m.bytes.size());
    if (n > 0) std::memcpy(stream.advance(n), m.bytes.data(), n);
  }
  template <typename Stream>
  static void read(Stream& stream, rescuesim::ros1_wire::RawMessage& m) {
    const std::uint32_t n = stream.getLength();
    m.bytes.assign(stream.getData(), stream.getData() + n);
    stream.advance(n);
  }
  static std::uint32_t serializedLength(const rescuesim::ros1_wire::RawMessage& m) { return static_cast<std::uint32_t>(m.bytes.size()); }
};

template <>
struct Serializer<rescuesim::ros1_wire::OutgoingMessage> {
  template <typename Stream>
  static void write(Stream& stream, const rescuesim::ros1_wire::OutgoingMessage& m) {
    rescuesim::msg::write_ros1(*m.message, {stream.advance(m.size), m.size}, m.seq);
  }
  static std::uint32_t serializedLength(const rescuesim::ros1_wire::OutgoingMessage& m) { return m.size; }
};

}  // namespace ros::serialization
