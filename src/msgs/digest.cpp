#include "msgs/digest.h"

#include <cstring>

namespace rescuesim::msg {

namespace {

struct Digest {
  std::uint64_t h = 0xcbf29ce484222325ull;
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= c[i];
      h *= 0x100000001b3ull;
    }
  }
  template <class T>
    requires std::is_arithmetic_v<T>
  void operator()(T v) {
    bytes(&v, sizeof v);
  }
  void operator()(const std::string& s) {
    (*this)(s.size());
    bytes(s.data(), s.size());
  }
  void operator()(SimTime t) { (*this)(t.ns); }
  void operator()(const Vec3& v) {
    for (int i = 0; i < 3; ++i) (*this)(v[i]);
  }
  void operator()(const Quat& q) {
    (*this)(q.w());
    (*this)(q.x());
    (*this)(q.y());
    (*this)(q.z());
  }
  void operator()(const Pose3& p) {
    (*this)(p.p);
    (*this)(p.q);
  }
  void operator()(const Header& hd) {
    (*this)(hd.stamp);
    (*this)(hd.frame_id);
  }
  void operator()(const Twist& t) {
    (*this)(t.linear);
    (*this)(t.angular);
  }
  template <class T, std::size_t N>
  void operator()(const std::array<T, N>& a) {
    for (const auto& x : a) (*this)(x);
  }
  template <class T>
  void operator()(const std::vector<T>& v) {
    (*this)(v.size());
    if constexpr (std::is_arithmetic_v<T>) {
      bytes(v.data(), v.size() * sizeof(T));
    } else {
      for (const auto& x : v) (*this)(x);
    }
  }
  void operator()(const TransformStamped& t) {
    (*this)(t.header);
    (*this)(t.child_frame_id);
    (*this)(t.transform);
  }
  void operator()(const PoseStamped& p) {
    (*this)(p.header);
    (*this)(p.pose);
  }
  void operator()(const PointField& f) {
    (*this)(f.name);
    (*this)(f.offset);
    (*this)(f.datatype);
    (*this)(f.count);
  }
};

}  // namespace

std::uint64_t digest(const Message& m) {
  Digest d;
  d(m.index());
  std::visit(
      [&d](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, Clock>) {
          d(x.clock);
        } else if constexpr (std::is_same_v<T, LaserScan>) {
          d(x.header), d(x.angle_min), d(x.angle_max), d(x.angle_increment), d(x.time_increment), d(x.scan_time);
          d(x.range_min), d(x.range_max), d(x.ranges), d(x.intensities);
        } else if constexpr (std::is_same_v<T, Range>) {
          d(x.header), d(x.radiation_type), d(x.field_of_view), d(x.min_range), d(x.max_range), d(x.range);
        } else if constexpr (std::is_same_v<T, Imu>) {
          d(x.header), d(x.orientation), d(x.orientation_covariance), d(x.angular_velocity), d(x.angular_velocity_covariance);
          d(x.linear_acceleration), d(x.linear_acceleration_covariance);
        } else if constexpr (std::is_same_v<T, Twist>) {
          d(x);
        } else if constexpr (std::is_same_v<T, Odometry>) {
          d(x.header), d(x.child_frame_id), d(x.pose), d(x.pose_covariance), d(x.twist), d(x.twist_covariance);
        } else if constexpr (std::is_same_v<T, JointState>) {
          d(x.header), d(x.name), d(x.position), d(x.velocity), d(x.effort);
        } else if constexpr (std::is_same_v<T, TFMessage>) {
          d(x.transforms);
        } else if constexpr (std::is_same_v<T, PoseStamped>) {
          d(x);
        } else if constexpr (std::is_same_v<T, Path>) {
          d(x.header), d(x.poses);
        } else if constexpr (std::is_same_v<T, OccupancyGrid>) {
          d(x.header), d(x.map_load_time), d(x.resolution), d(x.width), d(x.height), d(x.origin), d(x.data);
        } else if constexpr (std::is_same_v<T, Float64MultiArray>) {
          d(x.data);
        } else if constexpr (std::is_same_v<T, Contacts>) {
          d(x.header), d(x.touching);
        } else if constexpr (std::is_same_v<T, Image>) {
          d(x.header), d(x.height), d(x.width), d(x.encoding), d(x.is_bigendian), d(x.step), d(x.data);
        } else if constexpr (std::is_same_v<T, CameraInfo>) {
          d(x.header), d(x.height), d(x.width), d(x.distortion_model), d(x.d), d(x.k), d(x.r), d(x.p);
          d(x.binning_x), d(x.binning_y), d(x.roi_x_offset), d(x.roi_y_offset), d(x.roi_height), d(x.roi_width), d(x.roi_do_rectify);
        } else if constexpr (std::is_same_v<T, PointCloud2>) {
          d(x.header), d(x.height), d(x.width), d(x.fields), d(x.is_bigendian), d(x.point_step), d(x.row_step), d(x.data), d(x.is_dense);
        } else if constexpr (std::is_same_v<T, String>) {
          d(x.data);
        } else if constexpr (std::is_same_v<T, Bool>) {
          d(x.data);
        } else {
          static_assert(sizeof(T) == 0, "digest: a message type without its fields here");
        }
      },
      m);
  return d.h;
}

}  // namespace rescuesim::msg
