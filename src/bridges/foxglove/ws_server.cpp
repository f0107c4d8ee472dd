#include "bridges/foxglove/ws_server.h"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <array>
#include <atomic>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include "core/error.h"
#include "core/log.h"
#include "core/thread.h"

namespace rescuesim::foxglove {

namespace {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = net::ip::tcp;
using error_code = boost::system::error_code;

constexpr std::size_t kReadChunk = 64 * 1024;

/// One frame waiting to be written.
struct OutFrame {
  enum class Kind { control, status, reply, data, time };
  Kind kind = Kind::control;
  std::string text;                  ///< control and status frames
  std::vector<std::uint8_t> head;    ///< reply, data and time frames
  Payload body;                      ///< data frames
  std::size_t bytes() const { return text.size() + head.size() + (body ? body->size() : 0); }
};

/// True when the comma-separated header value lists `token`.
bool lists_token(std::string_view header, std::string_view token) {
  while (!header.empty()) {
    const std::size_t comma = header.find(',');
    std::string_view item = header.substr(0, comma);
    while (!item.empty() && (item.front() == ' ' || item.front() == '\t')) item.remove_prefix(1);
    while (!item.empty() && (item.back() == ' ' || item.back() == '\t')) item.remove_suffix(1);
    if (item == token) return true;
    if (comma == std::string_view::npos) break;
    header.remove_prefix(comma + 1);
  }
  return false;
}

class Server;

/// One client connection: HTTP upgrade, then a read loop and a write queue.
class Connection : public std::enable_shared_from_this<Connection> {
 public:
  Connection(Server& server, tcp::socket socket, ClientId id);

  ClientId id() const { return id_; }
  void start();

  // queueing, from any thread
  void queue(OutFrame frame, std::size_t* dropped);
  void queue_time(std::vector<std::uint8_t> frame);
  bool idle() const;
  ClientCounters counters() const;
  // io thread
  void close(std::chrono::milliseconds grace);

 private:
  void on_request(error_code ec);
  void refuse(http::status status, std::string reason);
  void on_accept(error_code ec);
  void read_more();
  void on_read(error_code ec, std::size_t n);
  void post_kick();
  void write_next();
  void on_write(error_code ec);
  void fail(const char* where, error_code ec);

  Server& server_;
  ClientId id_;
  std::string remote_;
  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::empty_body>> parser_;
  http::response<http::string_body> refusal_;
  net::steady_timer close_timer_;

  // read state (io thread)
  std::size_t message_size_ = 0;
  bool discarding_ = false;
  // write state (io thread)
  bool writing_ = false;
  bool has_place_ = false;    ///< holds one of the server's max_clients places
  bool opened_ = false;       ///< the handler heard on_open
  bool done_ = false;         ///< failed or closed: no more I/O
  OutFrame current_;

  // queues (guarded by mutex_)
  mutable std::mutex mutex_;
  std::deque<OutFrame> control_;             ///< control, status and reply frames, in order
  std::deque<OutFrame> data_;
  std::optional<std::vector<std::uint8_t>> time_;
  std::size_t data_bytes_ = 0, status_count_ = 0, reply_count_ = 0;
  bool accepting_ = true;                    ///< false once closed: queueing is ignored
  ClientCounters counters_;
  std::atomic<bool> kick_posted_{false};
};

class Server final : public WsServer {
 public:
  Server(const std::string& host, int port, std::string subprotocol, const ServerLimits& limits, ServerHandler& handler)
      : subprotocol_(std::move(subprotocol)), limits_(limits), handler_(handler), acceptor_(ioc_) {
    error_code ec;
    const auto address = net::ip::make_address(host, ec);
    if (ec) throw Error("--foxglove-host: '" + host + "' is not an IP address (" + ec.message() + ")");
    if (port < 0 || port > 65535) throw Error("--foxglove: port " + std::to_string(port) + " is outside 0..65535");
    const tcp::endpoint endpoint(address, static_cast<unsigned short>(port));
    acceptor_.open(endpoint.protocol(), ec);
    if (!ec) acceptor_.set_option(net::socket_base::reuse_address(true), ec);
    if (!ec) acceptor_.bind(endpoint, ec);
    if (!ec) acceptor_.listen(net::socket_base::max_listen_connections, ec);
    if (ec) {
      throw Error("foxglove: cannot listen on " + host + ":" + std::to_string(port) + ": " + ec.message() +
                  (ec == net::error::address_in_use
                       ? " (another program, or another rescuesim, uses it: pick another port with --foxglove=PORT)"
                       : ""));
    }
    port_ = acceptor_.local_endpoint().port();
    accept();
    thread_ = start_named_thread("fox-io", [this] {
      for (;;) {
        try {
          ioc_.run();
          break;
        } catch (const std::exception& e) {
          log::error("foxglove: I/O thread: {}", e.what());  // keep serving the other clients
        }
      }
    });
  }
  ~Server() override { shutdown(std::chrono::milliseconds(0)); }

