// The Foxglove bridge's data path: start and stop, what the simulation thread queues (the shared
// Bus messages clients subscribed to, in the Outbox; the newest scene snapshot), and the
// serialiser thread that encodes each message once and queues it for every subscriber (see
// bridge_impl.h for the threads and their locks).

#include "bridges/foxglove/foxglove_bridge.h"

#include <cmath>
#include <cstdio>
#include <variant>

#include "bridges/common/outbox.h"
#include "bridges/common/shared_cdr.h"
#include "bridges/foxglove/bridge_impl.h"
#include "core/error.h"
#include "core/log.h"
#include "core/thread.h"
#include "msgs/serialize.h"
#include "bus/bridge_host.h"

namespace rescuesim {

namespace foxglove {

namespace {

std::string mib(std::size_t bytes) {
  char s[32];
  std::snprintf(s, sizeof s, "%.1f MiB", static_cast<double>(bytes) / (1 << 20));
  return s;
}

}  // namespace

void FoxgloveBridge::start(BridgeHost& host) {
  if (started_) return;
  host_ = &host;
  control_ = host.control();
  gate_ = std::make_unique<CommandGate>(host, "foxglove");
  const World& world = host.world();
  const Bus& bus = host.bus();
  clock_topic_ = bus.find("/clock");

  // every Bus topic becomes a cdr channel with its ROS 2 schema
  for (const Topic& t : bus.topics()) add_topic(t, nullptr);
  known_topics_ = bus.topics().size();

  // the scene, drawn where the 3D panel can place it: in "map" when the simulation publishes
  // map -> odom, else in the first robot's odom frame at the robot's start pose
  if (!options_.scene_topic.empty() && bus.find(options_.scene_topic) == kNoTopic) {
    SceneFrames frames;
    if (!host.frames().publish_map_to_odom && !world.robots.empty()) {
      frames.world_frame = host.frame_name(RobotIndex(0), "odom");
      frames.X_FW = host.frames().tf_from_ground_truth ? Pose3{} : world.robots[0].X_W_start.inverse();
    }
    for (std::size_t r = 0; r < world.robots.size(); ++r) {
      std::vector<std::string> links;
      for (const LinkSpec& l : world.robots[r].spec.links) links.push_back(host.frame_name(RobotIndex::at(r), l.name));
      frames.link_frames.push_back(std::move(links));
    }
    scene_ = std::make_unique<SceneBuilder>(world, frames);
    ChannelState scene;
    scene.channel = {kSceneChannel, options_.scene_topic, "json", "foxglove.SceneUpdate", scene_update_schema(), "jsonschema"};
    scene.latched = true;
    last_scene_ = scene_state();
    const std::string full = scene_->full(host.time(), last_scene_);
    scene.last = std::make_shared<const std::vector<std::uint8_t>>(full.begin(), full.end());
    scene.last_stamp = static_cast<std::uint64_t>(host.time().ns);
    channels_[kSceneChannel] = std::move(scene);
    scene_period_ = SimTime::from_seconds(options_.scene_rate > 0 ? 1.0 / options_.scene_rate : 0.5);
  } else if (!options_.scene_topic.empty()) {
    log::warn("foxglove: no scene topic: {} is already a simulation topic", options_.scene_topic);
  }

  // what clients may publish: each robot's cmd_vel, head command and joint command
  set_command_topics(world);
  // and what the host takes beyond them (a mission's reports, datagrams, relay drops, map)
  host_inputs_ = host.inputs();

  // the Simulation Interfaces as services, when the run can be controlled (a replay cannot)
  capabilities_ = {"clientPublish", "time"};
  if (control_) {
    capabilities_.push_back("services");
    services_advertisement_ = advertise_services(sim_services());
  }

  std::string robots;
  for (const auto& r : world.robots) robots += (robots.empty() ? "" : ", ") + r.name;
  server_info_ = server_info(
      "rescuesim", capabilities_, {"cdr", "json"},
      {{"world", world.name}, {"seed", std::to_string(host.seed())}, {"robots", robots}, {"scene_topic", options_.scene_topic}},
      std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::system_clock::now().time_since_epoch()).count()));

  ServerLimits limits;
  limits.max_clients = options_.max_clients;
  limits.max_frame = options_.max_client_frame;
  limits.queue_bytes = options_.client_queue_bytes;
  limits.queue_messages = options_.client_queue_messages;
  server_ = WsServer::start(options_.host, options_.port, kSubprotocol, limits, *this);
  {
    std::lock_guard lock(link_->mutex);
    link_->server = server_.get();
    link_->finish = [this](CallAnswer answer) { finish_call(std::move(answer)); };
  }
  log::info("foxglove: listening on ws://{}:{} ({} channels, {} services)", options_.host, server_->port(), channels_.size(),
            control_ ? sim_services().size() : 0);

