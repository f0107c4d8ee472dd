#include "bridges/ros1/ros1_velocity.h"

#include <fmt/format.h>

#include <cstring>

#include "core/error.h"
#include "msgs/serialize.h"

namespace rescuesim::ros1_wire {

namespace {

const msg::TypeSupport& twist_type() {
  static const msg::TypeSupport* t = msg::find_type("geometry_msgs/Twist");
  if (!t) throw Error("ROS 1: the serialiser lacks geometry_msgs/Twist");
  return *t;
}

/// Reads the std_msgs/Header at the start of a TwistStamped, checking every length against the
/// bytes left (names the field that does not fit, as msgs' decoders do).
class HeaderReader {
 public:
  explicit HeaderReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  std::uint32_t u32(const char* field) {
    need(field, 4, "a value");
    std::uint32_t v = 0;
    // ROS 1 is little endian: assemble the bytes (no alignment, any host)
    for (int i = 3; i >= 0; --i) v = (v << 8) | bytes_[pos_ + static_cast<std::size_t>(i)];
    pos_ += 4;
    return v;
  }
  std::string string(const char* field) {
    const std::uint32_t len = u32(field);
    need(field, len, "string of " + std::to_string(len) + " bytes");
    std::string s(reinterpret_cast<const char*>(bytes_.data() + pos_), len);
    pos_ += len;
    return s;
  }
  std::span<const std::uint8_t> rest() const { return bytes_.subspan(pos_); }

 private:
  void need(const char* field, std::size_t n, const std::string& what) const {
    const std::size_t left = bytes_.size() - pos_;
    if (n > left) {
      throw Error(fmt::format("{}: header.{}: truncated: {} needs {} bytes, {} left", kTwistStampedName, field, what, n, left));
    }
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
};

}  // namespace

std::optional<VelocityType> velocity_type(std::string_view type, std::string_view md5, std::string* why) {
  const auto refuse = [&](std::string text) -> std::optional<VelocityType> {
    if (why) *why = std::move(text);
    return std::nullopt;
  };
  const msg::TypeSupport& twist = twist_type();
  std::optional<VelocityType> kind;
  std::string_view expected;
  if (type == twist.ros1_name) {
    kind = VelocityType::twist;
    expected = twist.ros1_md5;
  } else if (type == kTwistStampedName) {
    kind = VelocityType::twist_stamped;
    expected = kTwistStampedMd5;
  } else {
    return refuse(fmt::format("a {} message: cmd_vel takes {} or {}", type.empty() ? "(type not given)" : type, twist.ros1_name,
                              kTwistStampedName));
  }
  if (md5 != expected) {
    return refuse(fmt::format("a {} with MD5 {}, expected {} (another definition of the type: rebuild the publisher against "
                              "the standard geometry_msgs)",
                              type, md5.empty() ? "(none)" : md5, expected));
  }
  return kind;
}

VelocityCommand decode_velocity(VelocityType type, std::span<const std::uint8_t> bytes) {
  VelocityCommand c;
  if (type == VelocityType::twist) {
    c.twist = std::get<msg::Twist>(msg::from_ros1(twist_type(), bytes));
    return c;
  }
  // std_msgs/Header: uint32 seq, time stamp (uint32 sec, uint32 nsec), string frame_id
  HeaderReader r(bytes);
  r.u32("seq");
  const std::uint32_t sec = r.u32("stamp.sec");
  const std::uint32_t nsec = r.u32("stamp.nsec");
  c.frame_id = r.string("frame_id");
  c.stamped = true;
  c.stamp = SimTime{static_cast<std::int64_t>(sec) * 1'000'000'000 + nsec};
  // the Twist that follows, with msgs' decoder (which also refuses trailing bytes); its errors
  // name the field inside the TwistStamped
  try {
    c.twist = std::get<msg::Twist>(msg::from_ros1(twist_type(), r.rest()));
  } catch (const Error& e) {
    std::string what = e.what();
    const std::string prefix = twist_type().ros1_name + ": ";
    if (what.rfind(prefix, 0) == 0) what.erase(0, prefix.size());
    throw Error(fmt::format("{}: twist: {}", kTwistStampedName, what));
  }
  return c;
}


}  // namespace rescuesim::ros1_wire
