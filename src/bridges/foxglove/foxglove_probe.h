#pragma once
/// A bare Foxglove WebSocket client for `rescuesim bench`: it connects to a bridge's server,
/// subscribes to the channels of the topics asked for and reports the header stamp of every
/// message it receives, so the bench can time sim → client delivery as it does for ROS 1 and
/// ROS 2. It reads only the stamp: the `cdr` payload's 4-byte encapsulation header, then the
/// std_msgs/Header's int32 sec and uint32 nanosec that lead every stamped message. Tests use
/// the reference client (@foxglove/ws-protocol); the bench is an installed tool and has only
/// what rescuesim links (Boost.Beast, as the server).

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace rescuesim {

/// Called on the probe's thread for each message: the index of its topic in the list given to
/// run_foxglove_probe and its header stamp (ns of sim time).
using FoxgloveProbeCallback = std::function<void(std::size_t topic, std::int64_t stamp_ns)>;

/// Connects to ws://`host`:`port` (subprotocol foxglove.websocket.v1), retrying for up to 10 s
/// (or `seconds`, if shorter) while nothing listens there yet, subscribes to every advertised channel whose topic is in
/// `topics` (also those advertised later), calls `ready` once every topic is subscribed and
/// `on_message` per message until `stop` is set, the server closes, or `seconds` of wall time
/// pass. Throws rescuesim::Error when it cannot connect.
void run_foxglove_probe(const std::string& host, int port, const std::vector<std::string>& topics,
                        const FoxgloveProbeCallback& on_message, const std::function<void()>& ready, const std::atomic<bool>& stop,
                        double seconds);

}  // namespace rescuesim
