#pragma once
/// Rate limiting for repeated warnings: one bad sender or one broken topic must not flood the
/// log, but the log must still say how much it held back.

#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>

namespace rescuesim {

/// Lets a repeated warning through at most once per `period` (steady clock) and counts what
/// it held back. Thread-safe.
class Throttle {
 public:
  using Clock = std::chrono::steady_clock;
  explicit Throttle(Clock::duration period = std::chrono::seconds(2)) : period_(period) {}

  /// True when the caller should log now; `suppressed` (when given) is set to how many calls
  /// were held back since the last one let through.
  bool allow(std::uint64_t* suppressed = nullptr) { return allow_at(Clock::now(), suppressed); }

  /// As allow, at a given time (for callers with their own clock, and for tests).
  bool allow_at(Clock::time_point now, std::uint64_t* suppressed = nullptr) {
    std::lock_guard lock(mutex_);
    if (last_ && now - *last_ < period_) {
      ++held_;
      return false;
    }
    last_ = now;
    if (suppressed) *suppressed = held_;
    held_ = 0;
    return true;
  }

 private:
  std::mutex mutex_;
  Clock::duration period_;
  std::optional<Clock::time_point> last_;
  std::uint64_t held_ = 0;
};

}  // namespace rescuesim
