#pragma once
/// Internal to the Foxglove bridge: its class and the state shared by its three threads, split
/// over foxglove_bridge.cpp (start and stop, what the simulation thread hands over, the
/// serialiser thread that encodes and fans messages out), client_requests.cpp (what clients
/// ask for on the I/O thread: subscriptions, client channels, commands) and service_calls.cpp
/// (the Simulation Interfaces services: calls handed to the simulation thread through
/// SimControl::post, answers handed back to the I/O thread through WsServer::post).
///
/// Simulation thread -> serialiser thread: Bus messages go through the Outbox the ROS 1 and ROS 2
/// bridges use (bridges/common/outbox.h: a bounded queue per topic, so a burst on one topic never
/// pushes out an image or a latched message, and a byte budget over all of them); the scene is
/// no Bus message: only its newest snapshot waits (`pending_scene_`), an older one is replaced.
///
/// Robots spawned and deleted while running: a Bus layout watcher (on_layout, on the simulation
/// thread) announces the channels of new topics, unadvertises those of retired topics (ending
/// every subscription to them), rebuilds the per-robot command topics and points each client
/// channel at its robot's index now (none: a deleted robot's, refused until one of that name
/// is back).
///
/// Locking: `mutex_` guards channels, clients and the per-robot command topics; it may be held
/// while queueing frames on the server (whose own locks are inner), never the other way round.
/// `scene_mutex_` and the outbox's lock are leaves. A ServiceLink's mutex is held while posting a task to the server
/// (whose locks are inner), and never with `mutex_`.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "bridges/common/commands.h"
#include "bridges/common/outbox.h"
#include "bridges/foxglove/foxglove_bridge.h"
#include "bridges/foxglove/protocol.h"
#include "bridges/foxglove/scene.h"
#include "bridges/foxglove/sim_services.h"
#include "bridges/foxglove/ws_server.h"
#include "core/throttle.h"
#include "bus/bridge_host.h"
#include "bus/bus.h"
#include "msgs/serialize.h"

namespace rescuesim {
class BridgeHost;
}  // namespace rescuesim

namespace rescuesim::foxglove {

/// Bus topics the simulation thread can check without a lock (more are always forwarded).
constexpr std::size_t kMaxTopics = 4096;
/// The scene channel's id; Bus topic t is channel t + 2.
constexpr std::uint32_t kSceneChannel = 1;
constexpr std::uint32_t channel_of(TopicId topic) { return static_cast<std::uint32_t>(topic) + 2; }

/// A scene snapshot waiting for the serialiser thread.
struct PendingScene {
  SimTime at;        ///< sim time when it was taken
  SceneState scene;
};

/// A server channel with who subscribes to it.
struct ChannelState {
  Channel channel;
  TopicId topic = kNoTopic;                        ///< Bus topic, kNoTopic for the scene
  bool latched = false;
  Payload last;                                    ///< latched channels: the message a new subscriber gets
  std::uint64_t last_stamp = 0;
  std::map<ClientId, std::uint32_t> subscribers;   ///< client -> its subscription id
};

/// What a client channel publishes to.
struct CommandTarget {
  /// cmd_vel, head/command, joint_command, flippers/command, BridgeHost::inputs()
  enum class Kind { twist, head, joints, flippers, host };
  Kind kind = Kind::twist;
  RobotIndex robot{0};                      ///< invalid: none (no target, a host input of no robot, or the robot was deleted)
  std::size_t host_input = 0;               ///< Kind::host: the index in BridgeHost::inputs()
  const msg::TypeSupport* type = nullptr;   ///< Kind::host: the input's message type
  ClientChannel channel;
};

/// The answer to a service call, on its way back to the I/O thread.
struct CallAnswer {
  ClientId client = 0;
  std::uint32_t service = 0, call = 0;
  std::optional<SimResponse> response;  ///< the response, or none: a serviceCallFailure
  std::string failure;                  ///< why, when there is no response
};

/// Shared between the bridge and the service calls SimControl holds (which may run, or be
/// destroyed unrun, after the bridge stopped): while the bridge runs, its server and the
/// function that sends an answer (on the I/O thread); both empty once it stopped, so a late
/// answer reaches nobody.
struct ServiceLink {
  std::mutex mutex;
  WsServer* server = nullptr;
  std::function<void(CallAnswer)> finish;
};

/// Service calls one client may have waiting on the simulation at once; more are refused.
constexpr std::size_t kMaxCallsInFlight = 32;

/// One connected client.
struct ClientState {
  std::map<std::uint32_t, std::uint32_t> subscriptions;  ///< subscription id -> channel id
  std::map<std::uint32_t, CommandTarget> publishers;     ///< client channel id -> target
  std::size_t calls_in_flight = 0;                       ///< service calls handed to the simulation, not answered yet
  std::uint64_t dropped = 0;
  std::unique_ptr<Throttle> drop_warning = std::make_unique<Throttle>(std::chrono::seconds(2));
};

/// The bridge: a Bridge to the simulation, a ServerHandler to the WebSocket server.
class FoxgloveBridge final : public Bridge, private ServerHandler {
 public:
  explicit FoxgloveBridge(const FoxgloveOptions& options)
      : options_(options),
        outbox_(
            {.per_topic = std::max<std::size_t>(options.bridge_queue, 1), .byte_budget = options.bridge_queue_bytes, .lossless = false}) {}
  ~FoxgloveBridge() override { stop(); }

