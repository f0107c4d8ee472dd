#pragma once
/// Sensor descriptions as data: what each sensor is, where it is mounted, how often it samples
/// and how it is noisy. Samplers live in src/sensors; these are plain settings.

#include <array>
#include <span>
#include <string>

#include "core/pose.h"

namespace rescuesim {

/// Additive noise: white Gaussian noise plus a bias that starts at `bias` and random-walks.
struct NoiseSpec {
  double stddev = 0.0;       ///< white noise standard deviation (sensor units)
  double bias = 0.0;         ///< initial bias
  double bias_walk = 0.0;    ///< bias random walk: standard deviation growth per sqrt(second)
};

/// A planar or multi-layer scanning laser range finder.
struct LidarSpec {
  double min_angle = -M_PI * 3 / 4;  ///< first beam, rad, counter-clockwise from the sensor's x axis
  double max_angle = M_PI * 3 / 4;   ///< last beam
  int samples = 541;                 ///< beams per layer
  int layers = 1;                    ///< 1 = planar
  double vertical_fov = 0.0;         ///< rad between the lowest and highest layer
  double min_range = 0.05;           ///< m
  double max_range = 20.0;           ///< m
  NoiseSpec noise{0.01, 0, 0};       ///< range noise (m)
};

/// An ultrasonic range finder: a cone sampled by rays, reporting the nearest return.
struct SonarSpec {
  double fov = 0.5;                  ///< full cone angle (rad)
  int rays = 5;                      ///< rays across the cone in each direction (rays × rays in all)
  double min_range = 0.03;           ///< m
  double max_range = 4.0;            ///< m
  double max_incidence = 1.05;       ///< rad: steeper than this from the surface normal gives no echo
  NoiseSpec noise{0.01, 0, 0};
};

/// Inertial measurement unit on a link.
struct ImuSpec {
  NoiseSpec gyro{0.002, 0, 0.0005};      ///< rad/s
  NoiseSpec accel{0.02, 0, 0.001};       ///< m/s^2
  NoiseSpec orientation{0.0, 0, 0};      ///< rad (applied to yaw, pitch and roll)
};

/// Wheel odometry: travel integrated from wheel joint velocities, so it drifts with slip.
/// Heading comes from the chassis gyro by default, as on most real skid-steer robots (their
/// wheel-derived turn rate is off by however much the wheels skid); set gyro_heading false for
/// pure wheel odometry.
struct OdometrySpec {
  NoiseSpec wheel_noise{0.0, 0, 0};      ///< relative noise on each wheel speed (fraction)
  bool gyro_heading = true;              ///< heading from the gyro rather than from the wheel speed difference
  NoiseSpec gyro{0.002, 0, 0.0002};      ///< yaw-rate noise of that gyro (rad/s)
};

/// A pinhole camera (colour, depth or thermal); rendered by src/render.
struct CameraSpec {
  int width = 320, height = 240;
  double hfov = 1.2;                 ///< horizontal field of view (rad)
  double near_clip = 0.05, far_clip = 30.0;  ///< m
  double min_range = 0.1, max_range = 10.0;  ///< depth/thermal useful range (m)
  NoiseSpec noise;                   ///< pixel noise: colour in 0..1 units, depth in m (plus the quadratic term), thermal in K (NETD)
  double blur_sigma = 1.5;           ///< thermal: Gaussian blur (px)
  /// colour: Brown distortion k1, k2, p1, p2, k3 (all zero = an ideal pinhole)
  std::array<double, 5> distortion{0, 0, 0, 0, 0};
  double exposure = 1.0;             ///< colour: linear gain before encoding
  /// colour: the gain follows the light, so that the image's mean linear luminance is 0.18 (mid
  /// grey), within [exposure / max_gain, exposure * max_gain]; the pixel noise grows with the
  /// gain above `exposure` (read noise amplified), so dark scenes come out grainy
  bool auto_exposure = false;
  double max_gain = 16.0;
  std::string depth_encoding = "32FC1";  ///< depth: 32FC1 (m) or 16UC1 (mm)
  double depth_noise_quadratic = 0.0;    ///< depth: extra noise sigma = this x z^2 (structured-light sensors, ~0.0012 /m)
  bool point_cloud = true;           ///< depth: also publish a PointCloud2
  double mono8_min = 288.15, mono8_max = 313.15;  ///< thermal: temperature window (K) mapped to 0..255
};

struct SensorKindInfo;
struct SensorExtraTopic;

/// What kind of sensor, and the settings of that kind.
struct SensorSpec {
  enum class Type { lidar, sonar, imu, odometry, ground_truth, joint_states, contact, color_camera, depth_camera, thermal_camera };
  std::string name;          ///< unique per robot, e.g. "scan", "sonar_front"
  Type type = Type::lidar;
  std::string link = "base_link";  ///< mount link
  Pose3 X_LS;                ///< sensor frame in the link frame (x forward, z up; cameras: optical frame derived)
  double rate = 10.0;        ///< Hz
  bool enabled = true;
  std::string topic;         ///< relative topic name, e.g. "scan" (namespaced by robot when needed)
  std::string frame_id;      ///< frame name for messages, e.g. "laser"
  LidarSpec lidar;
  SonarSpec sonar;
  ImuSpec imu;
  OdometrySpec odometry;
  CameraSpec camera;

