#pragma once
/// The in-process message bus: named, typed topics; subscribers are called synchronously, in
/// the order they subscribed, on the thread that publishes (the simulation thread). Bridges
/// subscribe and hand messages to their own threads; nothing here blocks on them.
///
/// Subscribing and advertising are for set-up time (before a run starts, or from the
/// simulation thread between publishes); publishing is for the simulation thread only. Like
/// Box2D's locked world, the Bus is locked while it delivers: subscribe, subscribe_shared,
/// unsubscribe and advertise called from inside a subscriber callback (including the latched
/// replay that subscribe itself makes) are bugs and abort with a message (RS_DEMAND), because
/// they would change the lists being walked. A callback may publish (nested delivery is fine).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "bus/topic_id.h"  // TopicId, kNoTopic
#include "core/index.h"    // RobotIndex
#include "msgs/messages.h"

namespace rescuesim {

/// A subscription's handle, from Bus::subscribe, for Bus::unsubscribe. Handles start at 1.
enum class SubscriptionId : int {};
/// No subscription (a bridge not yet started).
inline constexpr SubscriptionId kNoSubscription{0};

/// A topic's description.
struct Topic {
  TopicId id = kNoTopic;
  std::string name;        ///< absolute, e.g. "/scan" or "/robot2/scan"
  std::string type;        ///< ROS 1 type name, e.g. "sensor_msgs/LaserScan"
  double rate = 0;         ///< nominal rate (Hz), 0 when irregular
  bool latched = false;    ///< late subscribers get the last message (like /tf_static)
  RobotIndex robot;        ///< the robot it belongs to; invalid for global topics
  /// Gone: its robot was deleted while running (DeleteEntity, a reset that removes spawned
  /// robots). The id stays valid and nothing is published on it; bridges drop its writers.
  /// Advertising the name again brings it back.
  bool retired = false;
};

class Bus {
 public:
  using Callback = std::function<void(const Topic&, const msg::Message&)>;
  /// A published message, shared and immutable: what bridges keep for their own threads
  /// instead of copying (an image is hundreds of kB).
  using SharedMessage = std::shared_ptr<const msg::Message>;
  using SharedCallback = std::function<void(const Topic&, const SharedMessage&)>;

  /// Declares a topic (or returns the existing one of that name; the type must match, else
  /// throws Error naming the topic). Not from a subscriber callback.
  TopicId advertise(const std::string& name, const std::string& type, double rate = 0, bool latched = false, RobotIndex robot = {});
  /// Delivers a message to the topic's subscribers, in subscription order. `topic` must be
  /// one this Bus advertised.
  void publish(TopicId topic, msg::Message message);
  /// Subscribes to one topic by name, or to every topic with name "". A latched topic's last
  /// message is delivered at once. Returns a handle for unsubscribe. Not from a subscriber callback.
  SubscriptionId subscribe(const std::string& name, Callback callback);
  /// As subscribe, but the callback gets the message itself, shared, to keep without a copy.
  /// Subscribers of both kinds are called in subscription order.
  SubscriptionId subscribe_shared(const std::string& name, SharedCallback callback);
  /// Ends a subscription (an unknown or already ended handle: nothing happens). Not from a
  /// subscriber callback.
  void unsubscribe(SubscriptionId handle);

  /// Retires a topic (Topic::retired): its latched message is dropped. Not from a subscriber callback.
  void retire(TopicId topic);
  /// Called on the owner's thread each time the owner says the layout changed (topics
  /// advertised or retired, robots added or removed while running: layout_changed()). Bridges
  /// watch it to make writers and command readers for what appeared and drop what went,
  /// without waiting for the next message. Returns a handle for unsubscribe.
  SubscriptionId watch_layout(std::function<void()> callback);
  /// The owner (Simulation) says the layout changed: bumps layout_version() and calls the
  /// watchers, in the order they watched. Not from a subscriber callback.
  void layout_changed();
  /// How many times the layout changed.
  std::uint64_t layout_version() const { return layout_version_; }

  const std::vector<Topic>& topics() const { return topics_; }
  /// The topic of that id (which must be valid).
  const Topic& topic(TopicId id) const;
  /// The id of a topic, or kNoTopic.
  TopicId find(const std::string& name) const;
  /// Messages published on a topic so far.
  std::uint64_t count(TopicId topic) const;

 private:
  struct Subscriber {
    SubscriptionId handle;
    std::string name;
    std::variant<Callback, SharedCallback> callback;
  };
  SubscriptionId add(const std::string& name, std::variant<Callback, SharedCallback> callback);
  void deliver_latched(const Subscriber& s);
  void demand_unlocked(const char* function) const;
  std::size_t index(TopicId topic, const char* function) const;
  void rebuild_index();

  std::vector<Topic> topics_;
  std::vector<std::uint64_t> counts_;
  std::vector<std::vector<std::size_t>> subscribers_of_;  ///< per topic: indices into subscribers_
  std::vector<Subscriber> subscribers_;
  std::vector<int> shared_subscribers_;           ///< per topic: how many take SharedMessage
  std::vector<SharedMessage> latched_;            ///< per topic: the last message of a latched one
  std::vector<std::pair<SubscriptionId, std::function<void()>>> layout_watchers_;
  std::uint64_t layout_version_ = 0;
  int next_handle_ = 1;
  int delivering_ = 0;                            ///< depth of deliveries under way (> 0: locked)
};

}  // namespace rescuesim
