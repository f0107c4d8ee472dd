#pragma once
/// Simulation time: an integer count of nanoseconds, so sums of fixed steps are exact.

#include <cmath>
#include <compare>
#include <cstdint>

namespace rescuesim {

/// A point or span on the simulation clock, in integer nanoseconds since the start of a run.
struct SimTime {
  std::int64_t ns = 0;  ///< nanoseconds

  /// The time nearest to `s` seconds (rounded to the nearest nanosecond).
  static constexpr SimTime from_seconds(double s) {
    return SimTime{static_cast<std::int64_t>(s >= 0 ? s * 1e9 + 0.5 : s * 1e9 - 0.5)};
  }
  static constexpr SimTime from_ms(std::int64_t ms) { return SimTime{ms * 1'000'000}; }
  static constexpr SimTime from_us(std::int64_t us) { return SimTime{us * 1'000}; }

  /// Seconds as a double (exact below 2^53 ns, about 104 days).
  constexpr double seconds() const { return static_cast<double>(ns) * 1e-9; }
  /// Whole seconds and remaining nanoseconds, as ROS time stamps carry them.
  constexpr std::int64_t sec_part() const { return ns >= 0 ? ns / 1'000'000'000 : -((-ns + 999'999'999) / 1'000'000'000); }
  constexpr std::uint32_t nsec_part() const { return static_cast<std::uint32_t>(ns - sec_part() * 1'000'000'000); }

  constexpr auto operator<=>(const SimTime&) const = default;
  constexpr SimTime operator+(SimTime o) const { return {ns + o.ns}; }
  constexpr SimTime operator-(SimTime o) const { return {ns - o.ns}; }
  constexpr SimTime& operator+=(SimTime o) { ns += o.ns; return *this; }
  constexpr SimTime& operator-=(SimTime o) { ns -= o.ns; return *this; }
  constexpr SimTime operator*(std::int64_t k) const { return {ns * k}; }
};

}  // namespace rescuesim
