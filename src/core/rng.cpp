#include "core/rng.h"

#include <cmath>

namespace rescuesim {

Rng::Rng(std::uint64_t seed, std::string_view name) {
  // state and stream both depend on seed and name; the stream selector must be odd
  const std::uint64_t h = fnv1a64(name);
  const std::uint64_t init = splitmix64(seed ^ splitmix64(h));
  inc_ = (splitmix64(h ^ 0x6a09e667f3bcc909ull) << 1u) | 1u;
  state_ = 0;
  next_u32();
  state_ += init;
  next_u32();
}

Rng::Rng(std::uint64_t state, std::uint64_t stream, int) : state_(state), inc_(stream | 1u) {}

std::uint32_t Rng::next_u32() {
  const std::uint64_t old = state_;
  state_ = old * 6364136223846793005ull + inc_;
  const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
  const auto rot = static_cast<std::uint32_t>(old >> 59u);
  return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

std::uint64_t Rng::next_u64() {
  const std::uint64_t hi = next_u32();
  return (hi << 32u) | next_u32();
}

double Rng::uniform() { return static_cast<double>(next_u64() >> 11u) * 0x1.0p-53; }

std::uint32_t Rng::below(std::uint32_t n) {
  // Lemire's nearly divisionless bounded integers
  std::uint64_t m = static_cast<std::uint64_t>(next_u32()) * n;
  auto low = static_cast<std::uint32_t>(m);
  if (low < n) {
    const std::uint32_t threshold = (0u - n) % n;
    while (low < threshold) {
      m = static_cast<std::uint64_t>(next_u32()) * n;
      low = static_cast<std::uint32_t>(m);
    }
  }
  return static_cast<std::uint32_t>(m >> 32u);
}

double Rng::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_normal_;
  }
  // Marsaglia polar method: log and sqrt are the only libm calls, both well specified
  double u, v, s;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double f = std::sqrt(-2.0 * std::log(s) / s);
  spare_normal_ = v * f;
  has_spare_ = true;
  return u * f;
}

}  // namespace rescuesim
