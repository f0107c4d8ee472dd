#pragma once
/// Wire formats of the neutral messages (msgs/messages.h):
///   ROS 1      the TCPROS serialisation (little endian, no alignment, Header with seq),
///              the full message definition (gendeps --cat style) and its MD5 as ROS 1 computes it;
///   ROS 2      CDR / XCDR1 little endian with the 4-byte encapsulation header 00 01 00 00
///              (alignment counted after it), the `ros2msg` schema text (MCAP ros2 profile);
///   JSON       one object per message with ROS field names (for Foxglove's json encoding),
///              and a JSON Schema per type.
/// Decoders are bounds-checked: malformed bytes from the network give an Error naming the
/// type and the field, never a crash or an out-of-range read.
///
/// Layout choices (one field list in msgs/message_fields.h drives every format):
///   - ROS 2 layouts are Humble's. In particular sensor_msgs/Range has NO `float32 variance`
///     (added in Iron); an Iron/Jazzy subscriber expects 4 more bytes, so /sonar needs a Humble
///     peer or a per-distro bridge option. Everything else we use is unchanged Humble → Jazzy.
///   - ROS 1 `std_msgs/Header.seq` is written from to_ros1's `seq` for the message's own header
///     and 0 for nested headers (TFMessage, Path); decoders read and drop it.
///   - std_msgs/Float64MultiArray: the layout is written empty; a received layout is
///     validated and dropped (the neutral struct has no place for it).
///   - Time: ROS 1 `time` is uint32 sec + uint32 nsec (negative stamps wrap); ROS 2 is int32 sec
///     + uint32 nanosec.
///   - CDR: sequences of primitives align their first element only when non-empty (as Fast-CDR
///     and Cyclone do); from_cdr accepts encapsulation 00 01 (CDR_LE, XCDR1) only, and honours
///     the options' two low bits as a count of trailing padding bytes (DDS-XTypes 7.6.3.1.2).
///   - JSON uses ROS 1 field names (CameraInfo D/K/R/P), stamps {"sec","nsec"}, no Header.seq,
///     and writes non-finite floats (REP-117 ±inf, NaN) as null; the schemas still declare them
///     "number" because Foxglove's schema reader accepts only one type name per field.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "msgs/messages.h"

namespace rescuesim::msg {

/// Everything a transport needs to know about one message type.
struct TypeSupport {
  std::string ros1_name;        ///< "sensor_msgs/LaserScan"
  std::string ros2_name;        ///< "sensor_msgs/msg/LaserScan"
  std::string dds_name;         ///< "sensor_msgs::msg::dds_::LaserScan_"
  std::string ros1_md5;         ///< 32 lowercase hex digits, as rosmsg md5 prints
  std::string ros1_definition;  ///< full text: the type's own .msg, then for each dependency a
                                ///< line of 80 '=', "MSG: pkg/Type" and its .msg (as roscpp's
                                ///< message_definition and rosbag store it)
  std::string ros2_definition;  ///< `ros2msg` schema: same layout with ROS 2 types (builtin_interfaces/Time, no seq)
  std::string json_schema;      ///< JSON Schema (draft 07) of to_json's output
  std::size_t variant_index;    ///< index of the alternative in msg::Message
};

/// The type support for a ROS 1 type name ("sensor_msgs/LaserScan") or ROS 2 name
/// ("sensor_msgs/msg/LaserScan"), or nullptr when the type is not one of msg::Message's.
const TypeSupport* find_type(std::string_view name);
/// The type support of a message's alternative.
const TypeSupport& type_of(const Message& m);
/// Every supported type, in msg::Message alternative order.
const std::vector<TypeSupport>& all_types();

/// ROS 1 serialisation (appended to `out`); `seq` fills std_msgs/Header.seq of stamped messages.
void to_ros1(const Message& m, std::vector<std::uint8_t>& out, std::uint32_t seq = 0);
/// The number of bytes to_ros1 appends for `m`.
std::size_t ros1_size(const Message& m);
/// to_ros1 into a buffer the caller owns, of exactly ros1_size(m) bytes (a transport's own send
/// buffer: a megabyte image is written once, with no vector to fill with zeros first and copy
/// from). A buffer of another size is a bug of the caller: it aborts (RS_DEMAND).
void write_ros1(const Message& m, std::span<std::uint8_t> out, std::uint32_t seq = 0);
/// CDR (XCDR1, little endian) with the encapsulation header, appended to `out`.
void to_cdr(const Message& m, std::vector<std::uint8_t>& out);
/// One JSON object (compact) with ROS field names; stamps as {"sec":..,"nsec":..}; byte arrays
/// (Image.data, PointCloud2.data) base64-encoded strings, as Foxglove's json encoding expects.
std::string to_json(const Message& m);

/// Decoders: the bytes must hold exactly one message of `type` (trailing bytes are an error).
/// Throw rescuesim::Error ("sensor_msgs/LaserScan: ranges: sequence of 4000000000 elements
/// needs 16000000000 bytes, 12 left") on malformed input; from_cdr's errors use the ROS 2 type
/// and field names ("sensor_msgs/msg/CameraInfo: k: ..."). Counts are checked against the bytes
/// left before anything is allocated.
Message from_ros1(const TypeSupport& type, std::span<const std::uint8_t> bytes);
Message from_cdr(const TypeSupport& type, std::span<const std::uint8_t> bytes);
/// JSON as to_json writes it (ROS 1 field names; a differing ROS 2 name is taken too; stamps
/// with nsec or nanosec; uint8[] as base64 or an array of numbers; null for a non-finite float).
/// A field left out keeps its default; a key that is no field is an error naming it.
Message from_json(const TypeSupport& type, std::string_view text);

/// The MD5 of a ROS 1 message text as `genmsg` computes it (comments and blank lines dropped,
/// constants first, field types of non-builtin types replaced by their own MD5): exposed for
/// tests. `text_of(type)` gives the .msg text of a dependency ("std_msgs/Header").
std::string ros1_md5_of(std::string_view msg_text, std::string_view package,
                        std::string (*text_of)(std::string_view type));

}  // namespace rescuesim::msg
