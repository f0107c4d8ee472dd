#include "bridges/mcap/mcap_bridge.h"

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <thread>

#include "bridges/common/shared_cdr.h"
#include "core/bounded_queue.h"
#include "core/error.h"
#include "core/log.h"
#include "core/thread.h"
#include "core/throttle.h"
#include "msgs/serialize.h"
#include "bus/bridge_host.h"

namespace rescuesim {

namespace {

using Clock = std::chrono::steady_clock;

/// One message on its way from the simulation thread to the recorder thread.
struct Item {
  std::shared_ptr<const Topic> topic;  // shared: every item of a topic carries what a new channel needs
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;
  Bus::SharedMessage message;  // shared with the Bus and other bridges, never copied
};

}  // namespace

std::string offered_qos_profiles(bool latched) {
  // rmw enums: history 1 keep-last; reliability 1 reliable; durability 1 transient-local,
  // 2 volatile; liveliness 1 automatic; durations at their "infinite" default
  const char* forever = "\n    sec: 2147483647\n    nsec: 4294967295";
  return std::string("- history: 1\n  depth: ") + (latched ? "1" : "10") + "\n  reliability: 1\n  durability: " + (latched ? "1" : "2") +
         "\n  deadline:" + forever + "\n  lifespan:" + forever + "\n  liveliness: 1\n  liveliness_lease_duration:" + forever +
         "\n  avoid_ros_namespace_conventions: false";
}

struct McapRecorder::Impl {
  explicit Impl(McapOptions o) : options(std::move(o)), queue(options.queue_size) {}

  McapOptions options;
  BridgeHost* host = nullptr;
  SubscriptionId handle = kNoSubscription;
  std::unique_ptr<mcap::McapWriter> writer;
  BoundedQueue<Item> queue;
  std::thread thread;
  bool stopped = false;

  // simulation thread
  std::vector<std::shared_ptr<const Topic>> topics;
  std::vector<std::uint32_t> sequences;
  Throttle drop_log;

  // whoever owns the writer (start(), then the recorder thread, then stop())
  std::vector<int> channel_of_topic;  // topic id -> channel id; 0 not yet, -1 type without a ros2 schema
  std::map<std::string, std::uint16_t> schema_of_type;
  std::vector<std::uint8_t> cdr;
  bool failed = false;

  // shared, under stats_mutex
  mutable std::mutex stats_mutex;
  McapRecordingStats stats;

  /// The channel of a topic, declared on first use (0 when its type has no CDR form).
  std::uint16_t channel_for(const Topic& t) {
    const auto id = static_cast<std::size_t>(t.id);
    if (id >= channel_of_topic.size()) channel_of_topic.resize(id + 1, 0);
    int& ch = channel_of_topic[id];
    if (ch != 0) return ch > 0 ? static_cast<std::uint16_t>(ch) : 0;
    const msg::TypeSupport* type = msg::find_type(t.type);
    if (!type) {
      log::warn("mcap: {} ({}) is not recorded: no ROS 2 form for that type", t.name, t.type);
      ch = -1;
      return 0;
    }
    auto schema = schema_of_type.find(type->ros2_name);
    if (schema == schema_of_type.end()) {
      schema = schema_of_type.emplace(type->ros2_name, writer->add_schema(type->ros2_name, "ros2msg", type->ros2_definition)).first;
    }
    ch = writer->add_channel(schema->second, t.name, "cdr", {{"offered_qos_profiles", offered_qos_profiles(t.latched)}});
    return static_cast<std::uint16_t>(ch);
  }

  /// Simulation thread: queues the (shared) message with its log time and sequence.
  void on_message(const Topic& t, const Bus::SharedMessage& m) {
    const auto id = static_cast<std::size_t>(t.id);
    if (id >= topics.size()) {
      topics.resize(id + 1);
      sequences.resize(id + 1, 0);
    }
    if (!topics[id]) topics[id] = std::make_shared<const Topic>(t);
    Item item{topics[id], ++sequences[id], static_cast<std::uint64_t>(host->time().ns), m};
    if (options.lossless) {
      queue.push_wait(std::move(item));
    } else if (!queue.push(std::move(item))) {
      std::uint64_t held = 0;
      if (drop_log.allow(&held)) {
        log::warn("mcap: the recorder falls behind; dropping the oldest queued messages ({} dropped so far)", queue.dropped());
      }
    }
  }

