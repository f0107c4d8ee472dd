#pragma once
/// Bridges: transports attached to a simulation's Bus (ROS 1, ROS 2, Foxglove, MCAP; in
/// src/bridges/<name>). A bridge subscribes on the simulation thread (Bus::subscribe_shared),
/// queues each message it wants, shared and uncopied, in a bounded queue (cheap; never blocks),
/// and serialises and sends from its own thread.
/// Commands it receives go through Simulation::command_velocity / command_head /
/// command_joints, which queue them for the next step boundary. A slow network or subscriber
/// therefore never slows the simulation: when a queue is full the oldest message is dropped and
/// counted.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

namespace rescuesim {

class Simulation;

/// What a bridge did, for summaries and benches.
struct BridgeStats {
  std::uint64_t sent = 0;         ///< messages handed to the transport
  std::uint64_t dropped = 0;      ///< messages dropped because a queue was full
  std::uint64_t received = 0;     ///< commands received and accepted
  std::uint64_t rejected = 0;     ///< commands refused (malformed, non-finite, wrong size)
};

class Bridge {
 public:
  virtual ~Bridge() = default;
  /// "ros1", "ros2", "foxglove", "mcap".
  virtual std::string name() const = 0;
  /// Subscribes to the simulation's Bus and starts the bridge's thread(s). Call before the
  /// first step (so latched topics such as /tf_static are seen) and from the thread that steps.
  /// Throws rescuesim::Error when the transport cannot start (the message says why).
  virtual void start(Simulation& sim) = 0;
  /// Sends what is queued (up to a short deadline), unsubscribes and joins the threads.
  virtual void stop() = 0;
  virtual BridgeStats stats() const = 0;
};

/// A bounded multi-producer queue; push never blocks: when full, the oldest item is dropped
/// (and counted). pop waits until an item arrives, the timeout passes or the queue is closed.
/// push_wait is the lossless alternative: it waits for room instead (a lockstep recording
/// blocks the simulation thread rather than drop, which keeps the run deterministic).
template <class T>
class BoundedQueue {
 public:
  explicit BoundedQueue(std::size_t capacity) : capacity_(capacity) {}

  /// Returns false when an older item had to be dropped to make room.
  bool push(T item) {
    bool dropped = false;
    {
      std::lock_guard lock(mutex_);
      if (closed_) return true;
      if (items_.size() >= capacity_) {
        items_.pop_front();
        ++dropped_;
        dropped = true;
      }
      items_.push_back(std::move(item));
    }
    ready_.notify_one();
    return !dropped;
  }

  /// Like push, but waits while the queue is full instead of dropping; returns false (and
  /// drops the item) only when the queue is closed.
  bool push_wait(T item) {
    {
      std::unique_lock lock(mutex_);
      room_.wait(lock, [&] { return items_.size() < capacity_ || closed_; });
      if (closed_) return false;
      items_.push_back(std::move(item));
    }
    ready_.notify_one();
    return true;
  }

  /// The oldest item, or nothing after `timeout` or once closed and drained.
  template <class Rep, class Period>
  std::optional<T> pop(std::chrono::duration<Rep, Period> timeout) {
    std::unique_lock lock(mutex_);
    if (!ready_.wait_for(lock, timeout, [&] { return !items_.empty() || closed_; })) return std::nullopt;
    if (items_.empty()) return std::nullopt;
    T item = std::move(items_.front());
    items_.pop_front();
    room_.notify_one();
    return item;
  }

  /// Wakes every waiter; later pushes are ignored, items already queued can still be popped.
  void close() {
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
    }
    ready_.notify_all();
    room_.notify_all();
  }
  bool closed() const {
    std::lock_guard lock(mutex_);
    return closed_;
  }
  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return items_.size();
  }
  std::uint64_t dropped() const {
    std::lock_guard lock(mutex_);
    return dropped_;
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::condition_variable room_;  ///< signalled when an item leaves (push_wait waits on it)
  std::deque<T> items_;
  std::size_t capacity_;
  std::uint64_t dropped_ = 0;
  bool closed_ = false;
};

/// Lets a repeated warning through at most once per `period` and counts what it held back.
class Throttle {
 public:
  explicit Throttle(std::chrono::steady_clock::duration period = std::chrono::seconds(2)) : period_(period) {}
  /// True when the caller should log now; `suppressed` is how many were held back since.
  bool allow(std::uint64_t* suppressed = nullptr) {
    std::lock_guard lock(mutex_);
    const auto now = std::chrono::steady_clock::now();
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
  std::chrono::steady_clock::duration period_;
  std::optional<std::chrono::steady_clock::time_point> last_;
  std::uint64_t held_ = 0;
};

}  // namespace rescuesim
