#pragma once
/// The Foxglove bridge: a WebSocket server speaking the Foxglove WebSocket protocol
/// (subprotocol `foxglove.websocket.v1`), so Foxglove and Lichtblick connect to a running
/// simulation at ws://localhost:8765. Every Bus topic is advertised as a `cdr` channel with its
/// ROS 2 `ros2msg` schema, plus a `foxglove.SceneUpdate` topic (`/scene`, json) drawing the
/// world; clients subscribe per channel, get sim-time `time` messages, and may publish
/// `/cmd_vel`, `/head/command` and `/joint_command` (cdr or json) to drive the robots. See
/// docs/foxglove.md.
///
/// Slow clients never slow the simulation or grow memory without bound: each client has a
/// byte- and count-bounded send queue that drops its oldest data first (counted, and reported
/// to that client with a `status` warning).

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
  std::size_t bridge_queue = 256;           ///< messages between the simulation and the serialiser thread
  std::size_t bridge_queue_bytes = 32 << 20;  ///< bytes of message copies waiting for the serialiser thread
};

/// The bridge; throws rescuesim::Error on start() when the port cannot be bound.
std::unique_ptr<Bridge> make_foxglove_bridge(const FoxgloveOptions& options = {});

}  // namespace rescuesim
