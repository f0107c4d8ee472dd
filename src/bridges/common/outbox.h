#pragma once
/// Outbox: the outbound queues between the publishing thread (a Bus callback) and a bridge's
/// sender thread, one policy for every transport.
///  - One bounded queue per topic, so a burst on one topic (10 000 /clock messages) only ever
///    pushes out older messages of that topic, never an image or /tf_static.
///  - An optional byte budget over all queues; a message that would break it first pushes out
///    older messages of its own topic, and is dropped itself if that is not enough.
///  - Bounded mode drops (the oldest of the topic) and counts; lossless mode (MCAP recording
///    in lockstep) makes push wait for room instead, so nothing is lost and the run stays
///    deterministic.
///  - A sequence number per topic counting every message pushed (dropped or not), for ROS 1's
///    Header.seq and MCAP's sequence.
///  - Topics advertised after the bridge started get a queue on their first message, like the
///    others: a transport that cannot carry them (no writer) just discards what it takes.
/// Messages are shared with the Bus, never copied. Thread-safe.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <vector>

#include "core/sim_time.h"
#include "bus/bus.h"

namespace rescuesim {

/// How an Outbox queues.
struct OutboxOptions {
  std::size_t per_topic = 64;   ///< messages held per topic at most (at least 1)
  std::size_t byte_budget = 0;  ///< bytes held over all topics at most; 0: no budget
  bool lossless = false;        ///< push waits for room instead of dropping
};

/// A message on its way out.
struct OutboxItem {
  TopicId topic = kNoTopic;
  std::uint32_t seq = 0;         ///< 1, 2, ... per topic
  SimTime at;                    ///< the host's time when it was pushed (MCAP log time)
  Bus::SharedMessage message;    ///< shared with the Bus and other bridges
  std::size_t bytes = 0;         ///< what it counts against the byte budget
};

/// What an Outbox dropped, for BridgeStats.
struct OutboxStats {
  std::uint64_t pushed = 0;      ///< messages pushed
  std::uint64_t dropped = 0;     ///< pushed out by a newer one, refused by the byte budget, or pushed after close
  std::size_t queued = 0;        ///< waiting now
  std::size_t queued_bytes = 0;  ///< their bytes
};

class Outbox {
 public:
  explicit Outbox(OutboxOptions options = {});

  /// Publishing thread: queues `message` of `topic` (see the file comment for the policy).
  /// `bytes` is what it counts against the byte budget (approx_bytes). Returns false when a
  /// message was dropped to make room (or this one was). Lossless: waits for room instead.
  bool push(TopicId topic, SimTime at, Bus::SharedMessage message, std::size_t bytes);

  /// Publishing thread: counts a message of `topic` that is not queued (nobody wants it), so
  /// the sequence numbers still count every message the host published. Returns its number.
  std::uint32_t skip(TopicId topic);

  /// Sets one topic's bound (messages, at least 1) instead of OutboxOptions::per_topic (ROS 2
  /// sizes each topic's queue from its rate). Call before its messages arrive.
  void set_capacity(TopicId topic, std::size_t messages);

  /// Sender thread: waits up to `timeout` for a message, then takes at most one per topic,
  /// oldest first, in topic order (so no topic starves another) and appends them to `out`.
  /// Returns false when nothing was taken (timeout, or closed and drained).
  bool take_round(std::vector<OutboxItem>& out, std::chrono::milliseconds timeout);

  /// Wakes the sender and any waiting push; later pushes are dropped (counted); what is queued
  /// can still be taken.
  void close();
  bool closed() const;
  /// Closed and nothing left to take.
  bool drained() const;
  OutboxStats stats() const;
  /// Messages of one topic dropped so far.
  std::uint64_t dropped(TopicId topic) const;

  /// An approximate size of a message for the byte budget: its big arrays plus 256.
  static std::size_t approx_bytes(const msg::Message& m);

 private:
  struct Queue {
    std::deque<OutboxItem> items;
    std::uint32_t seq = 0;
    std::uint64_t dropped = 0;
    std::size_t capacity = 0;  ///< 0: OutboxOptions::per_topic
  };
  Queue& queue_of(TopicId topic);
  bool fits(const Queue& q, std::size_t bytes) const;
  void drop_front(Queue& q);

  OutboxOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;  ///< signalled on push and close
  std::condition_variable room_;   ///< signalled when items leave (lossless push waits on it)
  std::vector<Queue> queues_;      ///< by topic id, grown as topics appear
  OutboxStats stats_;
  bool closed_ = false;
};

}  // namespace rescuesim
