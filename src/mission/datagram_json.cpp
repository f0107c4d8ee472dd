#include "mission/datagram_json.h"

#include <algorithm>
#include <cstdlib>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "msgs/base64.h"

namespace rescuesim {

SendRequest parse_send_request(std::string_view text) {
  if (text.size() > kMaxSendRequestBytes) {
    throw Error("send request of " + std::to_string(text.size()) + " bytes: at most " + std::to_string(kMaxSendRequestBytes) + " are read");
  }
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded())
    throw Error("send request is not JSON (expected {\"to\": \"base\", \"text\": \"...\"} or {\"to\": ..., \"data\": \"<base64>\"})");
  if (!j.is_object()) throw Error("send request is not a JSON object");
  SendRequest r;
  const auto to = j.find("to");
  if (to == j.end()) throw Error("send request: 'to' is missing (\"base\", a robot's name, or \"*\" for every neighbour)");
  if (!to->is_string() || to->get_ref<const std::string&>().empty()) throw Error("send request: 'to' must be a non-empty string");
  r.to = to->get<std::string>();
  const auto data = j.find("data");
  const auto txt = j.find("text");
  if ((data == j.end()) == (txt == j.end())) throw Error("send request: give 'data' (base64) or 'text', exactly one of them");
  if (data != j.end()) {
    if (!data->is_string()) throw Error("send request: 'data' must be a base64 string");
    auto bytes = msg::decode_base64(data->get_ref<const std::string&>());
    if (!bytes) throw Error("send request: 'data' is not base64 (RFC 4648, with padding)");
    r.bytes = std::move(*bytes);
  } else {
    if (!txt->is_string()) throw Error("send request: 'text' must be a string");
    const std::string& s = txt->get_ref<const std::string&>();
    r.bytes.assign(s.begin(), s.end());
  }
  for (const auto& [key, value] : j.items()) {
    if (key != "to" && key != "data" && key != "text") throw Error("send request: unknown key '" + key + "' (to, data, text)");
  }
  return r;
}

std::string send_request_json(const SendRequest& request) {
  std::string data;
  msg::append_base64(data, request.bytes.data(), request.bytes.size());
  return nlohmann::json{{"to", request.to}, {"data", data}}.dump();
}

bool is_text(const std::vector<std::uint8_t>& bytes) {
  std::size_t i = 0;
  while (i < bytes.size()) {
    const std::uint8_t c = bytes[i];
    if (c < 0x80) {
      if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') return false;
      if (c == 0x7f) return false;
      ++i;
      continue;
    }
    // a multi-byte UTF-8 sequence: its length from the lead byte, then continuation bytes
    const int n = (c & 0xe0) == 0xc0 ? 1 : (c & 0xf0) == 0xe0 ? 2 : (c & 0xf8) == 0xf0 ? 3 : -1;
    if (n < 0 || c == 0xc0 || c == 0xc1 || c > 0xf4 || i + static_cast<std::size_t>(n) >= bytes.size()) return false;
    for (int k = 1; k <= n; ++k) {
      if ((bytes[i + static_cast<std::size_t>(k)] & 0xc0) != 0x80) return false;
    }
    i += static_cast<std::size_t>(n) + 1;
  }
  return true;
}

std::string inbox_json(const InboxEntry& e) {
  nlohmann::json j;
  j["seq"] = e.seq;
  j["from"] = e.from;
  j["to"] = e.to;
  j["hops"] = e.hops;
  j["sent"] = e.sent;
  j["delivered"] = e.delivered;
  const std::vector<std::uint8_t> none;
  const std::vector<std::uint8_t>& b = e.bytes ? *e.bytes : none;
  j["bytes"] = b.size();
  std::string data;
  msg::append_base64(data, b.data(), b.size());
  j["data"] = data;
  if (is_text(b)) j["text"] = std::string(b.begin(), b.end());
  // is_text does not rule out every sequence JSON refuses (surrogates, overlong forms): replace those
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace rescuesim
