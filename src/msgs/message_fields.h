#pragma once
/// The one field list of every message (internal to msgs/): `visit_fields(v, m)` walks a
/// message's fields in ROS order and hands each to a visitor, which the ROS 1 and CDR
/// writers and readers, the JSON writer and the definition / schema builders all are. So the
/// formats cannot disagree about a field's name, type or place.
///
/// A visitor provides (M is the message type, const for writers, non-const for readers):
///   value(Name, T&)            a primitive (float, double, int8, uint8, uint32, bool) or std::string
///   time(Name, SimTime&)       ROS 1 `time`, ROS 2 `builtin_interfaces/Time`
///   header(Name, Header&)      std_msgs/Header (ROS 1 adds seq)
///   array(Name, std::array&)   a fixed-size array of a primitive (`float64[9]`)
///   sequence(Name, vector&)    a variable-size array of a primitive or string (`float32[]`)
///   message(Name, type, f)     a nested message of ROS type `type`; `f(visitor)` visits its fields
///   messages(Name, type, vector&, f)  a sequence of nested messages; `f(visitor, element)`
///   constant(type, name, value) a constant of the .msg (definitions only)
/// The neutral structs flatten some ROS nesting (CameraInfo's roi, Odometry's covariances):
/// the field list puts it back.

#include <array>
#include <concepts>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "msgs/messages.h"

namespace rescuesim::msg::fields {

/// A field's name in ROS 1 and in ROS 2 (they differ only in CameraInfo: D/d, K/k, R/r, P/p).
struct Name {
  const char* ros1;  ///< ROS 1 name (also used by JSON)
  const char* ros2;  ///< ROS 2 name
  constexpr Name(const char* both) : ros1(both), ros2(both) {}  // NOLINT: implicit on purpose
  constexpr Name(const char* r1, const char* r2) : ros1(r1), ros2(r2) {}
};

/// True when M is T, possibly const.
template <class M, class T>
concept Is = std::same_as<std::remove_const_t<M>, T>;

/// std_msgs/MultiArrayDimension: not kept in the neutral Float64MultiArray, read and dropped.
struct MultiArrayDimension {
  std::string label;
  std::uint32_t size = 0, stride = 0;
};

/// geometry_msgs/Point from a Vec3.
template <class V, class P>
void point(V& v, Name n, P& p) {
  v.message(n, "geometry_msgs/Point", [&](auto& w) {
    w.value("x", p.x());
    w.value("y", p.y());
    w.value("z", p.z());
  });
}

/// geometry_msgs/Vector3 from a Vec3.
template <class V, class P>
void vector3(V& v, Name n, P& p) {
  v.message(n, "geometry_msgs/Vector3", [&](auto& w) {
    w.value("x", p.x());
    w.value("y", p.y());
    w.value("z", p.z());
  });
}

/// geometry_msgs/Quaternion in ROS order x, y, z, w (Eigen stores them otherwise).
template <class V, class Q>
void quaternion(V& v, Name n, Q& q) {
  v.message(n, "geometry_msgs/Quaternion", [&](auto& w) {
    w.value("x", q.x());
    w.value("y", q.y());
    w.value("z", q.z());
    w.value("w", q.w());
  });
}

/// geometry_msgs/Pose from a Pose3.
template <class V, class X>
void pose(V& v, Name n, X& X_AB) {
  v.message(n, "geometry_msgs/Pose", [&](auto& w) {
    point(w, "position", X_AB.p);
    quaternion(w, "orientation", X_AB.q);
  });
}

/// geometry_msgs/Transform from a Pose3.
template <class V, class X>
void transform(V& v, Name n, X& X_AB) {
  v.message(n, "geometry_msgs/Transform", [&](auto& w) {
    vector3(w, "translation", X_AB.p);
    quaternion(w, "rotation", X_AB.q);
  });
}

/// The fields of rosgraph_msgs/Clock, in .msg order.
template <class V, class M>
  requires Is<M, Clock>
void visit_fields(V& v, M& m) {
  v.time("clock", m.clock);
}

/// The fields of sensor_msgs/LaserScan, in .msg order.
template <class V, class M>
  requires Is<M, LaserScan>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  v.value("angle_min", m.angle_min);
  v.value("angle_max", m.angle_max);
  v.value("angle_increment", m.angle_increment);
  v.value("time_increment", m.time_increment);
  v.value("scan_time", m.scan_time);
  v.value("range_min", m.range_min);
  v.value("range_max", m.range_max);
  v.sequence("ranges", m.ranges);
  v.sequence("intensities", m.intensities);
}

