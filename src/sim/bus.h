#pragma once
/// The in-process message bus: named, typed topics; subscribers are called synchronously, in
/// the order they subscribed, on the thread that publishes (the simulation thread). Bridges
/// subscribe and hand messages to their own threads; nothing here blocks on them.
///
/// Subscribing and advertising are for set-up time (before a run starts, or from the
/// simulation thread); publishing is for the simulation thread only.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "msgs/messages.h"

namespace rescuesim {

/// A topic's description.
struct Topic {
  int id = -1;
  std::string name;        ///< absolute, e.g. "/scan" or "/robot2/scan"
  std::string type;        ///< ROS 1 type name, e.g. "sensor_msgs/LaserScan"
  double rate = 0;         ///< nominal rate (Hz), 0 when irregular
  bool latched = false;    ///< late subscribers get the last message (like /tf_static)
  int robot = -1;          ///< the robot it belongs to, -1 for global topics
};

class Bus {
 public:
  using Callback = std::function<void(const Topic&, const msg::Message&)>;
  /// A published message, shared and immutable: what bridges keep for their own threads
  /// instead of copying (an image is hundreds of kB).
  using SharedMessage = std::shared_ptr<const msg::Message>;
  using SharedCallback = std::function<void(const Topic&, const SharedMessage&)>;

  /// Declares a topic (or returns the existing one of that name; the type must match).
  int advertise(const std::string& name, const std::string& type, double rate = 0, bool latched = false, int robot = -1);
  /// Delivers a message to the topic's subscribers, in subscription order.
  void publish(int topic, msg::Message message);
  /// Subscribes to one topic by name, or to every topic with name "". A latched topic's last
  /// message is delivered at once. Returns a handle for unsubscribe.
  int subscribe(const std::string& name, Callback callback);
  /// As subscribe, but the callback gets the message itself, shared, to keep without a copy.
  /// Subscribers of both kinds are called in subscription order.
  int subscribe_shared(const std::string& name, SharedCallback callback);
  void unsubscribe(int handle);

  const std::vector<Topic>& topics() const { return topics_; }
  /// The id of a topic, or -1.
  int find(const std::string& name) const;
  /// Messages published on a topic so far.
  std::uint64_t count(int topic) const { return counts_[static_cast<std::size_t>(topic)]; }

 private:
  struct Subscriber {
    int handle;
    std::string name;
    Callback callback;        ///< one of the two is set
    SharedCallback shared;
  };
  void deliver_latched(Subscriber& s);
  std::vector<Topic> topics_;
  std::vector<std::uint64_t> counts_;
  std::vector<std::vector<int>> subscribers_of_;  ///< per topic: indices into subscribers_
  std::vector<Subscriber> subscribers_;
  std::vector<int> shared_subscribers_;           ///< per topic: how many take SharedMessage
  std::vector<SharedMessage> latched_;            ///< per topic: the last message of a latched one
  int next_handle_ = 1;

  void rebuild_index();
};

}  // namespace rescuesim