  std::string name() const override { return "foxglove"; }
  void start(BridgeHost& host) override;
  void stop() override;
  BridgeStats stats() const override;

  /// For tests: returns once the serialiser thread is between rounds, and keeps it there (taking
  /// nothing from the outbox, sending nothing) until resume_serialiser(), so what the simulation
  /// thread pushes meanwhile stays queued under the outbox's policy. Call after start().
  void pause_serialiser();
  void resume_serialiser();

 private:
  // simulation thread
  void on_bus(const Topic& topic, const Bus::SharedMessage& m);
  /// Adds a Bus topic's channel (call with mutex_ held, or before the threads start).
  void add_topic(const Topic& t, std::vector<Channel>* added);
  /// Channels for topics advertised since the last call and for retired topics advertised
  /// again (with mutex_ held).
  void add_new_topics(std::vector<Channel>* added);
  /// The Bus layout changed (robots spawned or deleted): see the file comment.
  void on_layout();
  /// The per-robot command topics of `world` (with mutex_ held, or before the threads start).
  void set_command_topics(const World& world);
  /// The per-robot command topics of the host's world now, and every client channel's robot
  /// index by its topic's name (with mutex_ held).
  void refresh_commands();
  SceneState scene_state() const;
  // serialiser thread
  void run();
  void handle(const OutboxItem& item);
  void handle_scene(PendingScene& pending);
  void wait_while_paused();
  void broadcast_time(std::int64_t ns);
  void deliver(const std::vector<std::pair<ClientId, std::uint32_t>>& subscribers, std::uint64_t stamp, const Payload& payload);
  void note_drops(ClientId client, std::size_t n);
  // I/O thread (ServerHandler)
  void on_open(ClientId client, const std::string& remote) override;
  void on_text(ClientId client, std::string_view text) override;
  void on_binary(ClientId client, std::span<const std::uint8_t> bytes) override;
  void on_oversize(ClientId client, std::size_t size, bool text) override;
  void on_close(ClientId client) override;
  void subscribe(ClientId client, const Subscribe& s);
  void unsubscribe(ClientId client, const Unsubscribe& u);
  void client_advertise(ClientId client, const ClientAdvertise& a);
  void client_unadvertise(ClientId client, const ClientUnadvertise& u);
  /// The robot command topic `topic` is (cmd_vel, head/command, ...): sets target.kind and
  /// target.robot and returns true, or false when no robot takes it now (with mutex_ held).
  bool robot_command(const std::string& topic, CommandTarget& target) const;
  void apply(ClientId client, const CommandTarget& target, std::span<const std::uint8_t> payload);
  void reply(ClientId client, StatusLevel level, const std::string& message);
  void reject(ClientId client, const std::string& message);
  /// The topics robot `robot` takes (commands and its host inputs), with their types, for status errors.
  std::string accepted_topics(RobotIndex robot) const;
  /// Every topic a client may publish on, with its type.
  std::string accepted_topics() const;
  // I/O thread: service calls (service_calls.cpp)
  void service_call(ClientId client, const ServiceCallRequest& request);
  /// Answers a call with a serviceCallFailure naming the problem, and counts it as rejected.
  void fail_call(ClientId client, std::uint32_t service, std::uint32_t call, const std::string& message);
  /// Sends an answer that came back from the simulation, if its client is still connected.
  void finish_call(CallAnswer answer);

