#pragma once
/// Bridges: transports attached to a BridgeHost's Bus (ROS 1, ROS 2, Foxglove, MCAP; in
/// src/bridges/<name>). The host is a running Simulation or a replay (bus/bridge_host.h). A
/// bridge subscribes on the publishing thread (Bus::subscribe_shared), queues each message it
/// wants, shared and uncopied, in bounded queues (bridges/common/outbox.h for ROS 1, ROS 2
/// and Foxglove; the MCAP recorder keeps one FIFO so that a recording's order is the publish
/// order; cheap, never blocks unless the bridge is lossless), and serialises and sends from its
/// own thread. Commands it receives are checked by the gate the bridges share
/// (bridges/common/commands.h) and handed to the host's command_velocity / command_head /
/// command_joints, which queue them for the next step boundary.
/// A slow network or subscriber therefore never slows the simulation: when a queue is full the
/// oldest message is dropped and counted.

#include <cstdint>
#include <string>

namespace rescuesim {

class BridgeHost;

/// What a bridge did, for summaries and benches.
struct BridgeStats {
  std::uint64_t sent = 0;         ///< messages handed to the transport
  std::uint64_t dropped = 0;      ///< messages dropped because a queue was full
  std::uint64_t received = 0;     ///< commands received and accepted
  std::uint64_t rejected = 0;     ///< commands refused (malformed, non-finite, wrong size)
};

class Bridge {
 public:
  virtual ~Bridge() = default;
  /// "ros1", "ros2", "foxglove", "mcap".
  virtual std::string name() const = 0;
  /// Subscribes to the host's Bus and starts the bridge's thread(s). Call before the first step
  /// (so latched topics such as /tf_static are seen) and from the thread that steps. The host
  /// must outlive the bridge's stop(). Throws rescuesim::Error when the transport cannot start
  /// (the message says why).
  virtual void start(BridgeHost& host) = 0;
  /// Sends what is queued (up to a short deadline), unsubscribes and joins the threads.
  virtual void stop() = 0;
  virtual BridgeStats stats() const = 0;
};

}  // namespace rescuesim