/// The fields of sensor_msgs/Range, in .msg order.
template <class V, class M>
  requires Is<M, Range>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  v.constant("uint8", "ULTRASOUND", "0");
  v.constant("uint8", "INFRARED", "1");
  v.value("radiation_type", m.radiation_type);
  v.value("field_of_view", m.field_of_view);
  v.value("min_range", m.min_range);
  v.value("max_range", m.max_range);
  v.value("range", m.range);
}

/// The fields of sensor_msgs/Imu, in .msg order.
template <class V, class M>
  requires Is<M, Imu>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  quaternion(v, "orientation", m.orientation);
  v.array("orientation_covariance", m.orientation_covariance);
  vector3(v, "angular_velocity", m.angular_velocity);
  v.array("angular_velocity_covariance", m.angular_velocity_covariance);
  vector3(v, "linear_acceleration", m.linear_acceleration);
  v.array("linear_acceleration_covariance", m.linear_acceleration_covariance);
}

/// The fields of geometry_msgs/Twist, in .msg order.
template <class V, class M>
  requires Is<M, Twist>
void visit_fields(V& v, M& m) {
  vector3(v, "linear", m.linear);
  vector3(v, "angular", m.angular);
}

/// The fields of nav_msgs/Odometry, in .msg order.
template <class V, class M>
  requires Is<M, Odometry>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  v.value("child_frame_id", m.child_frame_id);
  v.message("pose", "geometry_msgs/PoseWithCovariance", [&](auto& w) {
    pose(w, "pose", m.pose);
    w.array("covariance", m.pose_covariance);
  });
  v.message("twist", "geometry_msgs/TwistWithCovariance", [&](auto& w) {
    w.message("twist", "geometry_msgs/Twist", [&](auto& x) { visit_fields(x, m.twist); });
    w.array("covariance", m.twist_covariance);
  });
}

/// The fields of sensor_msgs/JointState, in .msg order.
template <class V, class M>
  requires Is<M, JointState>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  v.sequence("name", m.name);
  v.sequence("position", m.position);
  v.sequence("velocity", m.velocity);
  v.sequence("effort", m.effort);
}

/// The fields of geometry_msgs/TransformStamped, in .msg order.
template <class V, class M>
  requires Is<M, TransformStamped>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  v.value("child_frame_id", m.child_frame_id);
  transform(v, "transform", m.transform);
}

/// The fields of tf2_msgs/TFMessage, in .msg order.
template <class V, class M>
  requires Is<M, TFMessage>
void visit_fields(V& v, M& m) {
  v.messages("transforms", "geometry_msgs/TransformStamped", m.transforms,
             [](auto& w, auto& t) { visit_fields(w, t); });
}

/// The fields of geometry_msgs/PoseStamped, in .msg order.
template <class V, class M>
  requires Is<M, PoseStamped>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  pose(v, "pose", m.pose);
}

/// The fields of nav_msgs/Path, in .msg order.
template <class V, class M>
  requires Is<M, Path>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  v.messages("poses", "geometry_msgs/PoseStamped", m.poses, [](auto& w, auto& p) { visit_fields(w, p); });
}

/// The fields of nav_msgs/OccupancyGrid, in .msg order.
template <class V, class M>
  requires Is<M, OccupancyGrid>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  v.message("info", "nav_msgs/MapMetaData", [&](auto& w) {
    w.time("map_load_time", m.map_load_time);
    w.value("resolution", m.resolution);
    w.value("width", m.width);
    w.value("height", m.height);
    pose(w, "origin", m.origin);
  });
  v.sequence("data", m.data);
}

/// The fields of std_msgs/Float64MultiArray. The layout is written empty; a received layout is
/// checked and dropped (the neutral struct has no place for it).
template <class V, class M>
  requires Is<M, Float64MultiArray>
