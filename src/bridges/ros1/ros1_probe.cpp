// The bench's ROS 1 subscriber: a type-agnostic subscription (md5 "*", as rostopic's AnyMsg)
// whose deserialiser keeps only the leading header stamp.

#include "bridges/ros1/ros1_probe.h"

#include <ros/callback_queue.h>
#include <ros/init.h>
#include <ros/master.h>
#include <ros/message_traits.h>
#include <ros/node_handle.h>
#include <ros/serialization.h>
#include <ros/subscriber.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "bridges/ros1/ros1_console.h"
#include "bridges/ros1/ros1_endpoint.h"
#include "core/error.h"

namespace rescuesim::ros1_probe_wire {

/// The stamp of a stamped message: std_msgs/Header is `uint32 seq, time stamp (uint32 secs,
/// uint32 nsecs), string frame_id`, little endian, first in every stamped message.
struct StampOnly {
  bool has_stamp = false;
  std::int64_t stamp_ns = 0;
};

}  // namespace rescuesim::ros1_probe_wire

namespace ros::message_traits {

template <>
struct MD5Sum<rescuesim::ros1_probe_wire::StampOnly> {
  static const char* value() { return "*"; }
  static const char* value(const rescuesim::ros1_probe_wire::StampOnly&) { return "*"; }
};
template <>
struct DataType<rescuesim::ros1_probe_wire::StampOnly> {
  static const char* value() { return "*"; }
  static const char* value(const rescuesim::ros1_probe_wire::StampOnly&) { return "*"; }
};
template <>
struct Definition<rescuesim::ros1_probe_wire::StampOnly> {
  static const char* value() { return ""; }
  static const char* value(const rescuesim::ros1_probe_wire::StampOnly&) { return ""; }
};

}  // namespace ros::message_traits

namespace ros::serialization {

template <>
struct Serializer<rescuesim::ros1_probe_wire::StampOnly> {
  template <typename Stream>
  static void read(Stream& stream, rescuesim::ros1_probe_wire::StampOnly& m) {
    const std::uint32_t n = stream.getLength();
    const std::uint8_t* b = stream.getData();
    const auto u32 = [b](int at) {
      return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 | static_cast<std::uint32_t>(b[at + 2]) << 16 |
             static_cast<std::uint32_t>(b[at + 3]) << 24;
    };
    m.has_stamp = n >= 12;
    if (m.has_stamp) m.stamp_ns = static_cast<std::int64_t>(u32(4)) * 1000000000 + u32(8);
    stream.advance(n);
  }
};

}  // namespace ros::serialization

namespace rescuesim {

void run_ros1_probe(const std::string& node_name, const std::vector<std::string>& topics, const Ros1ProbeCallback& on_message,
                    const std::function<void()>& ready, const std::atomic<bool>& stop, double seconds) {
  using ros1_probe_wire::StampOnly;
  using Clock = std::chrono::steady_clock;
  const Ros1Endpoint endpoint = resolve_ros1_endpoint(std::getenv("ROS_MASTER_URI"), std::getenv("ROS_HOSTNAME"), std::getenv("ROS_IP"));
  route_rosconsole_to_log();
  ros::M_string remappings{{"__master", endpoint.master_uri}};
  if (!endpoint.hostname.empty()) remappings["__hostname"] = endpoint.hostname;
  ros::init(remappings, node_name, ros::init_options::NoSigintHandler | ros::init_options::AnonymousName);
  ros::master::setRetryTimeout(ros::WallDuration(1.0));
  // the master must answer first (roscpp would wait for it forever)
  const auto deadline = Clock::now() + std::chrono::seconds(5);
  while (!ros::master::check()) {
    if (Clock::now() >= deadline) throw Error("ROS 1 probe: no master at " + endpoint.master_uri + " (ROS_MASTER_URI)");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ros::start();
  {
    ros::NodeHandle nh;
    ros::CallbackQueue queue;
    std::vector<ros::Subscriber> subs;
    using Helper = ros::SubscriptionCallbackHelperT<const boost::shared_ptr<const StampOnly>&>;
    for (std::size_t i = 0; i < topics.size(); ++i) {
      ros::SubscribeOptions so(topics[i], 10, "*", "*");
      so.helper = boost::make_shared<Helper>([&on_message, i](const boost::shared_ptr<const StampOnly>& m) {
        if (m->has_stamp) on_message(i, m->stamp_ns);
      });
      so.callback_queue = &queue;
      // no Nagle delay on the TCP connection, as latency-minded subscribers ask
      so.transport_hints = ros::TransportHints().tcpNoDelay();
      subs.push_back(nh.subscribe(so));
    }
    if (ready) ready();
    // callbacks run here, as soon as each message has arrived
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    while (!stop && Clock::now() < end && ros::ok()) queue.callAvailable(ros::WallDuration(0.01));
    for (auto& s : subs) s.shutdown();
  }
  ros::shutdown();
}

}  // namespace rescuesim