  /// Recorder thread: serialise, write (compressing full chunks), until closed and drained.
  void run() {
    for (;;) {
      // poll rather than wait: a waiting consumer makes every push a wake-up (a system call and
      // a context switch per message, tens of thousands a second in lockstep); looking every
      // millisecond takes the messages in batches instead (size() never waits, pop(0) may)
      if (queue.size() == 0) {
        if (queue.closed()) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        continue;
      }
      std::optional<Item> item = queue.pop(std::chrono::milliseconds(0));
      if (!item) continue;
      const auto t0 = Clock::now();
      if (failed) {
        std::lock_guard lock(stats_mutex);
        ++stats.dropped;
        continue;
      }
      try {
        if (const std::uint16_t ch = channel_for(*item->topic)) {
          const std::int64_t stamp = msg::stamp_of(*item->message).ns;
          const std::uint64_t publish = stamp > 0 ? static_cast<std::uint64_t>(stamp) : item->log_time;
          if (cdr_is_shared(*item->message)) {
            // a large message's bytes are shared with the other CDR bridges (bridges/common/shared_cdr.h)
            writer->write_message(ch, item->sequence, item->log_time, publish, *shared_cdr(item->message));
          } else {
            cdr.clear();
            msg::to_cdr(*item->message, cdr);
            writer->write_message(ch, item->sequence, item->log_time, publish, cdr);
          }
        }
      } catch (const std::exception& e) {
        // a full disk or an unwritable file: stop writing, keep draining so the simulation never waits
        failed = true;
        log::error("mcap: recording to {} stopped: {}", options.path.string(), e.what());
        std::lock_guard lock(stats_mutex);
        stats.error = e.what();
        ++stats.dropped;
      }
      std::lock_guard lock(stats_mutex);
      stats.writer = writer->stats();
      stats.busy_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    }
  }
};

McapRecorder::McapRecorder(McapOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {}

McapRecorder::~McapRecorder() {
  try {
    stop();
  } catch (const std::exception& e) {
    log::error("mcap: {}", e.what());
  }
}

void McapRecorder::start(BridgeHost& host) {
  Impl& m = *impl_;
  RS_DEMAND(!m.host, "McapRecorder::start: started twice");
  mcap::WriterOptions wo;
  wo.profile = "ros2";
  wo.library = m.options.library;
  wo.compression = m.options.compression;
  wo.compression_level = m.options.compression_level;
  wo.chunk_size = m.options.chunk_size;
  wo.chunk_log_seconds = m.options.chunk_seconds;
  wo.chunk_wall_seconds = m.options.lossless ? 0 : m.options.chunk_wall_seconds;
  m.writer = std::make_unique<mcap::McapWriter>(std::make_unique<mcap::FileSink>(m.options.path), wo);
  // the run's description first, then a channel per topic known now (in topic order, so two
  // runs of one scenario number their channels alike); later topics get theirs on first use
  for (const auto& md : m.options.metadata) m.writer->write_metadata(md);
  for (const auto& a : m.options.attachments) m.writer->write_attachment(a);
  for (const Topic& t : host.bus().topics()) m.channel_for(t);
  m.host = &host;
  m.thread = start_named_thread("mcap-write", [&m] { m.run(); });
  m.handle = host.bus().subscribe_shared("", [&m](const Topic& t, const Bus::SharedMessage& msg) { m.on_message(t, msg); });
}

void McapRecorder::stop() {
  Impl& m = *impl_;
  if (!m.host || m.stopped) return;
  m.stopped = true;
  m.host->bus().unsubscribe(m.handle);
  m.queue.close();
  if (m.thread.joinable()) m.thread.join();
  const auto t0 = Clock::now();
  try {
    if (!m.failed) {
      // how the recording went, beside the messages (deterministic in lockstep: nothing dropped)
      const std::uint64_t dropped = m.queue.dropped() + m.stats.dropped;
      m.writer->write_metadata({"rescuesim.recording",
                                {{"messages", std::to_string(m.writer->stats().messages)}, {"dropped", std::to_string(dropped)},
                                 {"mode", m.options.lossless ? "lossless" : "bounded (drop oldest)"}}});
      m.writer->close();
    }
  } catch (const std::exception& e) {
    log::error("mcap: finishing {} failed: {}", m.options.path.string(), e.what());
    std::lock_guard lock(m.stats_mutex);
    if (m.stats.error.empty()) m.stats.error = e.what();
  }
  std::lock_guard lock(m.stats_mutex);
  m.stats.writer = m.writer->stats();
  m.stats.busy_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
}

BridgeStats McapRecorder::stats() const {
  const McapRecordingStats r = recording();
  BridgeStats s;
  s.sent = r.writer.messages;
  s.dropped = r.dropped;
  return s;
}

McapRecordingStats McapRecorder::recording() const {
  std::lock_guard lock(impl_->stats_mutex);
  McapRecordingStats r = impl_->stats;
  r.dropped += impl_->queue.dropped();
  return r;
}

std::unique_ptr<Bridge> make_mcap_recorder(const McapOptions& options) { return std::make_unique<McapRecorder>(options); }

}  // namespace rescuesim
