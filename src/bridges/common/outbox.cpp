#include "bridges/common/outbox.h"

#include <variant>

namespace rescuesim {

Outbox::Outbox(OutboxOptions options) : options_(options) {
  if (options_.per_topic == 0) options_.per_topic = 1;
}

std::size_t Outbox::approx_bytes(const msg::Message& m) {
  return std::visit(
      [](const auto& x) -> std::size_t {
        if constexpr (requires { x.data.size(); }) {
          return 256 + x.data.size() * sizeof(x.data[0]);
        } else if constexpr (requires { x.ranges.size(); }) {
          return 256 + 4 * (x.ranges.size() + x.intensities.size());
        } else {
          return 256;
        }
      },
      m);
}

Outbox::Queue& Outbox::queue_of(TopicId topic) {
  const auto t = static_cast<std::size_t>(topic);
  if (t >= queues_.size()) queues_.resize(t + 1);
  return queues_[t];
}

bool Outbox::fits(const Queue& q, std::size_t bytes) const {
  if (q.items.size() >= (q.capacity > 0 ? q.capacity : options_.per_topic)) return false;
  return options_.byte_budget == 0 || stats_.queued_bytes + bytes <= options_.byte_budget;
}

void Outbox::drop_front(Queue& q) {
  stats_.queued_bytes -= q.items.front().bytes;
  --stats_.queued;
  q.items.pop_front();
  ++q.dropped;
  ++stats_.dropped;
}

bool Outbox::push(TopicId topic, SimTime at, Bus::SharedMessage message, std::size_t bytes) {
  bool kept_all = true;
  {
    std::unique_lock lock(mutex_);
    Queue& q = queue_of(topic);
    ++stats_.pushed;
    const std::uint32_t seq = ++q.seq;
    if (options_.lossless) {
      // wait for room (a message larger than the whole budget goes in alone, once all else left)
      room_.wait(lock, [&] { return closed_ || fits(q, bytes) || stats_.queued == 0; });
    } else {
      // make room by pushing out older messages of this topic only
      while (!q.items.empty() && !fits(q, bytes)) {
        drop_front(q);
        kept_all = false;
      }
    }
    const bool room = options_.lossless ? stats_.queued == 0 || fits(q, bytes) : fits(q, bytes);
    if (closed_ || !room) {
      // closed, or (bounded) the other topics' messages fill the byte budget: this one is dropped
      ++q.dropped;
      ++stats_.dropped;
      return false;
    }
    q.items.push_back({topic, seq, at, std::move(message), bytes});
    ++stats_.queued;
    stats_.queued_bytes += bytes;
  }
  ready_.notify_one();
  return kept_all;
}

std::uint32_t Outbox::skip(TopicId topic) {
  std::lock_guard lock(mutex_);
  return ++queue_of(topic).seq;
}

void Outbox::set_capacity(TopicId topic, std::size_t messages) {
  std::lock_guard lock(mutex_);
  queue_of(topic).capacity = messages > 0 ? messages : 1;
}

bool Outbox::take_round(std::vector<OutboxItem>& out, std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  if (!ready_.wait_for(lock, timeout, [&] { return stats_.queued > 0 || closed_; })) return false;
  const std::size_t before = out.size();
  for (Queue& q : queues_) {
    if (q.items.empty()) continue;
    stats_.queued_bytes -= q.items.front().bytes;
    --stats_.queued;
    out.push_back(std::move(q.items.front()));
    q.items.pop_front();
  }
  if (out.size() > before) room_.notify_all();
  return out.size() > before;
}

void Outbox::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  ready_.notify_all();
  room_.notify_all();
}

bool Outbox::closed() const {
  std::lock_guard lock(mutex_);
  return closed_;
}

bool Outbox::drained() const {
  std::lock_guard lock(mutex_);
  return closed_ && stats_.queued == 0;
}

OutboxStats Outbox::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

std::uint64_t Outbox::dropped(TopicId topic) const {
  std::lock_guard lock(mutex_);
  const auto t = static_cast<std::size_t>(topic);
  return t < queues_.size() ? queues_[t].dropped : 0;
}

}  // namespace rescuesim
