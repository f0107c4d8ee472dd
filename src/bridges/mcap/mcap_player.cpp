#include "bridges/mcap/mcap_player.h"

#include <chrono>
#include <thread>

#include "core/error.h"
#include "core/log.h"
#include "core/throttle.h"

namespace rescuesim {

namespace {

using Clock = std::chrono::steady_clock;

/// ros2 profile: a transient-local channel is a latched topic.
bool latched(const mcap::Channel& c) {
  for (const auto& [k, v] : c.metadata) {
    if (k == "offered_qos_profiles") return v.find("durability: 1") != std::string::npos;
  }
  return false;
}

}  // namespace

McapPlayer::McapPlayer(const std::filesystem::path& path, const RebuildWorld& rebuild) : reader_(path), replayed_(rebuild(reader_)) {
  host_ = std::make_unique<ReplayHost>(replayed_.world, replayed_.seed);
  // every recorded topic is on the Bus before bridges start (they advertise what they see then)
  for (const auto& [id, channel] : reader_.channels()) route(channel);
}

McapPlayer::~McapPlayer() = default;

const McapPlayer::Route& McapPlayer::route(const mcap::Channel& channel) {
  const auto known = routes_.find(channel.id);
  if (known != routes_.end()) return known->second;
  Route r;
  const auto schema = reader_.schemas().find(channel.schema_id);
  if (channel.message_encoding != "cdr" || schema == reader_.schemas().end() || schema->second.encoding != "ros2msg") {
    log::warn("replay: {} is not replayed: its messages are '{}', not CDR with a ros2msg schema", channel.topic, channel.message_encoding);
  } else if (!(r.type = msg::find_type(schema->second.name))) {
    log::warn("replay: {} is not replayed: rescuesim does not know its type {}", channel.topic, schema->second.name);
  } else {
    Bus& bus = host_->bus();
    const TopicId existing = bus.find(channel.topic);
    if (existing != kNoTopic && bus.topic(existing).type != r.type->ros1_name) {
      log::warn("replay: {} is not replayed: recorded as {} but this world has it as {}", channel.topic, r.type->ros1_name,
                bus.topic(existing).type);
    } else {
      r.topic = existing != kNoTopic ? existing : bus.advertise(channel.topic, r.type->ros1_name, 0, latched(channel));
    }
  }
  return routes_.emplace(channel.id, r).first->second;
}

PlayResult McapPlayer::play(double rate, const std::atomic<bool>* stop, const std::function<void(const PlayProgress&)>& progress) {
  RS_DEMAND(rate > 0, "McapPlayer::play: rate must be positive");
  PlayResult result;
  const auto t0 = Clock::now();
  auto last_report = t0;
  std::optional<std::uint64_t> first;
  std::uint64_t now_ns = static_cast<std::uint64_t>(host_->time().ns);
  PlayProgress p;
  if (reader_.statistics()) {
    p.duration = 1e-9 * static_cast<double>(reader_.statistics()->message_end_time - reader_.statistics()->message_start_time);
  }
  Throttle decode_log;
  const auto stopped = [&] { return stop && stop->load(std::memory_order_relaxed); };

  reader_.read_messages([&](const mcap::Channel& channel, const mcap::MessageView& m) {
    if (stopped()) return false;
    const Route& r = route(channel);
    if (r.topic == kNoTopic) {
      ++result.skipped;
      return true;
    }
    msg::Message message;
    try {
      message = msg::from_cdr(*r.type, m.data);
    } catch (const Error& e) {
      ++result.skipped;
      std::uint64_t held = 0;
      if (decode_log.allow(&held)) log::warn("replay: a {} message (sequence {}) does not decode: {}", channel.topic, m.sequence, e.what());
      return true;
    }
    // wait for the wall clock (log times that go backwards are published at once)
    if (!first) first = m.log_time;
    const double due = m.log_time > *first ? 1e-9 * static_cast<double>(m.log_time - *first) / rate : 0.0;
    for (;;) {
      const double late = std::chrono::duration<double>(Clock::now() - t0).count();
      if (late >= due || stopped()) break;
      std::this_thread::sleep_for(std::chrono::duration<double>(std::min(due - late, 0.05)));
    }
    if (stopped()) return false;
    // the host's clock shows the replayed time
    if (m.log_time != now_ns) {
      now_ns = m.log_time;
      host_->set_time(SimTime{static_cast<std::int64_t>(now_ns)});
    }
    host_->bus().publish(r.topic, std::move(message));
    ++result.messages;
    result.duration = 1e-9 * static_cast<double>(m.log_time - std::min(m.log_time, *first));
    if (progress) {
      const auto wall = Clock::now();
      if (wall - last_report > std::chrono::milliseconds(100)) {
        last_report = wall;
        p.log_time = result.duration;
        p.wall_time = std::chrono::duration<double>(wall - t0).count();
        p.messages = result.messages;
        progress(p);
      }
    }
    return true;
  });
  result.interrupted = stopped();
  result.wall_time = std::chrono::duration<double>(Clock::now() - t0).count();
  return result;
}

}  // namespace rescuesim
