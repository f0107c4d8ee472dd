#pragma once
/// A bounded multi-producer, multi-consumer queue between threads, with two ways to add:
/// push never blocks (when full the oldest item is dropped and counted: a bridge must never
/// slow the simulation), push_wait waits for room instead (lossless: a lockstep recording
/// blocks the simulation thread rather than drop, which keeps the run deterministic).

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <utility>

namespace rescuesim {

/// See the file comment. pop waits until an item arrives, the timeout passes or the queue is
/// closed; close wakes every waiter.
template <class T>
class BoundedQueue {
 public:
  /// `capacity`: items held at most (at least 1).
  explicit BoundedQueue(std::size_t capacity) : capacity_(capacity > 0 ? capacity : 1) {}

  /// Adds `item`; when the queue is full the oldest item is dropped first (and counted).
  /// Returns false when an item had to be dropped to make room. After close(), does nothing.
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
  /// discards the item) only when the queue is closed.
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
    return take(lock);
  }

  /// The oldest item, or nothing when the queue is empty (never waits).
  std::optional<T> try_pop() {
    std::unique_lock lock(mutex_);
    return take(lock);
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
  /// Items waiting.
  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return items_.size();
  }
  std::size_t capacity() const { return capacity_; }
  /// Items push dropped to make room, so far.
  std::uint64_t dropped() const {
    std::lock_guard lock(mutex_);
    return dropped_;
  }

 private:
  std::optional<T> take(std::unique_lock<std::mutex>&) {
    if (items_.empty()) return std::nullopt;
    T item = std::move(items_.front());
    items_.pop_front();
    room_.notify_one();
    return item;
  }

  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::condition_variable room_;  ///< signalled when an item leaves (push_wait waits on it)
  std::deque<T> items_;
  std::size_t capacity_;
  std::uint64_t dropped_ = 0;
  bool closed_ = false;
};

}  // namespace rescuesim