  int port() const override { return port_; }

  void send_control(ClientId client, std::string text) override {
    if (auto c = find(client)) c->queue({OutFrame::Kind::control, std::move(text), {}, nullptr}, nullptr);
  }
  void send_status(ClientId client, std::string text) override {
    if (auto c = find(client)) c->queue({OutFrame::Kind::status, std::move(text), {}, nullptr}, nullptr);
  }
  void send_reply(ClientId client, std::vector<std::uint8_t> frame) override {
    if (auto c = find(client)) c->queue({OutFrame::Kind::reply, {}, std::move(frame), nullptr}, nullptr);
  }
  void post(std::function<void()> task) override { net::post(ioc_, std::move(task)); }
  std::size_t send_data(ClientId client, std::vector<std::uint8_t> head, Payload body) override {
    std::size_t dropped = 0;
    if (auto c = find(client)) c->queue({OutFrame::Kind::data, {}, std::move(head), std::move(body)}, &dropped);
    return dropped;
  }
  void send_time(ClientId client, std::vector<std::uint8_t> frame) override {
    if (auto c = find(client)) c->queue_time(std::move(frame));
  }
  ClientCounters counters(ClientId client) const override {
    auto c = find(client);
    return c ? c->counters() : ClientCounters{};
  }
  ClientCounters totals() const override {
    std::lock_guard lock(mutex_);
    ClientCounters t = gone_;
    for (const auto& [id, c] : connections_) {
      const ClientCounters k = c->counters();
      t.sent += k.sent;
      t.dropped += k.dropped;
    }
    return t;
  }