  FoxgloveOptions options_;
  BridgeHost* host_ = nullptr;
  bool started_ = false, stopped_ = false;
  SubscriptionId bus_handle_ = kNoSubscription;
  SubscriptionId layout_handle_ = kNoSubscription;  ///< Bus::watch_layout
  TopicId clock_topic_ = kNoTopic;
  std::unique_ptr<WsServer> server_;
  std::string server_info_;
  std::vector<std::string> capabilities_;  ///< as in server_info_
  control::SimControl* control_ = nullptr;  ///< the host's; null: no services
  std::string services_advertisement_;      ///< advertiseServices, sent on connect when control_ is set
  std::shared_ptr<ServiceLink> link_ = std::make_shared<ServiceLink>();

  // simulation thread
  std::size_t known_topics_ = 0;
  std::set<TopicId> gone_;  ///< retired topics whose channel was unadvertised (a channel again once advertised again)
  SimTime next_scene_;
  SimTime scene_period_;
  std::unique_ptr<std::atomic<int>[]> wanted_{new std::atomic<int>[kMaxTopics]()};  ///< subscriptions per Bus topic
  std::atomic<std::int64_t> latest_time_{-1};

  // simulation thread -> serialiser thread
  Outbox outbox_;                              ///< Bus messages (per topic bridge_queue, bridge_queue_bytes over all)
  std::mutex scene_mutex_;
  std::optional<PendingScene> pending_scene_;  ///< the newest scene snapshot not yet handled

  // serialiser thread
  std::thread worker_;
  std::unique_ptr<SceneBuilder> scene_;
  SceneState last_scene_;  ///< what the scene's latched message shows

  // shared between the serialiser and I/O threads
  mutable std::mutex mutex_;
  std::map<std::uint32_t, ChannelState> channels_;
  std::map<ClientId, ClientState> clients_;

  // per robot now (rebuilt when the layout changes), under mutex_
  IndexedVector<RobotTag, std::string> twist_topics_, head_topics_, joint_topics_, flipper_topics_;
  IndexedVector<RobotTag, std::size_t> flipper_sizes_;
  IndexedVector<RobotTag, std::size_t> head_sizes_;
  IndexedVector<RobotTag, bool> joints_commandable_;  ///< per robot: has joints that joint_command may drive
  std::vector<HostInput> host_inputs_;    ///< what the host takes beyond commands (a mission's reports, datagrams, maps)
  std::atomic<std::uint64_t> received_{0}, rejected_{0};
  std::unique_ptr<CommandGate> gate_;  ///< checks client commands, hands them to the host, warns (as ROS 1 and 2 do)
  Throttle client_log_{std::chrono::seconds(5)};
  Throttle error_log_{std::chrono::seconds(5)};

  // pause_serialiser (tests)
  std::atomic<bool> pause_requested_{false};
  std::mutex pause_mutex_;
  std::condition_variable pause_cv_;
  bool paused_ = false;
};

}  // namespace rescuesim::foxglove