void visit_fields(V& v, M& m) {
  std::vector<MultiArrayDimension> dim;
  std::uint32_t data_offset = 0;
  v.message("layout", "std_msgs/MultiArrayLayout", [&](auto& w) {
    w.messages("dim", "std_msgs/MultiArrayDimension", dim, [](auto& x, auto& d) {
      x.value("label", d.label);
      x.value("size", d.size);
      x.value("stride", d.stride);
    });
    w.value("data_offset", data_offset);
  });
  v.sequence("data", m.data);
}

/// The fields of rescuesim_msgs/Contacts, in .msg order.
template <class V, class M>
  requires Is<M, Contacts>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  v.sequence("touching", m.touching);
}

/// The fields of sensor_msgs/Image, in .msg order.
template <class V, class M>
  requires Is<M, Image>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  v.value("height", m.height);
  v.value("width", m.width);
  v.value("encoding", m.encoding);
  v.value("is_bigendian", m.is_bigendian);
  v.value("step", m.step);
  v.sequence("data", m.data);
}

/// The fields of sensor_msgs/CameraInfo, in .msg order.
template <class V, class M>
  requires Is<M, CameraInfo>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  v.value("height", m.height);
  v.value("width", m.width);
  v.value("distortion_model", m.distortion_model);
  v.sequence(Name("D", "d"), m.d);
  v.array(Name("K", "k"), m.k);
  v.array(Name("R", "r"), m.r);
  v.array(Name("P", "p"), m.p);
  v.value("binning_x", m.binning_x);
  v.value("binning_y", m.binning_y);
  v.message("roi", "sensor_msgs/RegionOfInterest", [&](auto& w) {
    w.value("x_offset", m.roi_x_offset);
    w.value("y_offset", m.roi_y_offset);
    w.value("height", m.roi_height);
    w.value("width", m.roi_width);
    w.value("do_rectify", m.roi_do_rectify);
  });
}

/// The fields of sensor_msgs/PointField, in .msg order.
template <class V, class M>
  requires Is<M, PointField>
void visit_fields(V& v, M& m) {
  v.constant("uint8", "INT8", "1");
  v.constant("uint8", "UINT8", "2");
  v.constant("uint8", "INT16", "3");
  v.constant("uint8", "UINT16", "4");
  v.constant("uint8", "INT32", "5");
  v.constant("uint8", "UINT32", "6");
  v.constant("uint8", "FLOAT32", "7");
  v.constant("uint8", "FLOAT64", "8");
  v.value("name", m.name);
  v.value("offset", m.offset);
  v.value("datatype", m.datatype);
  v.value("count", m.count);
}

/// The fields of sensor_msgs/PointCloud2, in .msg order.
template <class V, class M>
  requires Is<M, PointCloud2>
void visit_fields(V& v, M& m) {
  v.header("header", m.header);
  v.value("height", m.height);
  v.value("width", m.width);
  v.messages("fields", "sensor_msgs/PointField", m.fields, [](auto& w, auto& f) { visit_fields(w, f); });
  v.value("is_bigendian", m.is_bigendian);
  v.value("point_step", m.point_step);
  v.value("row_step", m.row_step);
  v.sequence("data", m.data);
  v.value("is_dense", m.is_dense);
}

/// The fields of std_msgs/String, in .msg order.
template <class V, class M>
  requires Is<M, String>
void visit_fields(V& v, M& m) {
  v.value("data", m.data);
}

/// The fields of std_msgs/Bool, in .msg order.
template <class V, class M>
  requires Is<M, Bool>
void visit_fields(V& v, M& m) {
  v.value("data", m.data);
}

/// Implementation of with_alternative: a table of one call per alternative.
template <class F, std::size_t... I>
decltype(auto) with_alternative_impl(std::size_t index, F&& f, std::index_sequence<I...>) {
  using R = decltype(f(std::type_identity<std::variant_alternative_t<0, Message>>{}));
  using Fn = R (*)(F&);
  static constexpr Fn table[] = {
      [](F& g) -> R { return g(std::type_identity<std::variant_alternative_t<I, Message>>{}); }...};
  return table[index](f);
}

/// Calls `f(std::type_identity<T>{})` with T the alternative `index` (< variant_size) of msg::Message.
template <class F>
decltype(auto) with_alternative(std::size_t index, F&& f) {
  return with_alternative_impl(index, f, std::make_index_sequence<std::variant_size_v<Message>>{});
}

}  // namespace rescuesim::msg::fields