  started_ = true;
  worker_ = start_named_thread("fox-serialise", [this] { run(); });
  bus_handle_ = host.bus().subscribe_shared("", [this](const Topic& t, const Bus::SharedMessage& m) { on_bus(t, m); });
  // robots spawned and deleted while running
  layout_handle_ = host.bus().watch_layout([this] { on_layout(); });
}

void FoxgloveBridge::stop() {
  if (!started_ || stopped_) return;
  stopped_ = true;
  host_->bus().unsubscribe(bus_handle_);
  host_->bus().unsubscribe(layout_handle_);
  // the serialiser sends what is queued (and the pending scene), then ends
  resume_serialiser();
  outbox_.close();
  if (worker_.joinable()) worker_.join();
  // service calls still held by SimControl answer nobody from now on
  {
    std::lock_guard lock(link_->mutex);
    link_->server = nullptr;
    link_->finish = nullptr;
  }
  server_->shutdown(std::chrono::milliseconds(500));
}

BridgeStats FoxgloveBridge::stats() const {
  BridgeStats s;
  if (server_) {
    const ClientCounters c = server_->totals();
    s.sent = c.sent;
    s.dropped = c.dropped;
  }
  s.dropped += outbox_.stats().dropped;
  s.received = received_;
  s.rejected = rejected_;
  return s;
}

// ---- simulation thread ----

SceneState FoxgloveBridge::scene_state() const {
  const State& st = host_->state();
  SceneState s;
  for (const BodyState& b : st.dynamics) s.rubble.push_back(b.X_WB);
  for (const VictimState& v : st.victims) {
    s.victim_found_at.push_back(v.first_seen.ns >= 0 ? v.first_seen.seconds() : -1.0);
    s.victim_found_by.push_back(v.seen_by);
  }
  return s;
}

void FoxgloveBridge::on_bus(const Topic& topic, const Bus::SharedMessage& m) {
  const SimTime now = host_->time();
  if (topic.id == clock_topic_) latest_time_.store(now.ns, std::memory_order_relaxed);
  // moving parts of the scene, at a low rate; only the newest snapshot matters, so one the
  // serialiser has not taken yet is replaced
  if (scene_ && now >= next_scene_) {
    next_scene_ = now + scene_period_;
    PendingScene pending{now, scene_state()};
    std::lock_guard lock(scene_mutex_);
    pending_scene_ = std::move(pending);
  }
  // topics advertised after start (and retired ones advertised again: a robot spawned again,
  // whose latched description comes before the layout watchers are called) become new
  // channels, announced to every client at once (rare, so the simulation thread takes the lock
  // itself rather than risk a dropped item)
  if (known_topics_ < host_->bus().topics().size() || (!gone_.empty() && gone_.count(topic.id) > 0)) {
    std::vector<Channel> added;
    std::lock_guard lock(mutex_);
    add_new_topics(&added);
    if (!added.empty()) {
      // a spawned robot's topics may come before the layout watchers are called (its latched
      // description, /tf_static): its command topics are taken before clients hear of it
      refresh_commands();
      const std::string text = advertise(added);
      for (const auto& [id, c] : clients_) server_->send_control(id, text);
    }
  }
  // only what some client wants (and latched topics, for later subscribers) is queued, shared
  // and uncopied, in the outbox: per topic at most bridge_queue messages (a burst pushes out
  // older messages of its own topic only), bridge_queue_bytes over all topics. Foxglove uses no
  // sequence numbers, so a topic nobody wants is not counted either (as in ROS 2). Latched
  // messages count no bytes: the budget never refuses them (their own topic's bound still holds).
  const auto id = static_cast<std::size_t>(topic.id);
  if (!topic.latched && id < kMaxTopics && wanted_[id].load(std::memory_order_relaxed) <= 0) return;
  outbox_.push(topic.id, now, m, topic.latched ? 0 : Outbox::approx_bytes(*m));
}

void FoxgloveBridge::add_new_topics(std::vector<Channel>* added) {
  const Bus& bus = host_->bus();
  const auto& topics = bus.topics();
  while (known_topics_ < topics.size()) {
    const Topic& t = topics[known_topics_++];
    if (t.retired) {
      gone_.insert(t.id);
    } else {
      add_topic(t, added);
    }
  }
  for (auto it = gone_.begin(); it != gone_.end();) {
    const Topic& t = bus.topic(*it);
    if (t.retired) {
      ++it;
      continue;
    }
    add_topic(t, added);
    it = gone_.erase(it);
  }
}

