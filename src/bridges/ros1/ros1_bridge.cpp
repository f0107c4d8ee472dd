// The ROS 1 bridge on roscpp: one node, pre-serialised messages out, checked commands in,
// and a watch on the master so the simulation outlives it.

#include "bridges/ros1/ros1_bridge.h"

#include <ros/callback_queue.h>
#include <ros/init.h>
#include <ros/master.h>
#include <ros/message_event.h>
#include <ros/message_traits.h>
#include <ros/network.h>
#include <ros/node_handle.h>
#include <ros/param.h>
#include <ros/publisher.h>
#include <ros/serialization.h>
#include <ros/subscriber.h>
#include <ros/this_node.h>
#include <ros/xmlrpc_manager.h>
#include <xmlrpcpp/XmlRpcException.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "bridges/common/commands.h"
#include "bridges/common/outbox.h"
#include "bridges/ros1/ros1_console.h"
#include "bridges/ros1/ros1_endpoint.h"
#include "bridges/ros1/ros1_raw_message.h"
#include "bridges/ros1/ros1_sim_services.h"
#include "bridges/ros1/ros1_velocity.h"
#include "core/error.h"
#include "core/log.h"
#include "core/thread.h"
#include "core/throttle.h"
#include "msgs/serialize.h"
#include "bus/bridge_host.h"


namespace rescuesim {

namespace {

using ros1_wire::RawMessage;
using Clock = std::chrono::steady_clock;

/// roscpp is one node per process.
std::atomic<bool> g_node_in_use{false};

constexpr std::uint32_t kRosPublishQueue = 20;   ///< roscpp's outgoing queue per subscriber connection
constexpr std::uint32_t kRosSubscribeQueue = 10;

const char* env(const char* name) { return std::getenv(name); }

/// The master's process id, or nothing when it does not answer (one try, no waiting).
std::optional<int> master_pid() {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getPid", args, result, payload, false)) return std::nullopt;
  if (payload.getType() != XmlRpc::XmlRpcValue::TypeInt) return 0;
  return static_cast<int>(payload);
}

class Ros1Bridge final : public Bridge {
 public:
  explicit Ros1Bridge(const Ros1Options& options)
      : options_(options), outbox_({.per_topic = std::max<std::size_t>(1, options.queue_size)}) {}
  /// Without stop(), the Bus subscription is left to the simulation (which then must not publish
  /// again): stop() belongs on the simulation thread, the destructor may run anywhere.
  ~Ros1Bridge() override { shut_down(); }

  std::string name() const override { return "ros1"; }
  void start(BridgeHost& host) override;
  void stop() override;
  BridgeStats stats() const override {
    BridgeStats s;
    s.sent = sent_.load();
    s.dropped = outbox_.stats().dropped;
    s.received = gate_ ? gate_->received() : 0;
    s.rejected = (gate_ ? gate_->rejected() : 0) + refused_.load();
    return s;
  }

 private:
  /// A Bus topic as published to ROS.
  struct Output {
    std::string name;
    bool latched = false;
    const msg::TypeSupport* type = nullptr;  ///< nullptr: no ROS 1 serialiser, not published
    ros::Publisher pub;                      ///< made on start or by the layout watcher, used by every thread (roscpp locks inside)
    bool retired = false;                    ///< its Bus topic is retired (or not yet advertised to ROS): no publisher
  };
  /// A command topic of a robot.
  struct Input {
    /// cmd_vel, head/command, joint_command, flippers/command, BridgeHost::inputs()
    enum class Kind { velocity, head, joints, flippers, host };
    std::string topic;
    RobotIndex robot{0};  ///< index into world().robots; the layout watcher keeps it current
    Kind kind = Kind::velocity;
    const msg::TypeSupport* type = nullptr;
    ros::Subscriber sub;                      ///< like every field, under inputs_mutex_ after start
    int unconnected_checks = 0;               ///< master checks in a row that found publishers it could not connect to
    std::size_t host_input = 0;               ///< Kind::host: the index in BridgeHost::inputs()
    // Kind::velocity (spinner thread): a roscpp subscription of MD5 "*" takes on the MD5 of the
    // first publisher it connects to, and publishers of the other type then refuse it
    bool adopted = false;                     ///< connected since it was made: its type is set
    std::string connected_type{};             ///< the type of the last message received
    /// the robot's name (RobotInstance::name), which follows it when its index changes; "" for
    /// Kind::host
    std::string robot_name{};
  };
  /// The type a command subscription asks its publishers for: "*" for cmd_vel (either type).
  static std::string subscribed_type(const Input& in) { return in.kind == Input::Kind::velocity ? "*" : in.type->ros1_name; }

