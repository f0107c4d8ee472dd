#include "sensors/media_echo.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rescuesim {

void sensor_media(const World& world, SimTime stamp, SensingBand band, std::vector<MediumVolume>& out) {
  out.clear();
  if (world.media.empty()) return;
  media_at(world.media, stamp.seconds(), band, out);
}

float echo_through_media(float distance, const Ray& ray, std::span<const MediumVolume> media, double echo_probability, Rng& rng,
                         std::vector<MediumSegment>& scratch) {
  if (std::isnan(distance) || media.empty()) return distance;
  const bool target = std::isfinite(distance);
  const double length = target ? static_cast<double>(distance) : static_cast<double>(ray.max_distance);
  if (!std::isfinite(length)) return distance;
  const double tau = optical_depth(media, ray.origin, ray.direction, length, scratch);
  if (!(tau > 0)) return distance;

  // the target's echo, out and back through tau each way
  if (rng.uniform() < std::exp(-2.0 * tau)) return distance;

  // lost: the medium may answer from where the pulse was first scattered
  if (echo_probability > 0 && rng.uniform() < echo_probability) {
    const double v = rng.uniform();
    const double depth = std::min(-std::log1p(v * std::expm1(-tau)), tau * (1 - 1e-12));
    const double at = distance_at_depth(scratch, depth);
    if (std::isfinite(at)) return static_cast<float>(at);
  }
  return std::numeric_limits<float>::infinity();
}

}  // namespace rescuesim
