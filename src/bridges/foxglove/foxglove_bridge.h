#pragma once
/// The Foxglove bridge: a WebSocket server speaking the Foxglove WebSocket protocol
/// (subprotocol `foxglove.websocket.v1`), so Foxglove and Lichtblick connect to a running
/// simulation at ws://localhost:8765. Every Bus topic is advertised as a `cdr` channel with its
/// ROS 2 `ros2msg` schema, plus a `foxglove.SceneUpdate` topic (`/scene`, json) drawing the
/// world; clients subscribe per channel, get sim-time `time` messages, and may publish
/// `/cmd_vel`, `/head/command` and `/joint_command` (cdr or json) to drive the robots. See
/// docs/foxglove.md.
///
/// Neither a slow bridge nor slow clients slow the simulation or grow memory without bound. The
/// simulation thread queues the messages some client subscribed to (and latched ones) for the
/// serialiser thread in the Outbox the ROS 1 and ROS 2 bridges use (bridges/common/outbox.h):
/// `bridge_queue` messages per topic, so a burst on one topic only pushes out older messages of
/// that topic, never an image or a latched message waiting on another, and `bridge_queue_bytes`
/// over all topics (latched messages are not refused by it). Of the scene only the newest
/// snapshot waits. Each client then has a byte- and count-bounded send queue that drops its
/// oldest data first (reported to that client with a `status` warning). Both kinds of drop are
/// counted in BridgeStats::dropped.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "bus/bridge.h"

namespace rescuesim {

/// Settings of the Foxglove WebSocket server.
struct FoxgloveOptions {
  std::string host = "127.0.0.1";           ///< interface to listen on ("0.0.0.0" for every one)
  int port = 8765;                          ///< TCP port; 0 picks a free one (logged at info level)
  std::string scene_topic = "/scene";       ///< the foxglove.SceneUpdate topic; "" for none
  double scene_rate = 2.0;                  ///< Hz: how often moving parts of the scene (rubble, victims found) are checked
  std::size_t max_clients = 16;             ///< further connections are refused (HTTP 503)
  std::size_t max_client_frame = 1 << 20;   ///< bytes: larger client messages are discarded with a status error
  std::size_t client_queue_bytes = 8 << 20; ///< bytes of data queued per client before the oldest is dropped
  std::size_t client_queue_messages = 512;  ///< data messages queued per client before the oldest is dropped
  /// per topic: messages waiting for the serialiser thread before the topic's oldest is dropped
  /// (as ROS 1/2 queue_size)
  std::size_t bridge_queue = 64;
  /// bytes (Outbox::approx_bytes) waiting for the serialiser thread over all topics; 0: no budget
  std::size_t bridge_queue_bytes = 32 << 20;
};

/// The bridge; throws rescuesim::Error on start() when the port cannot be bound.
std::unique_ptr<Bridge> make_foxglove_bridge(const FoxgloveOptions& options = {});

}  // namespace rescuesim
