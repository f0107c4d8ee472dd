#include "sensors/lidar.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "sensors/media_echo.h"
#include "sensors/noise.h"

namespace rescuesim {

namespace {

// point clouds are written in the machine's byte order and declared little-endian
static_assert(std::endian::native == std::endian::little, "PointCloud2 data is written as little-endian floats");

/// Rays and hits of the calling thread, reused from call to call.
struct Buffers {
  std::vector<Ray> rays;
  std::vector<RayHit> hits;
  std::vector<MediumVolume> media;
  std::vector<MediumSegment> segments;
  void resize(std::size_t n) {
    rays.resize(n);
    hits.resize(n);
  }
};

Buffers& thread_buffers() {
  thread_local Buffers b;
  return b;
}

/// Beam angles of one ring (rad): first at min_angle, counter-clockwise.
double beam_angle(const LidarSpec& l, int i) {
  const double inc = l.samples > 1 ? (l.max_angle - l.min_angle) / (l.samples - 1) : 0.0;
  return l.min_angle + i * inc;
}

/// Unit direction of beam i at elevation e, in the sensor frame.
Vec3 beam_direction(const LidarSpec& l, int i, double e) {
  const double a = beam_angle(l, i);
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

/// Sensor-frame beam directions, ring by ring: computed once per layout and kept per thread
/// (a pure function of the layout, so the cache never changes an answer, only saves the trig).
const std::vector<Vec3>& beam_directions(const LidarSpec& l, std::span<const double> elevations) {
  struct Layout {
    double min_angle = NAN, max_angle = NAN;
    int samples = -1;
    std::vector<double> elevations;
    std::vector<Vec3> directions;
  };
  thread_local Layout c;
  const bool same = c.min_angle == l.min_angle && c.max_angle == l.max_angle && c.samples == l.samples &&
                    std::equal(c.elevations.begin(), c.elevations.end(), elevations.begin(), elevations.end());
  if (!same) {
    c.min_angle = l.min_angle;
    c.max_angle = l.max_angle;
    c.samples = l.samples;
    c.elevations.assign(elevations.begin(), elevations.end());
    c.directions.clear();
    for (double e : elevations) {
      for (int i = 0; i < l.samples; ++i) c.directions.push_back(beam_direction(l, i, e));
    }
  }
  return c.directions;
}

/// Fills rays ring by ring, one ring per elevation, from the sensor pose X_WS.
void lidar_rays(const Pose3& X_WS, const LidarSpec& l, std::span<const double> elevations, std::vector<Ray>& rays) {
  const Eigen::Matrix3d R_WS = X_WS.q.toRotationMatrix();
  const std::vector<Vec3>& d_S = beam_directions(l, elevations);
  for (std::size_t k = 0; k < d_S.size(); ++k) rays[k] = Ray{X_WS.p, R_WS * d_S[k], static_cast<float>(l.max_range)};
}

/// Elevations of the layers (rad), evenly over vertical_fov and centred on 0.
std::vector<double> layer_elevations(const LidarSpec& l) {
  const int layers = std::max(1, l.layers);
  std::vector<double> e(static_cast<std::size_t>(layers), 0.0);
  for (int k = 0; layers > 1 && k < layers; ++k) e[static_cast<std::size_t>(k)] = (k - 0.5 * (layers - 1)) * l.vertical_fov / (layers - 1);
  return e;
}

/// Smoke and dust on the first n rays (media_echo.h), in ray order from the lidar's stream; no
/// work at all in a world without media.
void lidar_through_media(const World& world, SimTime stamp, Buffers& b, std::size_t n, Rng& rng) {
  if (world.media.empty()) return;
  sensor_media(world, stamp, SensingBand::near_infrared, b.media);
  if (b.media.empty()) return;
  const double echo = medium_echo_probability(SensingBand::near_infrared);
  for (std::size_t i = 0; i < n; ++i) {
    b.hits[i].distance = echo_through_media(b.hits[i].distance, b.rays[i], b.media, echo, rng, b.segments);
  }
}

void check_robot(const World& world, const State& state, RobotIndex robot, const char* who) {
  RS_DEMAND(world.has_robot(robot) && robot.slot() < state.robots.size(), who);
}

}  // namespace

Pose3 sensor_pose_in_world(const World& world, const State& state, RobotIndex robot, const SensorSpec& spec) {
  check_robot(world, state, robot, "sensor_pose_in_world: robot index outside World::robots or State::robots");
  const auto r = robot.slot();
  const int link = world.robots[r].spec.link_index(spec.link);
  if (link < 0) {
    throw Error(SourceRef{"", 0, std::string("robot '") + world.robots[r].name + "' sensor '" + spec.name + "'"},
                std::string("rescuesim::sensor_pose_in_world: mount link '") + spec.link + "' is not a link of the robot");
  }
  RS_DEMAND(static_cast<std::size_t>(link) < state.robots[r].X_WL.size(), "sensor_pose_in_world: RobotState::X_WL is missing links");
  return state.robots[r].X_WL[static_cast<std::size_t>(link)] * spec.X_LS;
}

float range_reading(float distance, double min_range, double max_range, const NoiseSpec& noise, Rng& rng) {
  if (std::isnan(distance)) return NAN;
  if (std::isinf(distance)) return INFINITY;
  if (distance < min_range) return -INFINITY;
  const double noisy = add_noise(distance, noise, noise.bias, rng);
  return static_cast<float>(std::clamp(noisy, min_range, max_range));
}

msg::LaserScan sample_lidar(const World& world, const State& state, const RayScene& scene, RobotIndex robot, const SensorSpec& spec,
                            SimTime stamp, Rng& rng) {
  const LidarSpec& l = spec.lidar;
  const Pose3 X_WS = sensor_pose_in_world(world, state, robot, spec);
  const auto n = static_cast<std::size_t>(std::max(0, l.samples));

  // one ring at elevation 0, cast as one batch that cannot see the robot itself
  Buffers& b = thread_buffers();
  b.resize(n);
  static constexpr double kPlane[1] = {0.0};
  lidar_rays(X_WS, l, kPlane, b.rays);
  scene.cast(std::span<const Ray>(b.rays.data(), n), std::span<RayHit>(b.hits.data(), n), robot);
  lidar_through_media(world, stamp, b, n, rng);

  msg::LaserScan scan;
  scan.header.stamp = stamp;
  scan.header.frame_id = spec.frame_id;
  scan.angle_min = static_cast<float>(l.min_angle);
  scan.angle_max = static_cast<float>(l.max_angle);
  scan.angle_increment = static_cast<float>(l.samples > 1 ? (l.max_angle - l.min_angle) / (l.samples - 1) : 0.0);
  scan.time_increment = 0.0f;
  scan.scan_time = static_cast<float>(spec.rate > 0 ? 1.0 / spec.rate : 0.0);
  scan.range_min = static_cast<float>(l.min_range);
  scan.range_max = static_cast<float>(l.max_range);

  // readings per REP-117, noise drawn beam by beam in order
  scan.ranges.resize(n);
  for (std::size_t i = 0; i < n; ++i) scan.ranges[i] = range_reading(b.hits[i].distance, l.min_range, l.max_range, l.noise, rng);
  return scan;
}

msg::PointCloud2 sample_lidar_cloud(const World& world, const State& state, const RayScene& scene, RobotIndex robot, const SensorSpec& spec,
                                    SimTime stamp, Rng& rng) {
  const LidarSpec& l = spec.lidar;
  const Pose3 X_WS = sensor_pose_in_world(world, state, robot, spec);
  const std::vector<double> elevations = layer_elevations(l);
  const std::size_t per_ring = static_cast<std::size_t>(std::max(0, l.samples));
  const std::size_t n = per_ring * elevations.size();

  // every ring in one batch
  Buffers& b = thread_buffers();
  b.resize(n);
  lidar_rays(X_WS, l, elevations, b.rays);
  scene.cast(std::span<const Ray>(b.rays.data(), n), std::span<RayHit>(b.hits.data(), n), robot);
  lidar_through_media(world, stamp, b, n, rng);

  msg::PointCloud2 cloud;
  cloud.header.stamp = stamp;
  cloud.header.frame_id = spec.frame_id;
  cloud.height = 1;
  cloud.fields = {{"x", 0, msg::PointField::kFloat32, 1}, {"y", 4, msg::PointField::kFloat32, 1}, {"z", 8, msg::PointField::kFloat32, 1}};
  cloud.is_bigendian = false;
  cloud.point_step = 12;
  cloud.is_dense = true;

  // a point along each beam's sensor-frame direction at its noisy range, for real returns only
  const std::vector<Vec3>& d_S = beam_directions(l, elevations);
  cloud.data.reserve(n * 12);
  std::uint32_t points = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const float r = range_reading(b.hits[k].distance, l.min_range, l.max_range, l.noise, rng);
    if (!std::isfinite(r)) continue;
    const Vec3 p_S = d_S[k] * static_cast<double>(r);
    const float xyz[3] = {static_cast<float>(p_S.x()), static_cast<float>(p_S.y()), static_cast<float>(p_S.z())};
    const std::size_t at = cloud.data.size();
    cloud.data.resize(at + sizeof xyz);
    std::memcpy(cloud.data.data() + at, xyz, sizeof xyz);
    ++points;
  }
  cloud.width = points;
  cloud.row_step = cloud.point_step * points;
  return cloud;
}

}  // namespace rescuesim