  /// The Output of a Bus topic, not yet advertised to ROS (warns when it has no serialiser).
  static Output make_output(const Topic& t);
  /// Appends world.robots[robot]'s command inputs to inputs_ (not yet subscribed); inputs_mutex_ held or no other thread yet.
  void add_robot_inputs(const World& world, RobotIndex robot);
  void advertise(Output& o);
  void advertise_all();
  void set_parameters();
  /// (Re)makes the subscription of inputs_[key]; inputs_mutex_ held or no other thread yet.
  void subscribe(std::uint64_t key, Input& in);
  /// Makes the subscriptions of `keys` afresh (spin thread): shuts the old ones down without
  /// inputs_mutex_ (roscpp's shutdown takes the lock its callbacks run under, and a callback
  /// under way may be waiting for inputs_mutex_), then subscribes under it. Keys gone meanwhile
  /// are skipped; with `keep_checks` the inputs keep their count of unconnected checks.
  void renew_subscriptions(const std::vector<std::uint64_t>& keys, bool keep_checks);
  /// The layout watcher (simulation thread, Bus locked): publishers and command subscriptions
  /// follow the topics and robots that came and went (follow_layout); what roscpp throws is
  /// logged, not passed to the simulation.
  void on_layout();
  void follow_layout();
  bool register_again();
  void publish_loop();
  void publish(const OutboxItem& item);
  void refresh_wanted();
  void spin_loop();
  void watch_master();
  void check_input_publishers();
  void on_command(std::uint64_t key, const RawMessage& raw);
  void on_velocity(std::uint64_t key, const ros::M_string& connection, const RawMessage& raw);
  /// Counts a command refused here rather than by the gate, and warns as the gate does.
  void refuse(const std::string& topic, const char* kind, const std::string& why);
  void shut_down();

  Ros1Options options_;
  BridgeHost* host_ = nullptr;
  std::unique_ptr<CommandGate> gate_;
  Ros1Endpoint endpoint_;
  SubscriptionId bus_handle_ = kNoSubscription;
  SubscriptionId layout_handle_ = kNoSubscription;
  bool started_ = false;

  Outbox outbox_;  ///< per topic, queue_size each; its sequence numbers are Header.seq + 1
  /// outputs_ and wanted_ grow, and outputs_' entries change, only on the simulation thread (the
  /// layout watcher), under this lock; the publisher and spinner threads read them under it, the
  /// simulation thread's Bus callback without it.
  std::mutex outputs_mutex_;
  std::vector<Output> outputs_;  ///< by Bus topic id
  std::deque<std::atomic<bool>> wanted_;  ///< by Bus topic id: someone subscribes, or latched (a deque: entries stay put as it grows)
  /// Simulation thread only: the last message of latched topics that have no publisher yet (a
  /// spawned robot's robot_description is published before the layout watcher is called)
  std::map<std::size_t, Bus::SharedMessage> early_latched_;
  /// inputs_ is read and changed on the spinner thread (subscription callbacks, master checks) and
  /// changed by the layout watcher on the simulation thread: under this lock. Never held while a
  /// subscription is shut down (roscpp then waits for its callback, which may wait for the lock).
  std::mutex inputs_mutex_;
  std::map<std::uint64_t, Input> inputs_;  ///< by a key that never changes (callbacks carry it), in the order made
  std::uint64_t next_input_ = 0;
  /// The robot_description parameter (name, text) of each spawned robot that has one, by robot
  /// name: set by the layout watcher, set again by the spinner thread when a master comes back
  std::mutex params_mutex_;
  std::map<std::string, std::pair<std::string, std::string>> spawned_params_;
  std::unique_ptr<ros::NodeHandle> nh_;
  ros::CallbackQueue callbacks_;
  std::thread publisher_, spinner_;
  std::atomic<bool> stopping_{false};
  std::atomic<Clock::rep> drain_until_{Clock::time_point::max().time_since_epoch().count()};
  std::atomic<std::uint64_t> sent_{0};
  std::unique_ptr<Ros1SimServices> services_;  ///< /reset_simulation, /pause_physics, ... (their own thread)
  /// The host's sim time as of its last Bus message (written on the simulation thread): what
  /// stamped cmd_vel is checked against. A client on sim time stamps from /clock, which this
  /// never lags: it is updated before the /clock message is even queued.
  std::atomic<std::int64_t> sim_now_ns_{0};
  // refusals of commands the gate does not see (a cmd_vel of another type, a stamp in the
  // future): spinner thread only
  std::map<std::string, Throttle> throttles_;
  std::atomic<std::uint64_t> refused_{0};