  void shutdown(std::chrono::milliseconds flush) override {
    if (stopped_.exchange(true)) return;
    // let queued frames go out (clients that read keep up; the others are closed anyway)
    const auto deadline = std::chrono::steady_clock::now() + flush;
    while (std::chrono::steady_clock::now() < deadline) {
      bool idle = true;
      {
        std::lock_guard lock(mutex_);
        for (const auto& [id, c] : connections_) idle = idle && c->idle();
      }
      if (idle) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    net::post(ioc_, [this] {
      error_code ec;
      acceptor_.close(ec);
      std::vector<std::shared_ptr<Connection>> all;
      {
        std::lock_guard lock(mutex_);
        for (const auto& [id, c] : connections_) all.push_back(c);
      }
      for (auto& c : all) c->close(std::chrono::milliseconds(300));
    });
    // wait for the connections to go, then stop the loop
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::milliseconds(1000);
    while (std::chrono::steady_clock::now() < give_up) {
      {
        std::lock_guard lock(mutex_);
        if (connections_.empty()) break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ioc_.stop();
    if (thread_.joinable()) thread_.join();
    std::lock_guard lock(mutex_);
    for (const auto& [id, c] : connections_) {
      const ClientCounters k = c->counters();
      gone_.sent += k.sent;
      gone_.dropped += k.dropped;
    }
    connections_.clear();
  }

  // for connections (io thread)
  const std::string& subprotocol() const { return subprotocol_; }
  const ServerLimits& limits() const { return limits_; }
  ServerHandler& handler() { return handler_; }
  net::io_context& ioc() { return ioc_; }
  /// Takes one of the max_clients places for a connection about to open; false when full.
  bool reserve_place() {
    std::lock_guard lock(mutex_);
    if (open_ >= limits_.max_clients) return false;
    ++open_;
    return true;
  }
  /// Forgets a connection, giving back its place if it had one.
  void remove(ClientId id, bool had_place) {
    std::lock_guard lock(mutex_);
    const auto it = connections_.find(id);
    if (it == connections_.end()) return;
    const ClientCounters k = it->second->counters();
    gone_.sent += k.sent;
    gone_.dropped += k.dropped;
    if (had_place) --open_;
    connections_.erase(it);
  }

 private:
  std::shared_ptr<Connection> find(ClientId id) const {
    std::lock_guard lock(mutex_);
    const auto it = connections_.find(id);
    return it == connections_.end() ? nullptr : it->second;
  }

  void accept() {
    acceptor_.async_accept([this](error_code ec, tcp::socket socket) {
      if (ec == net::error::operation_aborted || !acceptor_.is_open()) return;
      if (!ec) {
        error_code ignored;
        socket.set_option(tcp::no_delay(true), ignored);
        std::shared_ptr<Connection> c;
        {
          std::lock_guard lock(mutex_);
          const ClientId id = next_id_++;
          c = std::make_shared<Connection>(*this, std::move(socket), id);
          connections_[id] = c;
        }
        c->start();
      } else {
        log::warn("foxglove: accept failed: {}", ec.message());
      }
      accept();
    });
  }

  std::string subprotocol_;
  ServerLimits limits_;
  ServerHandler& handler_;
  net::io_context ioc_{1};
  tcp::acceptor acceptor_;
  int port_ = 0;
  std::thread thread_;
  std::atomic<bool> stopped_{false};

  mutable std::mutex mutex_;
  std::map<ClientId, std::shared_ptr<Connection>> connections_;  ///< handshaking and open
  std::size_t open_ = 0;  ///< connections holding a place (open, or completing their handshake)
  ClientId next_id_ = 1;
  ClientCounters gone_;
};

Connection::Connection(Server& server, tcp::socket socket, ClientId id)
    : server_(server), id_(id), ws_(std::move(socket)), close_timer_(server.ioc()) {
  error_code ec;
  const auto ep = beast::get_lowest_layer(ws_).socket().remote_endpoint(ec);
  remote_ = ec ? "?" : ep.address().to_string() + ":" + std::to_string(ep.port());
}

void Connection::start() {
  // the HTTP upgrade request: small, and within a few seconds
  beast::get_lowest_layer(ws_).expires_after(std::chrono::seconds(10));
  parser_.emplace();
  parser_->header_limit(16 * 1024);
  http::async_read(ws_.next_layer(), buffer_, *parser_, [self = shared_from_this()](error_code ec, std::size_t) { self->on_request(ec); });
}

void Connection::on_request(error_code ec) {
  if (ec) return fail("reading the HTTP request", ec);
  const auto& req = parser_->get();
  if (!websocket::is_upgrade(req)) {
    return refuse(http::status::upgrade_required, "This is a Foxglove WebSocket server (subprotocol " + server_.subprotocol() +
                                                      "). Open it in Foxglove or Lichtblick: ws://<host>:<port>\n");
  }
  if (!lists_token(req[http::field::sec_websocket_protocol], server_.subprotocol())) {
    return refuse(http::status::bad_request, "WebSocket subprotocol " + server_.subprotocol() + " required (offered: '" +
                                                 std::string(req[http::field::sec_websocket_protocol]) + "')\n");
  }
  if (!server_.reserve_place()) {
    return refuse(http::status::service_unavailable,
                  "too many clients (" + std::to_string(server_.limits().max_clients) + " connected); try again later\n");
  }
  has_place_ = true;
  beast::get_lowest_layer(ws_).expires_never();
  // a peer that sends nothing (not even a pong to our ping) for a minute is gone: close it
  websocket::stream_base::timeout timeouts;
  timeouts.handshake_timeout = std::chrono::seconds(5);
  timeouts.idle_timeout = std::chrono::seconds(60);
  timeouts.keep_alive_pings = true;
  ws_.set_option(timeouts);
  const std::string proto = server_.subprotocol();
  ws_.set_option(websocket::stream_base::decorator([proto](websocket::response_type& res) {
    res.set(http::field::sec_websocket_protocol, proto);
    res.set(http::field::server, "rescuesim");
  }));
  ws_.read_message_max(0);  // no limit here: oversize messages are read, discarded and answered
  ws_.auto_fragment(false);
  ws_.async_accept(req, [self = shared_from_this()](error_code e) { self->on_accept(e); });
}

void Connection::refuse(http::status status, std::string reason) {
  log::info("foxglove: refused {}: {}", remote_, reason.substr(0, reason.size() - 1));
  refusal_ = http::response<http::string_body>(status, parser_->get().version());
  refusal_.set(http::field::server, "rescuesim");
  refusal_.set(http::field::content_type, "text/plain");
  refusal_.keep_alive(false);
  refusal_.body() = std::move(reason);
  refusal_.prepare_payload();
  http::async_write(ws_.next_layer(), refusal_, [self = shared_from_this()](error_code, std::size_t) {
    error_code ignored;
    beast::get_lowest_layer(self->ws_).socket().shutdown(tcp::socket::shutdown_both, ignored);
    self->fail("refused", {});
  });
}

void Connection::on_accept(error_code ec) {
  if (ec) return fail("WebSocket handshake", ec);
  buffer_.clear();
  parser_.reset();
  opened_ = true;
  log::info("foxglove: client {} connected from {}", id_, remote_);
  try {
    server_.handler().on_open(id_, remote_);
  } catch (const std::exception& e) {
    log::error("foxglove: on_open: {}", e.what());
  }
  read_more();
  post_kick();
}

void Connection::read_more() {
  ws_.async_read_some(buffer_, kReadChunk, [self = shared_from_this()](error_code ec, std::size_t n) { self->on_read(ec, n); });
}

void Connection::on_read(error_code ec, std::size_t n) {
  if (ec) return fail("reading", ec);
  message_size_ += n;
  // an oversize message is read to its end and thrown away, so the connection stays usable
  if (message_size_ > server_.limits().max_frame) discarding_ = true;
  if (discarding_) buffer_.clear();
  if (ws_.is_message_done()) {
    const bool text = ws_.got_text();
    try {
      if (discarding_) {
        server_.handler().on_oversize(id_, message_size_, text);
      } else {
        const auto data = buffer_.data();
        const auto* p = static_cast<const std::uint8_t*>(data.data());
        if (text) {
          server_.handler().on_text(id_, std::string_view(reinterpret_cast<const char*>(p), data.size()));
        } else {
          server_.handler().on_binary(id_, std::span<const std::uint8_t>(p, data.size()));
        }
      }
    } catch (const std::exception& e) {
      log::error("foxglove: handling a message of client {}: {}", id_, e.what());
    }
    buffer_.clear();
    message_size_ = 0;
    discarding_ = false;
  }
  if (!done_) read_more();
}

void Connection::queue(OutFrame frame, std::size_t* dropped) {
  {
    std::lock_guard lock(mutex_);
    if (!accepting_) return;
    switch (frame.kind) {
      case OutFrame::Kind::control: control_.push_back(std::move(frame)); break;
      case OutFrame::Kind::status:
        if (status_count_ >= server_.limits().status_messages) return;  // a client flooding us with bad input
        ++status_count_;
        control_.push_back(std::move(frame));
        break;
      case OutFrame::Kind::reply:
        if (reply_count_ >= server_.limits().reply_messages) return;  // a client that sends requests and reads no answer
        ++reply_count_;
        control_.push_back(std::move(frame));
        break;
      case OutFrame::Kind::data: {
        data_bytes_ += frame.bytes();
        data_.push_back(std::move(frame));
        std::size_t n = 0;
        while (data_.size() > 1 && (data_bytes_ > server_.limits().queue_bytes || data_.size() > server_.limits().queue_messages)) {
          data_bytes_ -= data_.front().bytes();
          data_.pop_front();
          ++n;
        }
        counters_.dropped += n;
        if (dropped) *dropped = n;
        break;
      }
      case OutFrame::Kind::time: time_ = std::move(frame.head); break;
    }
  }
  post_kick();
}

void Connection::queue_time(std::vector<std::uint8_t> frame) {
  {
    std::lock_guard lock(mutex_);
    if (!accepting_) return;
    time_ = std::move(frame);
  }
  post_kick();
}

bool Connection::idle() const {
  std::lock_guard lock(mutex_);
  return !opened_ || !accepting_ || (control_.empty() && data_.empty() && !time_);
}

ClientCounters Connection::counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

void Connection::post_kick() {
  if (kick_posted_.exchange(true)) return;
  net::post(server_.ioc(), [self = shared_from_this()] {
    self->kick_posted_ = false;
    if (self->opened_ && !self->done_ && !self->writing_) self->write_next();
  });
}

void Connection::write_next() {
  {
    std::lock_guard lock(mutex_);
    if (!control_.empty()) {
      current_ = std::move(control_.front());
      control_.pop_front();
      if (current_.kind == OutFrame::Kind::status) --status_count_;
      if (current_.kind == OutFrame::Kind::reply) --reply_count_;
    } else if (time_) {
      current_ = OutFrame{OutFrame::Kind::time, {}, std::move(*time_), nullptr};
      time_.reset();
    } else if (!data_.empty()) {
      current_ = std::move(data_.front());
      data_.pop_front();
      data_bytes_ -= current_.bytes();
    } else {
      return;
    }
  }
  writing_ = true;
  auto done = [self = shared_from_this()](error_code ec, std::size_t) { self->on_write(ec); };
  if (current_.kind == OutFrame::Kind::control || current_.kind == OutFrame::Kind::status) {
    ws_.text(true);
    ws_.async_write(net::buffer(current_.text), std::move(done));
  } else {
    ws_.binary(true);
    const std::array<net::const_buffer, 2> buffers{net::buffer(current_.head),
                                                   current_.body ? net::buffer(*current_.body) : net::const_buffer()};
    ws_.async_write(buffers, std::move(done));
  }
}

void Connection::on_write(error_code ec) {
  writing_ = false;
  if (ec) return fail("writing", ec);
  if (current_.kind == OutFrame::Kind::data) {
    std::lock_guard lock(mutex_);
    ++counters_.sent;
  }
  current_ = OutFrame{};
  if (!done_) write_next();
}

void Connection::close(std::chrono::milliseconds grace) {
  if (done_) return;
  {
    std::lock_guard lock(mutex_);
    accepting_ = false;
    control_.clear();
    data_.clear();
    time_.reset();
  }
  if (opened_) {
    ws_.async_close(websocket::close_code::going_away, [self = shared_from_this()](error_code) {});
  }
  close_timer_.expires_after(grace);
  close_timer_.async_wait([self = shared_from_this()](error_code) { self->fail("closing", {}); });
}

void Connection::fail(const char* where, error_code ec) {
  if (done_) return;
  done_ = true;
  {
    std::lock_guard lock(mutex_);
    accepting_ = false;
  }
  if (ec && ec != websocket::error::closed && ec != net::error::operation_aborted && ec != net::error::eof &&
      ec != net::error::connection_reset && ec != beast::error::timeout) {
    log::info("foxglove: client {} ({}): {}: {}", id_, remote_, where, ec.message());
  }
  error_code ignored;
  close_timer_.cancel();
  beast::get_lowest_layer(ws_).socket().close(ignored);
  server_.remove(id_, has_place_);
  if (opened_) {
    log::info("foxglove: client {} disconnected", id_);
    try {
      server_.handler().on_close(id_);
    } catch (const std::exception& e) {
      log::error("foxglove: on_close: {}", e.what());
    }
  }
}

}  // namespace

std::unique_ptr<WsServer> WsServer::start(const std::string& host, int port, const std::string& subprotocol, const ServerLimits& limits,
                                          ServerHandler& handler) {
  return std::make_unique<Server>(host, port, subprotocol, limits, handler);
}

}  // namespace rescuesim::foxglove