void FoxgloveBridge::on_layout() {
  // on the simulation thread, between steps, the Bus locked (read only)
  const Bus& bus = host_->bus();
  std::vector<std::uint32_t> removed;
  std::vector<Channel> added;
  std::lock_guard lock(mutex_);
  // retired topics' channels go, and every subscription to them (the client is told below)
  for (const Topic& t : bus.topics()) {
    if (!t.retired || static_cast<std::size_t>(t.id) >= known_topics_) continue;
    const auto it = channels_.find(channel_of(t.id));
    if (it == channels_.end()) continue;
    for (const auto& [client, sub] : it->second.subscribers) {
      const auto c = clients_.find(client);
      if (c != clients_.end()) c->second.subscriptions.erase(sub);
      if (static_cast<std::size_t>(t.id) < kMaxTopics) --wanted_[static_cast<std::size_t>(t.id)];
    }
    removed.push_back(it->first);
    channels_.erase(it);
    gone_.insert(t.id);
  }
  // new topics (a spawned robot's, before their first message) and topics back again
  add_new_topics(&added);
  refresh_commands();
  if (removed.empty() && added.empty()) return;
  const std::string gone_text = removed.empty() ? std::string() : unadvertise(removed);
  const std::string added_text = added.empty() ? std::string() : advertise(added);
  for (const auto& [id, c] : clients_) {
    if (!gone_text.empty()) server_->send_control(id, gone_text);
    if (!added_text.empty()) server_->send_control(id, added_text);
  }
}

void FoxgloveBridge::refresh_commands() {
  // the robots' command topics now, and each client channel pointed at its robot's index now,
  // by name (none when no robot takes it any more: its messages are refused)
  set_command_topics(host_->world());
  for (auto& [id, client] : clients_) {
    for (auto& [channel, target] : client.publishers) {
      if (target.kind == CommandTarget::Kind::host) continue;  // the host's inputs are fixed
      CommandTarget now;
      const bool found = robot_command(target.channel.topic, now) && now.kind == target.kind &&
                         (now.kind != CommandTarget::Kind::joints || joints_commandable_[now.robot]);
      target.robot = found ? now.robot : RobotIndex();
    }
  }
}

void FoxgloveBridge::set_command_topics(const World& world) {
  twist_topics_.clear();
  head_topics_.clear();
  joint_topics_.clear();
  flipper_topics_.clear();
  head_sizes_.clear();
  flipper_sizes_.clear();
  joints_commandable_.clear();
  for (RobotIndex r : world.robot_indices()) {
    twist_topics_.push_back(host_->topic_name(r, "cmd_vel"));
    head_topics_.push_back(host_->topic_name(r, "head/command"));
    head_sizes_.push_back(world.robot(r).spec.head_joints.size());
    joint_topics_.push_back(host_->topic_name(r, "joint_command"));
    flipper_topics_.push_back(host_->topic_name(r, "flippers/command"));
    flipper_sizes_.push_back(world.robot(r).spec.flipper_joints.size());
    joints_commandable_.push_back(has_commandable_joints(world.robot(r).spec));
  }
}

// ---- serialiser thread ----

void FoxgloveBridge::run() {
  std::int64_t last_time = -1;
  auto last_time_sent = std::chrono::steady_clock::now();
  std::vector<OutboxItem> round;
  const auto guarded = [this](auto&& f) {
    try {
      f();
    } catch (const std::exception& e) {
      std::uint64_t held = 0;
      if (error_log_.allow(&held)) log::error("foxglove: {} (and {} more)", e.what(), held);
    }
  };
  for (;;) {
    wait_while_paused();
    // at most one message per topic, oldest first
    round.clear();
    outbox_.take_round(round, std::chrono::milliseconds(5));
    // closed and nothing left after this round: handle it (and the pending scene), then end
    const bool done = outbox_.drained();
    // sim time at most every 5 ms of wall time (each client keeps only the latest)
    const std::int64_t t = latest_time_.load(std::memory_order_relaxed);
    const auto wall = std::chrono::steady_clock::now();
    if (t >= 0 && t != last_time && wall - last_time_sent >= std::chrono::milliseconds(5)) {
      broadcast_time(t);
      last_time = t;
      last_time_sent = wall;
    }
    for (const OutboxItem& item : round) guarded([&] { handle(item); });
    std::optional<PendingScene> scene;
    {
      std::lock_guard lock(scene_mutex_);
      scene.swap(pending_scene_);
    }
    if (scene) guarded([&] { handle_scene(*scene); });
    if (done) break;
  }
}

void FoxgloveBridge::wait_while_paused() {
  if (!pause_requested_.load()) return;
  std::unique_lock lock(pause_mutex_);
  paused_ = true;
  pause_cv_.notify_all();
  pause_cv_.wait(lock, [this] { return !pause_requested_.load(); });
  paused_ = false;
}

void FoxgloveBridge::pause_serialiser() {
  if (!started_ || stopped_) return;
  std::unique_lock lock(pause_mutex_);
  pause_requested_ = true;
  pause_cv_.wait(lock, [this] { return paused_; });
}

