#include "sensors/sonar.h"

#include <algorithm>
#include <cmath>

#include "sensors/lidar.h"
#include "sensors/media_echo.h"

namespace rescuesim {

void sonar_directions(const SonarSpec& sonar, std::vector<Vec3>& out) {
  out.clear();
  const int n = std::max(1, sonar.rays);
  const double half = 0.5 * sonar.fov;
  const double step = n > 1 ? sonar.fov / (n - 1) : 0.0;
  // a square grid of (yaw, pitch); the middle index of an odd grid is exactly 0
  bool has_axis = false;
  for (int iy = 0; iy < n; ++iy) {
    const double yaw = (iy - 0.5 * (n - 1)) * step;
    for (int ip = 0; ip < n; ++ip) {
      const double pitch = (ip - 0.5 * (n - 1)) * step;
      const Vec3 d(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch));
      // keep the directions inside the cone (a hair of slack for the rim)
      if (std::acos(std::clamp(d.x(), -1.0, 1.0)) > half + 1e-12) continue;
      has_axis = has_axis || (yaw == 0.0 && pitch == 0.0);
      out.push_back(d);
    }
  }
  if (!has_axis) out.push_back(Vec3::UnitX());
}

msg::Range sample_sonar(const World& world, const State& state, const RayScene& scene, RobotIndex robot, const SensorSpec& spec,
                        SimTime stamp, Rng& rng) {
  const SonarSpec& s = spec.sonar;
  const Pose3 X_WS = sensor_pose_in_world(world, state, robot, spec);

  // the cone's rays in the world, cast as one batch that cannot hear the robot itself
  thread_local std::vector<Vec3> directions;
  thread_local std::vector<Ray> rays;
  thread_local std::vector<RayHit> hits;
  sonar_directions(s, directions);
  rays.resize(directions.size());
  hits.resize(directions.size());
  const Eigen::Matrix3d R_WS = X_WS.q.toRotationMatrix();
  for (std::size_t i = 0; i < directions.size(); ++i) rays[i] = Ray{X_WS.p, R_WS * directions[i], static_cast<float>(s.max_range)};
  scene.cast(rays, hits, robot);

  // smoke and dust, ray by ray from the sonar's stream (none in a world without media): a ray
  // whose echo the medium absorbs hears nothing; an echo from the medium itself comes head-on
  thread_local std::vector<MediumVolume> media;
  thread_local std::vector<MediumSegment> segments;
  sensor_media(world, stamp, SensingBand::ultrasound, media);
  float medium_echo = INFINITY;
  if (!media.empty()) {
    const double p_echo = medium_echo_probability(SensingBand::ultrasound);
    for (std::size_t i = 0; i < hits.size(); ++i) {
      const float d = echo_through_media(hits[i].distance, rays[i], media, p_echo, rng, segments);
      if (d == hits[i].distance || std::isnan(d)) continue;
      hits[i].source = RayHit::Source::none;
      hits[i].distance = INFINITY;
      medium_echo = std::min(medium_echo, d);
    }
  }

  // nearest echo among the returns met steeply enough (specular loss at grazing incidence)
  float nearest = INFINITY;
  for (std::size_t i = 0; i < hits.size(); ++i) {
    const RayHit& h = hits[i];
    if (std::isnan(h.distance)) {
      nearest = NAN;
      break;
    }
    if (!h.hit()) continue;
    const double incidence = std::acos(std::clamp(-h.normal.dot(rays[i].direction), -1.0, 1.0));
    if (incidence <= s.max_incidence) nearest = std::min(nearest, h.distance);
  }
  if (!std::isnan(nearest)) nearest = std::min(nearest, medium_echo);

  msg::Range range;
  range.header.stamp = stamp;
  range.header.frame_id = spec.frame_id;
  range.radiation_type = msg::Range::kUltrasound;
  range.field_of_view = static_cast<float>(s.fov);
  range.min_range = static_cast<float>(s.min_range);
  range.max_range = static_cast<float>(s.max_range);
  range.range = range_reading(nearest, s.min_range, s.max_range, s.noise, rng);
  return range;
}

}  // namespace rescuesim
