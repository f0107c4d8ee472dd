#pragma once
/// A small WebSocket server for the Foxglove bridge (Boost.Beast inside ws_server.cpp; no
/// Boost type leaves that file). One I/O thread accepts connections, performs the handshake
/// (refusing any client that does not offer the required subprotocol), reads client messages
/// and writes queued frames. Any thread may queue frames, and hand the I/O thread a task
/// (post); each client's queue is bounded:
///   - control frames (server info, advertisements) are always kept;
///   - status frames are kept up to a count, further ones are dropped;
///   - reply frames (binary answers to a client's requests) are kept up to a count, in order
///     with the control and status frames;
///   - data frames are dropped oldest-first beyond a byte and a count budget;
///   - a time frame replaces the previous unsent one (only the latest time matters).
/// Callbacks run on the I/O thread and must not block for long; the server calls them without
/// holding its own locks, so they may queue frames.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rescuesim::foxglove {

/// Identifies a connection for its lifetime (never reused within a server).
using ClientId = std::uint64_t;
/// A message body shared by every client it is sent to.
using Payload = std::shared_ptr<const std::vector<std::uint8_t>>;

/// Limits of the server.
struct ServerLimits {
  std::size_t max_clients = 16;
  std::size_t max_frame = 1 << 20;         ///< bytes of one client message; larger ones are discarded
  std::size_t queue_bytes = 8 << 20;       ///< data bytes queued per client
  std::size_t queue_messages = 512;        ///< data frames queued per client
  std::size_t status_messages = 64;        ///< status frames queued per client
  std::size_t reply_messages = 256;        ///< reply frames queued per client
};

/// What happens on the connections; called on the I/O thread.
class ServerHandler {
 public:
  virtual ~ServerHandler() = default;
  /// A client completed the handshake.
  virtual void on_open(ClientId client, const std::string& remote) = 0;
  /// A complete text message.
  virtual void on_text(ClientId client, std::string_view text) = 0;
  /// A complete binary message.
  virtual void on_binary(ClientId client, std::span<const std::uint8_t> bytes) = 0;
  /// A message over ServerLimits::max_frame was received and discarded (`size` bytes).
  virtual void on_oversize(ClientId client, std::size_t size, bool text) = 0;
  /// The connection is gone (closed by either side or failed).
  virtual void on_close(ClientId client) = 0;
};

/// Per-client counters.
struct ClientCounters {
  std::uint64_t sent = 0;      ///< data frames written to the socket
  std::uint64_t dropped = 0;   ///< data frames dropped from the queue
};

class WsServer {
 public:
  virtual ~WsServer() = default;

  /// Listens on host:port (0: any free port) for clients offering `subprotocol`, and starts the
  /// I/O thread. Throws rescuesim::Error when the address cannot be bound.
  static std::unique_ptr<WsServer> start(const std::string& host, int port, const std::string& subprotocol,
                                         const ServerLimits& limits, ServerHandler& handler);

  /// The port actually bound.
  virtual int port() const = 0;
  /// Queues a text frame that is never dropped (keep these few and small).
  virtual void send_control(ClientId client, std::string text) = 0;
  /// Queues a text status frame; dropped when the client already has too many queued.
  virtual void send_status(ClientId client, std::string text) = 0;
  /// Queues a binary reply frame (a service call response), kept in order with the control and
  /// status frames; dropped when the client already has too many queued (it reads none).
  virtual void send_reply(ClientId client, std::vector<std::uint8_t> frame) = 0;
  /// Runs `task` on the I/O thread (after what it is doing now). A task posted after shutdown()
  /// began may never run; it is then destroyed with the server.
  virtual void post(std::function<void()> task) = 0;
  /// Queues a binary data frame `head` + `body`; returns how many older data frames were
  /// dropped to make room (0 normally). Unknown clients are ignored.
  virtual std::size_t send_data(ClientId client, std::vector<std::uint8_t> head, Payload body) = 0;
  /// Sets the binary time frame to send next (replacing one not yet sent).
  virtual void send_time(ClientId client, std::vector<std::uint8_t> frame) = 0;
  /// Counters of a client (zero for unknown ones).
  virtual ClientCounters counters(ClientId client) const = 0;
  /// Totals over every client so far, gone ones included.
  virtual ClientCounters totals() const = 0;
  /// Waits up to `flush` for queues to drain, closes every connection and joins the thread.
  virtual void shutdown(std::chrono::milliseconds flush) = 0;
};

}  // namespace rescuesim::foxglove