void FoxgloveBridge::resume_serialiser() {
  {
    std::lock_guard lock(pause_mutex_);
    pause_requested_ = false;
  }
  pause_cv_.notify_all();
}

void FoxgloveBridge::broadcast_time(std::int64_t ns) {
  std::vector<ClientId> ids;
  {
    std::lock_guard lock(mutex_);
    for (const auto& [id, c] : clients_) ids.push_back(id);
  }
  const std::vector<std::uint8_t> frame = time_frame(static_cast<std::uint64_t>(ns));
  for (ClientId id : ids) server_->send_time(id, frame);
}

void FoxgloveBridge::handle_scene(PendingScene& pending) {
  if (same_scene(pending.scene, last_scene_)) return;  // nothing moved
  last_scene_ = std::move(pending.scene);
  const std::string moving = scene_->moving(pending.at, last_scene_);
  const std::string full = scene_->full(pending.at, last_scene_);
  const Payload full_payload = std::make_shared<const std::vector<std::uint8_t>>(full.begin(), full.end());
  const Payload moving_payload = std::make_shared<const std::vector<std::uint8_t>>(moving.begin(), moving.end());
  std::vector<std::pair<ClientId, std::uint32_t>> subs;
  {
    std::lock_guard lock(mutex_);
    ChannelState& c = channels_.at(kSceneChannel);
    c.last = full_payload;
    c.last_stamp = static_cast<std::uint64_t>(pending.at.ns);
    subs.assign(c.subscribers.begin(), c.subscribers.end());
  }
  deliver(subs, static_cast<std::uint64_t>(pending.at.ns), moving_payload);
}

void FoxgloveBridge::handle(const OutboxItem& item) {
  const std::uint32_t channel = channel_of(item.topic);
  {
    std::lock_guard lock(mutex_);
    const auto it = channels_.find(channel);
    if (it == channels_.end() || (!it->second.latched && it->second.subscribers.empty())) return;
  }
  // a large message's bytes are shared with the other CDR bridges (bridges/common/shared_cdr.h)
  const Payload payload = shared_cdr(item.message);
  const auto stamp = static_cast<std::uint64_t>(std::max<std::int64_t>(item.at.ns, 0));
  std::vector<std::pair<ClientId, std::uint32_t>> subs;
  {
    std::lock_guard lock(mutex_);
    const auto it = channels_.find(channel);
    if (it == channels_.end()) return;  // unadvertised meanwhile (its robot was deleted)
    ChannelState& c = it->second;
    if (c.latched) {
      c.last = payload;
      c.last_stamp = stamp;
    }
    subs.assign(c.subscribers.begin(), c.subscribers.end());
  }
  deliver(subs, stamp, payload);
}

void FoxgloveBridge::deliver(const std::vector<std::pair<ClientId, std::uint32_t>>& subscribers, std::uint64_t stamp,
                             const Payload& payload) {
  for (const auto& [client, subscription] : subscribers) {
    const std::size_t dropped = server_->send_data(client, message_data_header(subscription, stamp), payload);
    if (dropped > 0) note_drops(client, dropped);
  }
}

void FoxgloveBridge::note_drops(ClientId client, std::size_t n) {
  std::uint64_t total = 0;
  bool warn = false;
  {
    std::lock_guard lock(mutex_);
    const auto it = clients_.find(client);
    if (it == clients_.end()) return;
    it->second.dropped += n;
    total = it->second.dropped;
    warn = it->second.drop_warning->allow();
  }
  if (!warn) return;
  server_->send_status(
      client, status(StatusLevel::warning, "rescuesim: this connection reads too slowly; " + std::to_string(total) +
                                               " messages dropped so far, oldest first (per-client queue limit " +
                                               mib(options_.client_queue_bytes) + " or " + std::to_string(options_.client_queue_messages) +
                                               " messages). Subscribe to fewer topics (images are large) or use a faster link."));
  std::uint64_t held = 0;
  if (client_log_.allow(&held)) log::info("foxglove: client {} is slow: {} messages dropped so far", client, total);
}

void FoxgloveBridge::add_topic(const Topic& t, std::vector<Channel>* added) {
  const msg::TypeSupport* type = msg::find_type(t.type);
  if (!type) {
    log::warn("foxglove: topic {} not advertised: no serialiser for {}", t.name, t.type);
    return;
  }
  ChannelState c;
  c.channel = {channel_of(t.id), t.name, "cdr", type->ros2_name, type->ros2_definition, "ros2msg"};
  c.topic = t.id;
  c.latched = t.latched;
  if (added) added->push_back(c.channel);
  channels_[c.channel.id] = std::move(c);
}

}  // namespace foxglove

std::unique_ptr<Bridge> make_foxglove_bridge(const FoxgloveOptions& options) { return std::make_unique<foxglove::FoxgloveBridge>(options); }

}  // namespace rescuesim
