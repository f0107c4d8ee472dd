// The ROS 2 bridge: every Bus topic becomes a DDS writer on rt/<topic> with ROS 2's type name,
// carrying msgs/serialize.h's XCDR1 bytes (latched ones, /tf_static and robot_description,
// transient local); /cmd_vel (as geometry_msgs/Twist and, on a second reader of the same topic,
// TwistStamped), /head/command and (for robots with commandable joints) /joint_command of each
// robot, and the host's own inputs (a mission's reports, datagrams, relay drops), become readers
// whose samples are decoded, checked and queued into the simulation; the services and actions
// that register_control_services() puts on the bridge's ServiceRegistry are served; the
// participant announces a node (rescuesim, namespace /) with all these endpoints on
// ros_discovery_info so `ros2 node list`, `ros2 service list` and `ros2 action list` see it.
//
// Threads: the Bus callback (simulation thread) only queues the shared message (no copy) in the
// Outbox (bridges/common/outbox.h: one bounded queue per topic, so a burst of /clock at 200 Hz
// never pushes out an image or /tf_static), and notes the sim time; a sender thread serialises
// and writes, a round of at most one message per topic at a time; a receiver thread waits on the
// readers, hands what they take to the shared command gate (bridges/common/commands.h), and
// polls the services (requests in, replies out: service_registry.h).
//
// Robots spawned and deleted while running (Bus::watch_layout, on the simulation thread between
// steps): topics new since start get writers, retired ones lose theirs, command readers follow
// the robots by name (a robot after a deleted one moves down one index), and the node is
// announced again. layout_mutex_ guards what that changes against the sender and receiver threads;
// the Bus callback reads it unlocked, being on the thread that changes it.

#include "bridges/ros2/ros2_bridge.h"

#include <algorithm>
#include <atomic>
#include <deque>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "bridges/common/commands.h"
#include "bridges/common/outbox.h"
#include "bridges/common/shared_cdr.h"
#include "bridges/ros2/command_input.h"
#include "bridges/ros2/control_services.h"
#include "bridges/ros2/dds_participant.h"
#include "bridges/ros2/ros2_conventions.h"
#include "bridges/ros2/service_registry.h"
#include "core/error.h"
#include "core/log.h"
#include "core/thread.h"
#include "core/throttle.h"
#include "msgs/serialize.h"
#include "bus/bridge_host.h"

namespace rescuesim {

namespace {

using ros2::DdsParticipant;

class Ros2Bridge final : public Bridge {
 public:
  explicit Ros2Bridge(const Ros2Options& options) : options_(options) {}
  ~Ros2Bridge() override { stop(); }

  std::string name() const override { return "ros2"; }
  void start(BridgeHost& host) override;
  void stop() override;
  BridgeStats stats() const override {
    BridgeStats s;
    s.sent = sent_.load();
    s.dropped = failed_.load();
    s.dropped += outbox_.stats().dropped;
    s.received = gate_ ? gate_->received() : 0;
    s.rejected = gate_ ? gate_->rejected() : 0;
    // malformed service requests count as refused commands
    std::lock_guard lock(services_mutex_);
    s.rejected += services_ ? services_->malformed() : services_malformed_;
    if (undecodable_requests_) s.rejected += undecodable_requests_();
    return s;
  }

 private:
  /// A command reader: whose commands, of which kind.
  struct Input {
    /// cmd_vel (Twist), cmd_vel (TwistStamped), head/command, joint_command, flippers/command, BridgeHost::inputs()
    enum class Kind { velocity, velocity_stamped, head, joints, flippers, host };
    int reader;
    RobotIndex robot;
    Kind kind;
    std::string topic;  ///< ROS name, for warnings
    std::string robot_name;                       ///< whose commands (the host's own inputs: "")
    std::size_t host_input = 0;                   ///< Kind::host: the index in BridgeHost::inputs()
    const msg::TypeSupport* type = nullptr;       ///< Kind::host: how to decode it
  };

  /// What goes out on one Bus topic.
  struct Out {
    int writer = -1;          ///< -1: not bridged (no ROS 2 type, or retired)
    bool bridgeable = false;  ///< ROS 2 knows its type
    bool latched = false;
  };

