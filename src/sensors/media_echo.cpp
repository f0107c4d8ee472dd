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

  // one uniform draw decides it all: below exp(-2 tau) the target's echo survives, out and back;
  // above, its excess over that, rescaled to [0, 1), decides below echo_probability that the
  // medium answers, and its excess over that, rescaled again, places the answer
  const double u = rng.uniform();
  const double survive = std::exp(-2.0 * tau);
  if (u < survive) return distance;
  const double answer = echo_probability * (1.0 - survive);
  if (u - survive < answer) {
    // the first scattering's optical depth, Exp(1) conditioned below tau (inverse transform):
    // -ln(1 - v (1 - exp(-tau))), exp(-tau) being the square root of exp(-2 tau)
    const double v = (u - survive) / answer;
    const double depth = std::min(-std::log1p(v * (std::sqrt(survive) - 1.0)), tau * (1 - 1e-12));
    const double at = distance_at_depth(scratch, depth);
    if (std::isfinite(at)) return static_cast<float>(at);
  }
  return std::numeric_limits<float>::infinity();
}

}  // namespace rescuesim
