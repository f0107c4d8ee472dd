#pragma once
/// Noise models shared by the samplers: white Gaussian noise plus a random-walk bias, drawn
/// from the sensor's own Rng stream.

#include <cmath>

#include "core/rng.h"
#include "world/sensor_spec.h"

namespace rescuesim {

/// value + bias + N(0, stddev^2); no draw at all when stddev is zero, so noise-free sensors
/// do not consume random numbers.
inline double add_noise(double value, const NoiseSpec& n, double bias, Rng& rng) {
  return n.stddev > 0 ? value + bias + rng.normal(0.0, n.stddev) : value + bias;
}

/// Advances a random-walk bias over `dt` seconds.
inline double walk_bias(double bias, const NoiseSpec& n, double dt, Rng& rng) {
  return n.bias_walk > 0 ? bias + rng.normal(0.0, n.bias_walk * std::sqrt(dt)) : bias;
}

}  // namespace rescuesim
