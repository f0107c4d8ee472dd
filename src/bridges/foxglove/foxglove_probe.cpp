#include "bridges/foxglove/foxglove_probe.h"

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <map>
#include <set>
#include <thread>

#include "core/error.h"

namespace rescuesim {

namespace {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

std::uint32_t u32_le(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 | static_cast<std::uint32_t>(p[2]) << 16 |
         static_cast<std::uint32_t>(p[3]) << 24;
}

}  // namespace

void run_foxglove_probe(const std::string& host, int port, const std::vector<std::string>& topics,
                        const FoxgloveProbeCallback& on_message, const std::function<void()>& ready, const std::atomic<bool>& stop,
                        double seconds) {
  const std::string where = host + ":" + std::to_string(port);
  net::io_context ioc;
  websocket::stream<tcp::socket> ws(ioc);
  // the server may still be starting: try for a while (10 s, or the probe's time if shorter)
  const auto give_up = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(std::min(10.0, seconds)));
  for (;;) {
    boost::system::error_code ec;
    tcp::resolver resolver(ioc);
    const auto endpoints = resolver.resolve(host, std::to_string(port), ec);
    if (!ec) net::connect(ws.next_layer(), endpoints, ec);
    if (!ec) break;
    if (Clock::now() > give_up || stop.load()) {
      throw Error("bench-probe: cannot connect to the Foxglove server at " + where + ": " + ec.message());
    }
    boost::system::error_code ignored;
    ws.next_layer().close(ignored);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ws.set_option(websocket::stream_base::decorator(
      [](websocket::request_type& req) { req.set(beast::http::field::sec_websocket_protocol, "foxglove.websocket.v1"); }));
  ws.read_message_max(64u << 20);
  try {
    ws.handshake(where, "/");
  } catch (const boost::system::system_error& e) {
    throw Error("bench-probe: the WebSocket handshake with " + where + " failed: " + e.what());
  }

  std::map<std::uint32_t, std::size_t> topic_of_subscription;  // subscription id -> index in `topics`
  std::set<std::size_t> subscribed;
  std::uint32_t next_subscription = 1;
  bool said_ready = false, closed = false;
  beast::flat_buffer buffer;

  // a text frame: subscribe to the channels of our topics as they are advertised
  const auto on_text = [&](const std::string& text) {
    const json j = json::parse(text, nullptr, false);
    if (!j.is_object() || j.value("op", "") != "advertise" || !j.contains("channels")) return;
    json subscriptions = json::array();
    for (const json& ch : j["channels"]) {
      const auto it = std::find(topics.begin(), topics.end(), ch.value("topic", ""));
      if (it == topics.end()) continue;
      const auto index = static_cast<std::size_t>(it - topics.begin());
      if (subscribed.contains(index)) continue;
      subscribed.insert(index);
      topic_of_subscription[next_subscription] = index;
      subscriptions.push_back({{"id", next_subscription++}, {"channelId", ch.value("id", 0)}});
    }
    if (subscriptions.empty()) return;
    ws.text(true);
    ws.write(net::buffer(json{{"op", "subscribe"}, {"subscriptions", subscriptions}}.dump()));
    if (!said_ready && subscribed.size() == topics.size()) {
      said_ready = true;
      ready();
    }
  };
  // a binary frame: 0x01 | u32 subscription | u64 receive time | payload (cdr: 4-byte
  // encapsulation, then the Header's int32 sec and uint32 nanosec)
  const auto on_binary = [&](const std::uint8_t* p, std::size_t n) {
    if (n < 1 + 4 + 8 + 12 || p[0] != 0x01) return;
    const auto it = topic_of_subscription.find(u32_le(p + 1));
    if (it == topic_of_subscription.end()) return;
    const std::uint8_t* payload = p + 13;
    const auto sec = static_cast<std::int32_t>(u32_le(payload + 4));
    on_message(it->second, static_cast<std::int64_t>(sec) * 1'000'000'000 + u32_le(payload + 8));
  };

  std::function<void()> read_next = [&] {
    ws.async_read(buffer, [&](boost::system::error_code ec, std::size_t) {
      if (ec) {
        closed = true;
        return;
      }
      const auto data = buffer.data();
      const auto* p = static_cast<const std::uint8_t*>(data.data());
      if (ws.got_text()) on_text(std::string(reinterpret_cast<const char*>(p), data.size()));
      else on_binary(p, data.size());
      buffer.consume(buffer.size());
      read_next();
    });
  };
  read_next();
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  while (!stop.load() && !closed && Clock::now() < end) ioc.run_for(std::chrono::milliseconds(100));
  boost::system::error_code ignored;
  ws.next_layer().close(ignored);
}

}  // namespace rescuesim