  /// The facts of this sensor's kind (sensor_kind(type)).
  const SensorKindInfo& kind() const;
  /// True for the rendered kinds (colour, depth, thermal camera).
  bool is_camera() const;
  /// The message type of the main topic: the kind's, except that a lidar with more than one
  /// layer publishes a PointCloud2 instead of a LaserScan.
  const char* ros_type() const;
  /// The output beside the main topic, or nullptr: the kind's extra topic unless its switch
  /// (SensorKindInfo::extra_switch, e.g. a depth camera's point_cloud) is off.
  const SensorExtraTopic* extra_topic() const;
};

/// A topic a sensor publishes beside its main one, named relative to the main topic's folder
/// (main "/camera/depth/image_raw", name "points" → "/camera/depth/points").
struct SensorExtraTopic {
  const char* name;      ///< last path element, e.g. "points"
  const char* ros_type;  ///< message type, e.g. "sensor_msgs/PointCloud2"
};

/// Everything the code needs to know about one kind of sensor besides its settings and its
/// sampler: one row per SensorSpec::Type, so that adding a kind is a row here, a sampler in
/// src/sensors and a case in Simulation::sample.
struct SensorKindInfo {
  SensorSpec::Type type = SensorSpec::Type::lidar;
  const char* name = "";                     ///< as scenario files and `rescuesim check` spell it ("lidar", "thermal_camera")
  const char* ros_type = "";                 ///< message type of the main topic
  const char* layered_ros_type = nullptr;    ///< the main topic's type instead when a lidar has layers > 1 (nullptr: none)
  bool camera = false;                       ///< rendered by the camera service, in an optical frame, with camera_info beside the image
  bool mounted = true;  ///< frame_id names the sensor's mount (X_LS on its link), published on /tf_static; false where it is a world-fixed
                        ///< frame (odometry's "odom", ground truth's "map")
  SensorExtraTopic extra{nullptr, nullptr};  ///< a further output beside the main topic (name nullptr: none)
  bool CameraSpec::*extra_switch = nullptr;  ///< the setting that turns `extra` off when false (depth: point_cloud); nullptr: always on
};

/// The topic every camera publishes beside its image: sensor_msgs/CameraInfo on "camera_info".
inline constexpr SensorExtraTopic kCameraInfoTopic{"camera_info", "sensor_msgs/CameraInfo"};

/// The row of kind `t`.
const SensorKindInfo& sensor_kind(SensorSpec::Type t);
/// Every kind, in SensorSpec::Type order.
std::span<const SensorKindInfo> sensor_kinds();

/// Readable name of a sensor type ("lidar", "sonar", ...): sensor_kind(t).name.
const char* sensor_type_name(SensorSpec::Type t);

}  // namespace rescuesim