  // master watch (spinner thread only), and type mismatches (publisher thread only)
  bool connected_ = true;
  int master_pid_ = -1;
  bool shutdown_reported_ = false;
  std::set<TopicId> mismatch_reported_;  ///< topics whose messages could not be published (type mismatch, serialiser error)
};

void Ros1Bridge::start(BridgeHost& host) {
  if (started_) throw Error("ROS 1: the bridge is already started");
  if (g_node_in_use.exchange(true)) throw Error("ROS 1: only one ROS 1 bridge per process (roscpp runs one node per process)");
  host_ = &host;
  gate_ = std::make_unique<CommandGate>(host, "ROS 1");
  sim_now_ns_ = host.time().ns;
  endpoint_ = resolve_ros1_endpoint(env("ROS_MASTER_URI"), env("ROS_HOSTNAME"), env("ROS_IP"));
  try {
    route_rosconsole_to_log();
    ros::M_string remappings{{"__master", endpoint_.master_uri}};
    if (!endpoint_.hostname.empty()) remappings["__hostname"] = endpoint_.hostname;
    // rescuesim handles SIGINT itself: roscpp must not install its handler
    ros::init(remappings, options_.node_name, ros::init_options::NoSigintHandler);
    // calls to a vanished master give up after this instead of retrying forever
    ros::master::setRetryTimeout(ros::WallDuration(1.0));

    // the master must answer before the node starts (roscpp would wait for it forever)
    const auto deadline = Clock::now() + std::chrono::duration<double>(options_.master_timeout);
    std::optional<int> pid;
    while (!(pid = master_pid())) {
      if (Clock::now() >= deadline) {
        throw Error(fmt::format("ROS 1: no master at {} (ROS_MASTER_URI); start roscore first", endpoint_.master_uri));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    master_pid_ = *pid;
    ros::start();
    nh_ = std::make_unique<ros::NodeHandle>();
    nh_->setCallbackQueue(&callbacks_);

    // every Bus topic goes out under its own name and type
    for (const Topic& t : host.bus().topics()) outputs_.push_back(make_output(t));
    // commands: each robot's cmd_vel and head/command, and joint_command when it has joints to command
    for (RobotIndex r : host.world().robot_indices()) {
      add_robot_inputs(host.world(), r);
      // (robots spawned before the bridge started: their description parameter as the watcher keeps it)
      const RobotInstance& robot = host.world().robot(r);
      if (robot.spawned && !robot.spec.description.empty()) {
        spawned_params_[robot.name] = {host.topic_name(r, "robot_description"), robot.spec.description};
      }
    }
    // the host's own inputs (a mission's reports, datagrams, relay drops)
    const std::vector<HostInput> host_inputs = host.inputs();
    for (std::size_t i = 0; i < host_inputs.size(); ++i) {
      Input in{host_inputs[i].topic, host_inputs[i].robot, Input::Kind::host, msg::find_type(host_inputs[i].type), {}};
      in.host_input = i;
      if (!in.type) throw Error("ROS 1: input " + in.topic + " has type " + host_inputs[i].type + ", which has no ROS 1 serialiser");
      inputs_.emplace(next_input_++, std::move(in));
    }
    advertise_all();
    set_parameters();
    // the simulation services last: they start a thread of their own
    services_ = std::make_unique<Ros1SimServices>(
        host, std::chrono::milliseconds(std::llround(std::max(0.0, options_.service_timeout) * 1000)));
    services_->advertise(*nh_);
  } catch (const ros::Exception& e) {
    services_.reset();
    g_node_in_use = false;
    throw Error(fmt::format("ROS 1: {} (master {})", e.what(), endpoint_.master_uri));
  } catch (...) {
    services_.reset();
    g_node_in_use = false;
    throw;
  }

  // the simulation thread only queues the shared message (no copy) in the outbox, and only what
  // someone listens to; serialising happens on the publisher thread. The outbox's sequence per
  // topic counts every message the simulation produced (Header.seq).
  for (const Output& o : outputs_) wanted_.emplace_back(o.type && o.latched);
  bus_handle_ = host.bus().subscribe_shared("", [this](const Topic& t, const Bus::SharedMessage& m) {
    sim_now_ns_.store(host_->time().ns, std::memory_order_relaxed);
    // a topic advertised after start, or brought back, has no ROS publisher until the layout
    // watcher makes one: not queued; a latched one's message waits for it. (Only this thread
    // changes outputs_: read without the lock.)
    const auto id = static_cast<std::size_t>(t.id);
    if (id >= outputs_.size() || outputs_[id].retired) {
      if (t.latched) early_latched_[id] = m;
      return;
    }
    if (wanted_[id].load(std::memory_order_relaxed)) {
      outbox_.push(t.id, host_->time(), m, 0);
    } else {
      outbox_.skip(t.id);
    }
  });
  // robots spawned and deleted while running: publishers and command subscriptions follow them
  layout_handle_ = host.bus().watch_layout([this] { on_layout(); });
  publisher_ = start_named_thread("ros1-send", [this] { publish_loop(); });
  spinner_ = start_named_thread("ros1-spin", [this] { spin_loop(); });
  started_ = true;
  log::info("ROS 1: node {} registered with the master at {}, reachable as {}: {} topics out, {} in, {} services",
            ros::this_node::getName(), endpoint_.master_uri, ros::network::getHost(), outputs_.size(), inputs_.size(),
            services_->size());
}

Ros1Bridge::Output Ros1Bridge::make_output(const Topic& t) {
  Output o;
  o.name = t.name;
  o.latched = t.latched;
  o.type = msg::find_type(t.type);
  if (!o.type) log::warn("ROS 1: {} has type {}, which has no ROS 1 serialiser: not published", t.name, t.type);
  return o;
}

void Ros1Bridge::add_robot_inputs(const World& world, RobotIndex r) {
  const RobotInstance& robot = world.robot(r);
  const BridgeHost& host = *host_;
  const auto add = [&](Input in) {
    in.robot_name = robot.name;
    inputs_.emplace(next_input_++, std::move(in));
  };
  Input v{host.topic_name(r, "cmd_vel"), r, Input::Kind::velocity, msg::find_type("geometry_msgs/Twist"), {}};
  Input h{host.topic_name(r, "head/command"), r, Input::Kind::head, msg::find_type("std_msgs/Float64MultiArray"), {}};
  RS_DEMAND(v.type && h.type, "the serialiser lacks geometry_msgs/Twist or std_msgs/Float64MultiArray");
  add(std::move(v));
  add(std::move(h));
  if (has_commandable_joints(robot.spec)) {
    Input j{host.topic_name(r, "joint_command"), r, Input::Kind::joints, msg::find_type("sensor_msgs/JointState"), {}};
    RS_DEMAND(j.type, "the serialiser lacks sensor_msgs/JointState");
    add(std::move(j));
  }
  if (!robot.spec.flipper_joints.empty()) {
    add(Input{host.topic_name(r, "flippers/command"), r, Input::Kind::flippers, msg::find_type("std_msgs/Float64MultiArray"), {}});
  }
}

void Ros1Bridge::advertise(Output& o) {
  if (!o.type) return;
  ros::AdvertiseOptions ao(o.name, kRosPublishQueue, o.type->ros1_md5, o.type->ros1_name, o.type->ros1_definition);
  ao.latch = o.latched;
  ao.callback_queue = &callbacks_;
  o.pub = nh_->advertise(ao);
}

void Ros1Bridge::advertise_all() {
  for (Output& o : outputs_) advertise(o);
  for (auto& [key, in] : inputs_) subscribe(key, in);
}

void Ros1Bridge::on_layout() {
  try {
    follow_layout();
  } catch (const std::exception& e) {
    log::error("ROS 1: following the robots spawned or deleted: {}", e.what());
  }
}

void Ros1Bridge::follow_layout() {
  const Bus& bus = host_->bus();
  // publishers for the topics that appeared or came back (a latched one's message, published
  // before this call, goes out on it at once); none for those retired
  {
    std::lock_guard lock(outputs_mutex_);
    for (const Topic& t : bus.topics()) {
      const auto id = static_cast<std::size_t>(t.id);
      if (id >= outputs_.size()) {
        outputs_.push_back(make_output(t));
        outputs_.back().retired = true;  // advertised just below
        wanted_.emplace_back(false);
      }
      Output& o = outputs_[id];
      if (t.retired && !o.retired) {
        o.pub.shutdown();
        o.pub = ros::Publisher();
        o.retired = true;
        wanted_[id] = false;
        early_latched_.erase(id);
      } else if (!t.retired && o.retired) {
        advertise(o);
        o.retired = false;
        wanted_[id] = o.type && o.latched;
        const auto early = early_latched_.find(id);
        if (early != early_latched_.end()) {
          if (o.type) outbox_.push(t.id, host_->time(), early->second, 0);
          early_latched_.erase(early);
        }
      }
    }
  }
  // command subscriptions follow the robots by name: the gone lose theirs, those after them
  // move down an index, the new get theirs
  const World& world = host_->world();
  std::map<std::string, RobotIndex> index_of;
  for (RobotIndex r : world.robot_indices()) index_of[world.robot(r).name] = r;
  std::vector<ros::Subscriber> gone;
  std::vector<RobotIndex> added;
  {
    std::lock_guard lock(inputs_mutex_);
    std::set<std::string> served;
    for (auto it = inputs_.begin(); it != inputs_.end();) {
      Input& in = it->second;
      if (in.kind == Input::Kind::host) {
        ++it;
        continue;
      }
      const auto r = index_of.find(in.robot_name);
      if (r == index_of.end()) {
        gone.push_back(std::move(in.sub));
        it = inputs_.erase(it);
        continue;
      }
      in.robot = r->second;
      served.insert(in.robot_name);
      ++it;
    }
    const std::uint64_t first_new = next_input_;
    for (const auto& [name, r] : index_of) {
      if (served.count(name) == 0) added.push_back(r);
    }
    std::sort(added.begin(), added.end());
    for (const RobotIndex r : added) add_robot_inputs(world, r);
    for (auto it = inputs_.lower_bound(first_new); it != inputs_.end(); ++it) subscribe(it->first, it->second);
  }
  // outside the lock: roscpp waits for a callback of the subscription under way, which may be
  // waiting for the lock
  for (ros::Subscriber& s : gone) s.shutdown();
  // a spawned robot's description also goes to its parameter, as the scenario's do
  std::vector<std::string> unset;
  std::vector<std::pair<std::string, std::string>> set;
  {
    std::lock_guard lock(params_mutex_);
    for (auto it = spawned_params_.begin(); it != spawned_params_.end();) {
      if (index_of.count(it->first) == 0) {
        unset.push_back(it->second.first);
        it = spawned_params_.erase(it);
      } else {
        ++it;
      }
    }
    for (const RobotIndex r : added) {
      const RobotInstance& robot = world.robot(r);
      if (robot.spec.description.empty()) continue;
      set.emplace_back(host_->topic_name(r, "robot_description"), robot.spec.description);
      spawned_params_[robot.name] = set.back();
    }
  }
  for (const std::string& param : unset) ros::param::del(param);
  for (const auto& [param, description] : set) ros::param::set(param, description);
}

void Ros1Bridge::subscribe(std::uint64_t i, Input& in) {
  in.sub.shutdown();
  if (in.kind == Input::Kind::velocity) {
    // cmd_vel takes geometry_msgs/Twist or TwistStamped: MD5 and type "*" let publishers of any
    // type connect (rospy checks the type name too), and each message's connection header says
    // which type it is. roscpp then fixes the subscription's MD5 to its first publisher's:
    // check_input_publishers makes it afresh when publishers of the other type come
    using Helper = ros::SubscriptionCallbackHelperT<const ros::MessageEvent<const RawMessage>&>;
    ros::SubscribeOptions so(in.topic, kRosSubscribeQueue, "*", subscribed_type(in));
    so.helper = boost::make_shared<Helper>(
        [this, i](const ros::MessageEvent<const RawMessage>& e) { on_velocity(i, e.getConnectionHeader(), *e.getConstMessage()); });
    so.callback_queue = &callbacks_;
    in.sub = nh_->subscribe(so);
    in.unconnected_checks = 0;
    in.adopted = false;
    // roscpp registered the subscription as "*": name the classic type to the master too (which
    // keeps the last type it is told), so that `rostopic type` and tools that bridge topics by
    // type see geometry_msgs/Twist
    XmlRpc::XmlRpcValue args, result, payload;
    args[0] = ros::this_node::getName();
    args[1] = in.topic;
    args[2] = in.type->ros1_name;
    args[3] = ros::XMLRPCManager::instance()->getServerURI();
    ros::master::execute("registerSubscriber", args, result, payload, false);
    return;
  }
  // the subscription asks for the command type's MD5: roscpp refuses publishers of other types
  using Helper = ros::SubscriptionCallbackHelperT<const boost::shared_ptr<const RawMessage>&>;
  ros::SubscribeOptions so(in.topic, kRosSubscribeQueue, in.type->ros1_md5, in.type->ros1_name);
  so.helper = boost::make_shared<Helper>([this, i](const boost::shared_ptr<const RawMessage>& m) { on_command(i, *m); });
  so.callback_queue = &callbacks_;
  in.sub = nh_->subscribe(so);
  in.unconnected_checks = 0;
}

void Ros1Bridge::renew_subscriptions(const std::vector<std::uint64_t>& keys, bool keep_checks) {
  if (keys.empty()) return;
  std::vector<ros::Subscriber> old;
  {
    std::lock_guard lock(inputs_mutex_);
    for (const std::uint64_t key : keys) {
      const auto it = inputs_.find(key);
      if (it == inputs_.end()) continue;
      old.push_back(it->second.sub);
      it->second.sub = ros::Subscriber();
    }
  }
  for (ros::Subscriber& s : old) s.shutdown();
  std::lock_guard lock(inputs_mutex_);
  for (const std::uint64_t key : keys) {
    const auto it = inputs_.find(key);
    if (it == inputs_.end()) continue;
    const int checks = it->second.unconnected_checks;
    subscribe(key, it->second);
    if (keep_checks) it->second.unconnected_checks = checks;
  }
}

void Ros1Bridge::set_parameters() {
  if (options_.use_sim_time) ros::param::set("/use_sim_time", true);
  // robot_state_publisher and RViz's RobotModel read a robot's URDF from the parameter server
  // (the same text is on the latched robot_description topic)
  // (the scenario's robots come first and never move; spawned ones, which may be going while this
  // runs on the spinner thread, as the layout watcher recorded them)
  const BridgeHost& host = *host_;
  const World& world = host.world();
  for (RobotIndex r : world.robot_indices()) {
    const RobotInstance& robot = world.robot(r);
    if (robot.spawned) continue;
    if (!robot.spec.description.empty()) ros::param::set(host.topic_name(r, "robot_description"), robot.spec.description);
  }
  std::vector<std::pair<std::string, std::string>> spawned;
  {
    std::lock_guard lock(params_mutex_);
    for (const auto& [name, param] : spawned_params_) spawned.push_back(param);
  }
  for (const auto& [param, description] : spawned) ros::param::set(param, description);
}

bool Ros1Bridge::register_again() {
  // roscpp registers with the master only when it advertises or subscribes, and never again.
  // Telling a new master through its API what this node already publishes (rather than
  // re-advertising) keeps the connections subscribers made before the outage, and the latched
  // /tf_static, alive; new subscribers find the node through the new master.
  const std::string me = ros::this_node::getName();
  const std::string api = ros::XMLRPCManager::instance()->getServerURI();
  const auto call = [&](const char* method, const std::string& topic, const std::string& type, XmlRpc::XmlRpcValue& payload) {
    XmlRpc::XmlRpcValue args, result;
    args[0] = me;
    args[1] = topic;
    args[2] = type;
    args[3] = api;
    return ros::master::execute(method, args, result, payload, false);
  };
  XmlRpc::XmlRpcValue payload;
  {
    std::lock_guard lock(outputs_mutex_);
    for (const Output& o : outputs_) {
      if (o.type && !o.retired && !call("registerPublisher", o.name, o.type->ros1_name, payload)) return false;
    }
  }
  // roscpp's own log topic
  if (!call("registerPublisher", "/rosout", "rosgraph_msgs/Log", payload)) return false;
  std::vector<std::uint64_t> renew;
  {
    std::lock_guard lock(inputs_mutex_);
    for (auto& [key, in] : inputs_) {
      if (!call("registerSubscriber", in.topic, in.type->ros1_name, payload)) return false;
      // publishers that found the new master first are only named in this answer (the master
      // tells subscribers of later ones): subscribing anew connects to them
      bool others = false;
      for (int i = 0; payload.getType() == XmlRpc::XmlRpcValue::TypeArray && i < payload.size(); ++i) {
        if (std::string(payload[i]) != api) others = true;
      }
      if (others) renew.push_back(key);
    }
  }
  renew_subscriptions(renew, false);
  return !services_ || services_->register_again();
}

void Ros1Bridge::publish_loop() {
  std::vector<OutboxItem> round;
  for (;;) {
    round.clear();
    if (!outbox_.take_round(round, std::chrono::milliseconds(100))) {
      if (outbox_.drained()) return;
      continue;
    }
    // on stop, what is queued goes out up to a short deadline
    if (Clock::now().time_since_epoch().count() > drain_until_.load()) return;
    for (const OutboxItem& item : round) publish(item);
  }
}

void Ros1Bridge::publish(const OutboxItem& item) {
  const msg::Message& message = *item.message;
  // held while publishing: the layout watcher must not shut the publisher down meanwhile
  std::lock_guard lock(outputs_mutex_);
  if (static_cast<std::size_t>(item.topic) >= outputs_.size()) return;
  const Output& o = outputs_[static_cast<std::size_t>(item.topic)];
  if (!o.type) return;
  if (message.index() != o.type->variant_index) {
    if (mismatch_reported_.insert(item.topic).second) {
      log::error("ROS 1: a {} message on {} (declared {}): not published", msg::type_name(message), o.name, o.type->ros1_name);
    }
    return;
  }
  if (!o.pub || !ros::ok()) return;
  // nobody listening: nothing to serialise (latched topics keep their last message for latecomers)
  if (!o.latched && o.pub.getNumSubscribers() == 0) return;
  try {
    // serialised by roscpp's call, straight into its send buffer
    const ros1_wire::OutgoingMessage out{o.type, &message, item.seq - 1,  // Header.seq counts from 0
                                         static_cast<std::uint32_t>(msg::ros1_size(message))};
    o.pub.publish(out);
    ++sent_;
  } catch (const std::exception& e) {
    // a bug, not bad input: say it once per topic and keep the other topics going
    if (mismatch_reported_.insert(item.topic).second) log::error("ROS 1: {} not published: {}", o.name, e.what());
  }
}

void Ros1Bridge::spin_loop() {
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options_.master_check_period));
  auto next_check = Clock::now() + period;
  while (!stopping_.load()) {
    callbacks_.callAvailable(ros::WallDuration(0.05));
    refresh_wanted();
    if (Clock::now() >= next_check) {
      // an answer of an unexpected shape (XmlRpcValue throws on a wrong type) must not end the thread
      try {
        watch_master();
      } catch (const XmlRpc::XmlRpcException& e) {
        log::debug("ROS 1: unexpected answer from the master at {}: {}", endpoint_.master_uri, e.getMessage());
      } catch (const std::exception& e) {
        log::debug("ROS 1: checking the master at {}: {}", endpoint_.master_uri, e.what());
      }
      next_check = Clock::now() + period;
    }
  }
}

void Ros1Bridge::refresh_wanted() {
  // a topic nobody subscribes to costs the simulation thread nothing (not even a copy)
  std::lock_guard lock(outputs_mutex_);
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    const Output& o = outputs_[i];
    if (o.type && !o.latched && !o.retired) wanted_[i].store(o.pub.getNumSubscribers() > 0, std::memory_order_relaxed);
  }
}

void Ros1Bridge::watch_master() {
  if (!ros::ok()) {
    // the master told the node to shut down, usually because another node took its name
    if (!shutdown_reported_) {
      log::warn("ROS 1: roscpp shut the node {} down (did another node register under that name?); still simulating without ROS 1",
                options_.node_name);
      shutdown_reported_ = true;
    }
    return;
  }
  const std::optional<int> pid = master_pid();
  if (!pid) {
    if (connected_) {
      log::warn("ROS 1 master at {} lost; still simulating, retrying every {:g} s", endpoint_.master_uri, options_.master_check_period);
      connected_ = false;
    }
    return;
  }
  if (connected_ && *pid == master_pid_) {
    check_input_publishers();
    return;
  }
  // a master is back, or a new one answers at the same URI: it knows nothing of this node
  const bool restarted = connected_;
  const bool registered = register_again();
  if (registered) set_parameters();
  // gone again while registering: try again at the next check
  if (!registered || master_pid() != pid) {
    connected_ = false;
    return;
  }
  master_pid_ = *pid;
  connected_ = true;
  std::ptrdiff_t topics = 0;
  {
    std::lock_guard lock(outputs_mutex_);
    topics = std::count_if(outputs_.begin(), outputs_.end(), [](const Output& o) { return o.type != nullptr && !o.retired; });
  }
  std::size_t inputs = 0;
  {
    std::lock_guard lock(inputs_mutex_);
    inputs = inputs_.size();
  }
  log::warn("ROS 1 master at {} {}: reconnected; registered {} topics and {} command subscriptions again", endpoint_.master_uri,
            restarted ? "was restarted" : "is back", topics, inputs);
}

void Ros1Bridge::check_input_publishers() {
  // a publisher of another type on a command topic cannot connect (roscpp and rospy refuse the
  // md5 when connecting): compare the master's publishers of each command topic with those the
  // subscription is connected to, and say so once when some stay unconnected for two checks.
  // cmd_vel connects to either type, but to one at a time: see below
  XmlRpc::XmlRpcValue args, result, state, types;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", args, result, state, false)) return;
  if (state.getType() != XmlRpc::XmlRpcValue::TypeArray || state.size() < 1) return;
  XmlRpc::XmlRpcValue& publishers = state[0];
  std::map<std::string, std::string> registered_type;
  if (ros::master::execute("getTopicTypes", args, result, types, false) && types.getType() == XmlRpc::XmlRpcValue::TypeArray) {
    for (int i = 0; i < types.size(); ++i) registered_type[std::string(types[i][0])] = std::string(types[i][1]);
  }
  std::vector<std::uint64_t> renew;  // after the loop, without the lock (renew_subscriptions)
  std::unique_lock lock(inputs_mutex_);
  for (auto& [key, in] : inputs_) {
    std::vector<std::string> nodes;
    for (int i = 0; i < publishers.size(); ++i) {
      if (std::string(publishers[i][0]) != in.topic) continue;
      for (int j = 0; j < publishers[i][1].size(); ++j) {
        const std::string node = publishers[i][1][j];
        if (node != ros::this_node::getName()) nodes.push_back(node);
      }
    }
    const std::size_t connected = in.sub.getNumPublishers();
    const bool missing = connected < nodes.size();
    if (in.kind == Input::Kind::velocity) {
      // cmd_vel's subscription takes the type of the first publisher it connects to and keeps it
      // after that publisher is gone (roscpp keeps the MD5 it adopted), even when the connection
      // came and went between two checks. So with none connected it is made afresh: once when it
      // had connected (the next publisher of either type then connects at once), and at every
      // check while there are publishers it is not connected to (a publisher of the other type
      // may have been first and gone since; a retry is one registerSubscriber). The warning
      // below comes when they still do not connect after two checks.
      if (connected > 0) in.adopted = true;
      if (connected == 0 && (in.adopted || missing)) renew.push_back(key);
    }
    in.unconnected_checks = missing ? in.unconnected_checks + 1 : 0;
    if (in.unconnected_checks != 2) continue;  // new publishers take a moment to connect; warn once
    std::string list;
    for (const auto& n : nodes) list += (list.empty() ? "" : ", ") + n;
    const std::string type = registered_type.count(in.topic) ? registered_type[in.topic] : "";
    const bool velocity = in.kind == Input::Kind::velocity;
    const bool known = type == in.type->ros1_name || (velocity && (type == ros1_wire::kTwistStampedName || type == "*"));
    std::string why = fmt::format("a message type other than {}, or a host name rescuesim cannot reach", in.type->ros1_name);
    if (velocity) {
      why = connected > 0 ? fmt::format("ROS 1 gives a subscription one type at a time, and rescuesim takes {} from the other "
                                        "publisher(s): these connect when those are gone; or a host name rescuesim cannot reach",
                                        in.connected_type.empty() ? std::string("another type") : in.connected_type)
                          : std::string("a host name rescuesim cannot reach?");
    }
    log::warn("ROS 1: {} has {} publisher(s) ({}) but rescuesim is connected to {}{}: their messages do not arrive ({}); still simulating",
              in.topic, nodes.size(), list, connected,
              !type.empty() && !known ? fmt::format("; the master has the topic as {}", type) : std::string(), why);
  }
  lock.unlock();
  renew_subscriptions(renew, true);
}

void Ros1Bridge::on_command(std::uint64_t key, const RawMessage& raw) {
  // what the message is for, as of now (the layout watcher moves and removes inputs)
  Input in;
  {
    std::lock_guard lock(inputs_mutex_);
    const auto it = inputs_.find(key);
    if (it == inputs_.end()) return;  // its robot is gone
    in.topic = it->second.topic;
    in.robot = it->second.robot;
    in.kind = it->second.kind;
    in.type = it->second.type;
    in.host_input = it->second.host_input;
  }
  try {
    const msg::Message m = msg::from_ros1(*in.type, raw.bytes);
    switch (in.kind) {
      case Input::Kind::velocity: gate_->velocity(in.robot, in.topic, std::get<msg::Twist>(m)); break;
      case Input::Kind::head: gate_->head(in.robot, in.topic, std::get<msg::Float64MultiArray>(m).data); break;
      case Input::Kind::joints: gate_->joints(in.robot, in.topic, std::get<msg::JointState>(m)); break;
      case Input::Kind::flippers: gate_->flippers(in.robot, in.topic, std::get<msg::Float64MultiArray>(m).data); break;
      case Input::Kind::host: gate_->input(in.host_input, in.topic, m); break;
    }
  } catch (const std::exception& e) {
    gate_->malformed(in.topic, e.what());
  }
}

void Ros1Bridge::on_velocity(std::uint64_t key, const ros::M_string& connection, const RawMessage& raw) {
  const auto header = [&](const char* name) {
    const auto it = connection.find(name);
    return it == connection.end() ? std::string() : it->second;
  };
  // which of the two types this publisher sends, by its connection header
  const std::string connected_type = header("type");
  std::string topic;
  RobotIndex robot{0};
  {
    std::lock_guard lock(inputs_mutex_);
    const auto it = inputs_.find(key);
    if (it == inputs_.end()) return;  // its robot is gone
    Input& in = it->second;
    in.connected_type = connected_type;
    in.adopted = true;
    topic = in.topic;
    robot = in.robot;
  }
  std::string why;
  const std::optional<ros1_wire::VelocityType> type = ros1_wire::velocity_type(connected_type, header("md5sum"), &why);
  if (!type) return refuse(topic, "type", why);
  ros1_wire::VelocityCommand command;
  try {
    command = ros1_wire::decode_velocity(*type, raw.bytes);
  } catch (const std::exception& e) {
    return gate_->malformed(topic, e.what());
  }
  // a stamp ahead of the simulation (a publisher on wall-clock time, say) is refused; NaN and the
  // drive's limits are the gate's, as for every velocity command
  try {
    if (command.stamped) {
      gate_->velocity_stamped(robot, topic, command.stamp, SimTime{sim_now_ns_.load(std::memory_order_relaxed)}, command.twist);
      return;
    }
    gate_->velocity(robot, topic, command.twist);
  } catch (const std::out_of_range&) {
    // the robot went between the look-up above and the gate's (a deletion under way): dropped
  }
}

void Ros1Bridge::refuse(const std::string& topic, const char* kind, const std::string& why) {
  ++refused_;
  // worded and throttled as CommandGate's refusals (per topic and kind, one every 2 s)
  std::uint64_t held = 0;
  if (!throttles_.try_emplace(topic + "#" + kind).first->second.allow(&held)) return;
  if (held > 0) {
    log::warn("ROS 1: rejected a command on {}: {} ({} more like it since the last report)", topic, why, held);
  } else {
    log::warn("ROS 1: rejected a command on {}: {}", topic, why);
  }
}

void Ros1Bridge::stop() {
  if (!started_) return;
  // the Bus belongs to the simulation thread, which calls stop()
  host_->bus().unsubscribe(bus_handle_);
  host_->bus().unsubscribe(layout_handle_);
  shut_down();
}

void Ros1Bridge::shut_down() {
  if (!started_) return;
  started_ = false;
  drain_until_ = (Clock::now() + std::chrono::seconds(1)).time_since_epoch().count();
  outbox_.close();
  if (publisher_.joinable()) publisher_.join();
  stopping_ = true;
  if (spinner_.joinable()) spinner_.join();
  {
    std::lock_guard lock(outputs_mutex_);
    for (Output& o : outputs_) o.pub.shutdown();
  }
  std::vector<ros::Subscriber> subs;
  {
    std::lock_guard lock(inputs_mutex_);
    for (auto& [key, in] : inputs_) subs.push_back(in.sub);
  }
  for (ros::Subscriber& s : subs) s.shutdown();
  // calls in progress end with an error ("stopping") rather than wait for a simulation that stops
  if (services_) services_->stop();
  nh_.reset();
  // unregisters from the master (without waiting for one that is gone)
  ros::shutdown();
}

}  // namespace

std::unique_ptr<Bridge> make_ros1_bridge(const Ros1Options& options) { return std::make_unique<Ros1Bridge>(options); }

}  // namespace rescuesim