  /// A writer for Bus topic `t` when ROS 2 knows its type (out_ grows to hold it). Under layout_mutex_.
  void add_writer(const Topic& t);
  /// The command readers of robot `robot` (cmd_vel twice, head, joints, flippers as it has them). Under layout_mutex_.
  void add_robot_readers(RobotIndex robot);
  /// Bus::watch_layout: writers for topics new or back, none for retired ones; readers follow the robots.
  void on_layout();
  void send_loop();
  void refresh_listened();
  void send(TopicId topic, const Bus::SharedMessage& message, std::vector<std::uint8_t>& buffer);
  void receive_loop();
  void receive(Input& input, std::span<const std::uint8_t> bytes);
  /// Writes ros_discovery_info: the node with its topics' endpoints and every service's.
  bool publish_discovery(std::string* error);

  Ros2Options options_;
  BridgeHost* host_ = nullptr;
  std::unique_ptr<DdsParticipant> dds_;
  std::mutex layout_mutex_;                 ///< guards out_, listened_'s size, inputs_ and node_
  std::vector<Out> out_;                    ///< by Bus topic id
  std::deque<std::atomic<bool>> listened_;  ///< by Bus topic id: has matched readers (or is latched)
  std::vector<Input> inputs_;
  Outbox outbox_;                            ///< per topic, sized from its rate (ros2::queue_capacity)
  SubscriptionId subscription_ = kNoSubscription;
  SubscriptionId layout_watch_ = kNoSubscription;
  std::thread sender_, receiver_;
  std::atomic<bool> receiving_{false};
  std::atomic<std::uint64_t> sent_{0}, failed_{0};
  std::unique_ptr<CommandGate> gate_;  ///< checks, counts and warns about what the readers take
  Throttle write_warning_;
  ros2::NodeEntities node_;  ///< the node's topic endpoints (the services' are added when announced)
  int discovery_writer_ = -1;
  mutable std::mutex services_mutex_;  ///< guards services_ itself (for stats() during stop())
  std::unique_ptr<ros2::ServiceRegistry> services_;  ///< polled on the receiver thread
  std::uint64_t services_malformed_ = 0;             ///< services_->malformed() when it was stopped
  std::function<std::uint64_t()> undecodable_requests_;  ///< whole requests that did not decode (control_services.h)
  std::atomic<bool> discovery_dirty_{false};         ///< services were added after start: announce again
  std::atomic<std::int64_t> sim_time_ns_{0};         ///< the host's sim time, noted on the simulation thread
};

void Ros2Bridge::start(BridgeHost& host) {
  if (dds_) throw Error("ROS 2 bridge: start() called twice");
  host_ = &host;
  gate_ = std::make_unique<CommandGate>(host, "ROS 2 bridge");
  const int domain = ros2::resolve_domain(options_.domain_id);
  dds_ = std::make_unique<DdsParticipant>(domain, ros2::participant_user_data());
  sim_time_ns_ = host.time().ns;
  ros2::NodeEntities& node = node_;
  node.node_name = options_.node_name;
  node.node_namespace = options_.node_namespace;

  // a writer per Bus topic, typed and named the ROS 2 way, and command readers for every robot
  {
    std::lock_guard lock(layout_mutex_);
    for (const Topic& t : host.bus().topics()) add_writer(t);
    for (RobotIndex r : host.world().robot_indices()) add_robot_readers(r);
  }

  // the host's own inputs (a mission's reports, datagrams, relay drops)
  const std::vector<HostInput> host_inputs = host.inputs();
  for (std::size_t i = 0; i < host_inputs.size(); ++i) {
    const msg::TypeSupport* type = msg::find_type(host_inputs[i].type);
    if (type == nullptr || !DdsParticipant::knows_type(type->dds_name)) {
      log::warn("ROS 2 bridge: input {} of type {} is not bridged (no ROS 2 type for it)", host_inputs[i].topic, host_inputs[i].type);
      continue;
    }
    const int reader = dds_->create_reader(ros2::dds_topic_name(host_inputs[i].topic), type->dds_name, ros2::command_reader_qos());
    Input in{reader, host_inputs[i].robot, Input::Kind::host, host_inputs[i].topic, ""};
    in.host_input = i;
    in.type = type;
    inputs_.push_back(std::move(in));
    node.readers.push_back(dds_->reader_guid(reader));
  }

  // the run's services and actions, served on the receiver thread (sim time stamps their goals)
  services_ = std::make_unique<ros2::ServiceRegistry>(*dds_, [this] { return sim_time_ns_.load(std::memory_order_relaxed); });
  undecodable_requests_ = ros2::register_control_services(*services_, host, options_);

  // the node, for `ros2 node list` / `ros2 node info` (transient-local: late joiners get it too);
  // services added later are announced again from the receiver thread
  discovery_writer_ = dds_->create_discovery_writer(ros2::gid_size(options_.distro));
  std::string error;
  if (!publish_discovery(&error)) throw Error("ROS 2 bridge: cannot publish ros_discovery_info: " + error);
  services_->set_on_change([this] {
    discovery_dirty_ = true;
    dds_->wake();
  });

  // the simulation thread only queues the shared messages (no copy), and only what someone listens to
  refresh_listened();
  subscription_ = host.bus().subscribe_shared("", [this](const Topic& topic, const Bus::SharedMessage& m) {
    // the receiver thread checks TwistStamped stamps against this
    sim_time_ns_.store(host_->time().ns, std::memory_order_relaxed);
    const std::size_t id = static_cast<std::size_t>(topic.id);
    // not bridged (no ROS 2 type, or advertised since the last layout change): not even queued
    if (id >= out_.size() || out_[id].writer < 0) return;
    if (!listened_[id].load(std::memory_order_relaxed)) return;
    outbox_.push(topic.id, host_->time(), m, 0);
  });
  layout_watch_ = host.bus().watch_layout([this] { on_layout(); });
  receiving_ = true;
  sender_ = start_named_thread("ros2-send", [this] { send_loop(); });
  receiver_ = start_named_thread("ros2-receive", [this] { receive_loop(); });
  log::info("ROS 2 bridge: domain {}, node {}{}{}, {} topics out, {} command readers in, {} services and actions", domain,
            options_.node_namespace, options_.node_namespace.ends_with('/') ? "" : "/", options_.node_name,
            node.writers.size(), inputs_.size(), services_->size());
}

void Ros2Bridge::stop() {
  if (!dds_) return;
  if (subscription_ != kNoSubscription) {
    host_->bus().unsubscribe(subscription_);
    subscription_ = kNoSubscription;
  }
  if (layout_watch_ != kNoSubscription) {
    host_->bus().unsubscribe(layout_watch_);
    layout_watch_ = kNoSubscription;
  }
  // the sender drains what is queued, then ends
  outbox_.close();
  if (sender_.joinable()) sender_.join();
  receiving_ = false;
  dds_->wake();
  if (receiver_.joinable()) receiver_.join();
  {
    // handles the simulation thread still holds find their services gone
    std::lock_guard lock(services_mutex_);
    if (services_) services_malformed_ = services_->malformed();
    services_.reset();
  }
  dds_.reset();
}

void Ros2Bridge::send_loop() {
  std::vector<std::uint8_t> buffer;
  std::vector<OutboxItem> round;
  std::optional<std::chrono::steady_clock::time_point> closed_at;
  auto next_refresh = std::chrono::steady_clock::now();
  for (;;) {
    round.clear();
    const bool took = outbox_.take_round(round, std::chrono::milliseconds(50));
    if (std::chrono::steady_clock::now() >= next_refresh) {
      refresh_listened();
      next_refresh = std::chrono::steady_clock::now() + std::chrono::milliseconds(100);
    }
    // a round is at most one message per topic, oldest first
    for (const OutboxItem& item : round) send(item.topic, item.message, buffer);
    if (outbox_.drained()) return;
    // stop() waits for what is queued, but not for ever
    if (took && outbox_.closed()) {
      const auto now = std::chrono::steady_clock::now();
      if (!closed_at) closed_at = now;
      if (now - *closed_at > std::chrono::seconds(2)) return;
    }
  }
}

void Ros2Bridge::refresh_listened() {
  // a topic nobody reads is neither copied nor serialised; latched ones always are, for latecomers
  std::lock_guard lock(layout_mutex_);
  for (std::size_t id = 0; id < out_.size(); ++id) {
    const Out& o = out_[id];
    listened_[id].store(o.writer >= 0 && (o.latched || dds_->matched_readers(o.writer) > 0), std::memory_order_relaxed);
  }
}

void Ros2Bridge::add_writer(const Topic& t) {
  const auto id = static_cast<std::size_t>(t.id);
  while (out_.size() <= id) {
    out_.emplace_back();
    listened_.emplace_back(false);
  }
  Out& o = out_[id];
  const msg::TypeSupport* type = msg::find_type(t.type);
  o.bridgeable = type != nullptr && DdsParticipant::knows_type(type->dds_name);
  if (!o.bridgeable) {
    log::warn("ROS 2 bridge: topic {} of type {} is not bridged (no ROS 2 type for it)", t.name, t.type);
    return;
  }
  if (t.retired) return;
  o.writer = dds_->create_writer(ros2::dds_topic_name(t.name), type->dds_name, ros2::writer_qos(t));
  o.latched = t.latched;
  outbox_.set_capacity(t.id, ros2::queue_capacity(t, options_.queue_size));
  node_.writers.push_back(dds_->writer_guid(o.writer));
}

void Ros2Bridge::add_robot_readers(RobotIndex robot) {
  const BridgeHost& host = *host_;
  const RobotInstance& r = host.world().robot(robot);
  const auto add = [&](Input::Kind kind, const std::string& topic, int reader) {
    inputs_.push_back({reader, robot, kind, topic, r.name});
    node_.readers.push_back(dds_->reader_guid(reader));
  };
  const std::string cmd_vel = host.topic_name(robot, "cmd_vel");
  add(Input::Kind::velocity, cmd_vel,
      dds_->create_reader(ros2::dds_topic_name(cmd_vel), "geometry_msgs::msg::dds_::Twist_", ros2::command_reader_qos()));
  // TwistStamped on the same topic (Jazzy's diff_drive_controller, Nav2 from Kilted): a type
  // of its own, so a reader of its own; Cyclone keeps two types on one topic name apart
  add(Input::Kind::velocity_stamped, cmd_vel,
      dds_->create_raw_reader(ros2::dds_topic_name(cmd_vel), "geometry_msgs::msg::dds_::TwistStamped_", ros2::command_reader_qos()));
  if (!r.spec.head_joints.empty()) {
    const std::string head = host.topic_name(robot, "head/command");
    add(Input::Kind::head, head,
        dds_->create_reader(ros2::dds_topic_name(head), "std_msgs::msg::dds_::Float64MultiArray_", ros2::command_reader_qos()));
  }
  if (has_commandable_joints(r.spec)) {
    const std::string joints = host.topic_name(robot, "joint_command");
    add(Input::Kind::joints, joints,
        dds_->create_reader(ros2::dds_topic_name(joints), "sensor_msgs::msg::dds_::JointState_", ros2::command_reader_qos()));
  }
  if (!r.spec.flipper_joints.empty()) {
    const std::string flippers = host.topic_name(robot, "flippers/command");
    add(Input::Kind::flippers, flippers,
        dds_->create_reader(ros2::dds_topic_name(flippers), "std_msgs::msg::dds_::Float64MultiArray_", ros2::command_reader_qos()));
  }
}

void Ros2Bridge::on_layout() {
  std::lock_guard lock(layout_mutex_);
  bool changed = false;
  // writers: for topics new since the last change or advertised again; none for retired ones
  for (const Topic& t : host_->bus().topics()) {
    const auto id = static_cast<std::size_t>(t.id);
    if (id >= out_.size()) {
      add_writer(t);
      changed = true;
      continue;
    }
    Out& o = out_[id];
    if (t.retired && o.writer >= 0) {
      std::erase(node_.writers, dds_->writer_guid(o.writer));
      dds_->delete_writer(o.writer);
      o.writer = -1;
      listened_[id].store(false, std::memory_order_relaxed);
      changed = true;
    } else if (!t.retired && o.writer < 0 && o.bridgeable) {
      add_writer(t);
      changed = true;
    }
  }
  // command readers follow their robots by name: gone with them, moved down with them
  const World& world = host_->world();
  std::map<std::string, RobotIndex> index;
  for (RobotIndex r : world.robot_indices()) index[world.robot(r).name] = r;
  std::set<std::string> served;
  for (auto it = inputs_.begin(); it != inputs_.end();) {
    if (it->robot_name.empty()) {
      ++it;
      continue;
    }
    const auto found = index.find(it->robot_name);
    if (found == index.end()) {
      std::erase(node_.readers, dds_->reader_guid(it->reader));
      dds_->delete_reader(it->reader);
      it = inputs_.erase(it);
      changed = true;
      continue;
    }
    it->robot = found->second;
    served.insert(it->robot_name);
    ++it;
  }
  for (const auto& [name, r] : index) {
    if (served.count(name)) continue;
    add_robot_readers(r);
    changed = true;
  }
  if (changed) {
    discovery_dirty_ = true;
    dds_->wake();
  }
}

void Ros2Bridge::send(TopicId topic, const Bus::SharedMessage& message, std::vector<std::uint8_t>& buffer) {
  // under the layout lock: a deleted robot's writer goes only between rounds
  std::lock_guard lock(layout_mutex_);
  const int writer = out_[static_cast<std::size_t>(topic)].writer;
  if (writer < 0) return;  // retired after it was queued
  const msg::Message& m = *message;
  // a large message's bytes are encoded once for every CDR bridge (bridges/common/shared_cdr.h);
  // the distro adaptations touch only small messages, so those are what this bridge encodes
  SharedBytes shared;
  std::span<const std::uint8_t> bytes;
  if (!ros2::distro_changes(m, options_.distro) && cdr_is_shared(m)) {
    shared = shared_cdr(message);
    bytes = *shared;
  } else {
    buffer.clear();
    msg::to_cdr(m, buffer);
    ros2::adapt_to_distro(m, options_.distro, buffer);
    bytes = buffer;
  }
  std::string error;
  if (dds_->write(writer, bytes, &error)) {
    ++sent_;
    return;
  }
  ++failed_;
  std::uint64_t held = 0;
  if (write_warning_.allow(&held)) {
    log::warn("ROS 2 bridge: cannot publish on {}: {} ({} more failures held back)", host_->bus().topic(topic).name, error, held);
  }
}

bool Ros2Bridge::publish_discovery(std::string* error) {
  ros2::NodeEntities node;
  {
    std::lock_guard lock(layout_mutex_);
    node = node_;
  }
  if (services_) {
    for (const ros2::Guid& g : services_->reader_guids()) node.readers.push_back(g);
    for (const ros2::Guid& g : services_->writer_guids()) node.writers.push_back(g);
  }
  const auto info = ros2::encode_discovery_info(dds_->participant_guid(), {node}, ros2::gid_size(options_.distro));
  return dds_->write(discovery_writer_, info, error);
}

void Ros2Bridge::receive_loop() {
  while (receiving_.load()) {
    // sooner than the usual 200 ms when a service reply waits for its client's reader to match
    dds_->wait(services_->poll_within(std::chrono::milliseconds(200)));
    {
      std::lock_guard lock(layout_mutex_);
      for (Input& in : inputs_) {
        dds_->take(in.reader, [&](std::span<const std::uint8_t> bytes) { receive(in, bytes); });
      }
    }
    services_->poll();
    if (discovery_dirty_.exchange(false)) {
      std::string error;
      if (!publish_discovery(&error)) log::warn("ROS 2 bridge: cannot publish ros_discovery_info: {}", error);
    }
  }
}

void Ros2Bridge::receive(Input& in, std::span<const std::uint8_t> bytes) {
  // decoded here, checked, counted and warned about by the gate every bridge shares
  const auto take = [&](auto decoded, auto apply) {
    if (!decoded.value) return gate_->malformed(in.topic, decoded.problem);
    apply(*decoded.value);
  };
  switch (in.kind) {
    case Input::Kind::velocity:
      take(ros2::decode_twist(bytes), [&](const msg::Twist& t) { gate_->velocity(in.robot, in.topic, t); });
      break;
    case Input::Kind::velocity_stamped:
      take(ros2::decode_twist_stamped(bytes), [&](const ros2::StampedTwist& t) {
        // a stamp from the future, NaN and the drive's limits: the gate's, as for every velocity command
        gate_->velocity_stamped(in.robot, in.topic, t.stamp, SimTime{sim_time_ns_.load(std::memory_order_relaxed)}, t.twist);
      });
      break;
    case Input::Kind::head:
      take(ros2::decode_head_command(bytes), [&](const std::vector<double>& p) { gate_->head(in.robot, in.topic, p); });
      break;
    case Input::Kind::joints:
      take(ros2::decode_joint_command(bytes), [&](const msg::JointState& j) { gate_->joints(in.robot, in.topic, j); });
      break;
    case Input::Kind::flippers:
      take(ros2::decode_head_command(bytes), [&](const std::vector<double>& p) { gate_->flippers(in.robot, in.topic, p); });
      break;
    case Input::Kind::host:
      try {
        gate_->input(in.host_input, in.topic, msg::from_cdr(*in.type, bytes));
      } catch (const Error& e) {
        gate_->malformed(in.topic, "malformed CDR: " + e.message());
      }
      break;
  }
}

}  // namespace

std::unique_ptr<Bridge> make_ros2_bridge(const Ros2Options& options) { return std::make_unique<Ros2Bridge>(options); }

}  // namespace rescuesim
