#pragma once
/// Seeded random streams. Every consumer of randomness owns an `Rng` derived from
/// (run seed, stream name), so adding a sensor never shifts another sensor's noise.
/// Generator: PCG32 (XSH-RR); distributions are implemented here, not taken from the
/// standard library, so the same seed gives the same numbers with any compiler or libc++.

#include <cstdint>
#include <string_view>

namespace rescuesim {

/// 64-bit FNV-1a of a string: a stable hash for naming streams (not for security).
constexpr std::uint64_t fnv1a64(std::string_view s) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

/// SplitMix64 finaliser: scrambles a 64-bit value into a well-mixed one.
constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

/// A PCG32 random stream with portable distributions.
class Rng {
 public:
  /// The stream for `name` under run seed `seed`.
  Rng(std::uint64_t seed, std::string_view name);
  /// A stream from raw PCG state and stream selector.
  Rng(std::uint64_t state, std::uint64_t stream, int /*raw*/);

  /// The next 32 random bits.
  std::uint32_t next_u32();
  /// The next 64 random bits (two draws).
  std::uint64_t next_u64();
  /// Uniform in [0, 1) with 53 random bits.
  double uniform();
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [0, n), unbiased (Lemire's method); n must be > 0.
  std::uint32_t below(std::uint32_t n);
  /// Uniform integer in [lo, hi] inclusive.
  int range(int lo, int hi) { return lo + static_cast<int>(below(static_cast<std::uint32_t>(hi - lo + 1))); }
  /// Standard normal N(0, 1) (Marsaglia's polar method; uses only log and sqrt).
  double normal();
  /// Normal with mean and standard deviation.
  double normal(double mean, double stddev) { return mean + stddev * normal(); }
  /// True with probability p.
  bool bernoulli(double p) { return uniform() < p; }

  /// Generator state, for hashing and snapshots.
  std::uint64_t state() const { return state_; }
  std::uint64_t stream() const { return inc_; }
  bool operator==(const Rng&) const = default;

 private:
  std::uint64_t state_ = 0;
  std::uint64_t inc_ = 1;
  double spare_normal_ = 0;
  bool has_spare_ = false;
};

}  // namespace rescuesim
