#include "bridges/foxglove/protocol.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "msgs/serialize.h"

namespace rescuesim::foxglove {

namespace {

using json = nlohmann::json;

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put_u64(std::vector<std::uint8_t>& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
std::uint32_t get_u32(std::span<const std::uint8_t> b) {
  return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 | static_cast<std::uint32_t>(b[2]) << 16 |
         static_cast<std::uint32_t>(b[3]) << 24;
}

/// A field of a JSON object that must be an array, with `where` naming it in errors.
const json& array_field(const json& object, const char* key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) throw Error(where + ": missing '" + key + "'");
  if (!it->is_array()) throw Error(where + "." + key + ": expected an array");
  return *it;
}

std::uint32_t u32_field(const json& object, const char* key, const std::string& where) {
  if (!object.is_object()) throw Error(where + ": expected an object");
  const auto it = object.find(key);
  if (it == object.end()) throw Error(where + ": missing '" + key + "'");
  if (!it->is_number_unsigned() || it->get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max()) {
    throw Error(where + "." + key + ": expected an unsigned 32-bit integer, got " + it->dump());
  }
  return it->get<std::uint32_t>();
}

std::string string_field(const json& object, const char* key, const std::string& where, bool required) {
  const auto it = object.find(key);
  if (it == object.end() || (it->is_null() && !required)) {
    if (required) throw Error(where + ": missing '" + key + "'");
    return {};
  }
  if (!it->is_string()) throw Error(where + "." + key + ": expected a string, got " + it->dump());
  return it->get<std::string>();
}

std::vector<std::uint32_t> u32_array(const json& request, const char* key, const std::string& op) {
  std::vector<std::uint32_t> ids;
  const json& a = array_field(request, key, op);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const json& v = a[i];
    if (!v.is_number_unsigned() || v.get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max()) {
      throw Error(op + "." + key + "[" + std::to_string(i) + "]: expected an unsigned 32-bit integer, got " + v.dump());
    }
    ids.push_back(v.get<std::uint32_t>());
  }
  return ids;
}

json parse_json(std::span<const std::uint8_t> payload, const char* type) {
  json j = json::parse(payload.begin(), payload.end(), nullptr, false);
  if (j.is_discarded()) throw Error(std::string(type) + ": payload is not valid JSON");
  if (!j.is_object()) throw Error(std::string(type) + ": expected a JSON object");
  return j;
}

const msg::TypeSupport& type_support(const char* name) {
  const msg::TypeSupport* t = msg::find_type(name);
  if (!t) throw Error(std::string(name) + ": no type support in this build");
  return *t;
}

}  // namespace

std::string server_info(const std::string& name, const std::vector<std::string>& capabilities, const std::vector<std::string>& encodings,
                        const std::vector<std::pair<std::string, std::string>>& metadata, const std::string& session_id) {
  json meta = json::object();
  for (const auto& [k, v] : metadata) meta[k] = v;
  json j = {{"op", "serverInfo"}, {"name", name},     {"capabilities", capabilities}, {"supportedEncodings", encodings},
            {"metadata", meta},   {"sessionId", session_id}};
  return j.dump();
}

std::string advertise(const std::vector<Channel>& channels) {
  json list = json::array();
  for (const Channel& c : channels) {
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", c.encoding},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", c.schema_encoding}});
  }
  return json{{"op", "advertise"}, {"channels", list}}.dump();
}

std::string unadvertise(const std::vector<std::uint32_t>& channel_ids) {
  return json{{"op", "unadvertise"}, {"channelIds", channel_ids}}.dump();
}

std::string status(StatusLevel level, const std::string& message) {
  // replace invalid UTF-8 (a client's bytes may be echoed in messages) instead of throwing
  return json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}.dump(-1, ' ', false,
                                                                                             json::error_handler_t::replace);
}

std::string advertise_services(const std::vector<Service>& services) {
  const auto message = [](const ServiceMessage& m) {
    return json{{"encoding", m.encoding}, {"schemaName", m.schema_name}, {"schemaEncoding", m.schema_encoding}, {"schema", m.schema}};
  };
  json list = json::array();
  for (const Service& s : services) {
    list.push_back({{"id", s.id}, {"name", s.name}, {"type", s.type}, {"request", message(s.request)}, {"response", message(s.response)}});
  }
  return json{{"op", "advertiseServices"}, {"services", list}}.dump();
}

std::string service_call_failure(std::uint32_t service, std::uint32_t call, const std::string& message) {
  // the message may quote a client's bytes (an encoding name): invalid UTF-8 is replaced
  return json{{"op", "serviceCallFailure"}, {"serviceId", service}, {"callId", call}, {"message", message}}.dump(
      -1, ' ', false, json::error_handler_t::replace);
}

std::vector<std::uint8_t> service_call_response(std::uint32_t service, std::uint32_t call, std::string_view encoding,
                                                std::string_view payload) {
  std::vector<std::uint8_t> f;
  f.reserve(13 + encoding.size() + payload.size());
  f.push_back(0x03);
  put_u32(f, service);
  put_u32(f, call);
  put_u32(f, static_cast<std::uint32_t>(encoding.size()));
  f.insert(f.end(), encoding.begin(), encoding.end());
  f.insert(f.end(), payload.begin(), payload.end());
  return f;
}

std::vector<std::uint8_t> message_data_header(std::uint32_t subscription, std::uint64_t timestamp_ns) {
  std::vector<std::uint8_t> h;
  h.reserve(13);
  h.push_back(0x01);
  put_u32(h, subscription);
  put_u64(h, timestamp_ns);
  return h;
}

std::vector<std::uint8_t> time_frame(std::uint64_t timestamp_ns) {
  std::vector<std::uint8_t> h;
  h.reserve(9);
  h.push_back(0x02);
  put_u64(h, timestamp_ns);
  return h;
}

ClientRequest parse_client_text(std::string_view text) {
  const json j = json::parse(text.begin(), text.end(), nullptr, false);
  if (j.is_discarded()) {
    std::string head(text.substr(0, 40));
    for (char& c : head) {
      if (static_cast<unsigned char>(c) < 0x20) c = ' ';
    }
    throw Error("malformed JSON text message (" + std::to_string(text.size()) + " bytes, starting '" + head + "')");
  }
  if (!j.is_object()) throw Error("text message must be a JSON object with an 'op' field");
  const auto op_it = j.find("op");
  if (op_it == j.end() || !op_it->is_string()) throw Error("text message has no string 'op' field");
  const std::string op = op_it->get<std::string>();
  if (op == "subscribe") {
    Subscribe s;
    const json& subs = array_field(j, "subscriptions", op);
    for (std::size_t i = 0; i < subs.size(); ++i) {
      const std::string where = op + ".subscriptions[" + std::to_string(i) + "]";
      s.subscriptions.emplace_back(u32_field(subs[i], "id", where), u32_field(subs[i], "channelId", where));
    }
    return s;
  }
  if (op == "unsubscribe") return Unsubscribe{u32_array(j, "subscriptionIds", op)};
  if (op == "advertise") {
    ClientAdvertise a;
    const json& chans = array_field(j, "channels", op);
    for (std::size_t i = 0; i < chans.size(); ++i) {
      const std::string where = op + ".channels[" + std::to_string(i) + "]";
      ClientChannel c;
      c.id = u32_field(chans[i], "id", where);
      c.topic = string_field(chans[i], "topic", where, true);
      c.encoding = string_field(chans[i], "encoding", where, true);
      c.schema_name = string_field(chans[i], "schemaName", where, false);
      a.channels.push_back(std::move(c));
    }
    return a;
  }
  if (op == "unadvertise") return ClientUnadvertise{u32_array(j, "channelIds", op)};
  for (const char* known : {"getParameters", "setParameters", "subscribeParameterUpdates", "unsubscribeParameterUpdates",
                            "subscribeConnectionGraph", "unsubscribeConnectionGraph", "fetchAsset"}) {
    if (op == known) return Unsupported{op};
  }
  std::string shown = op.substr(0, 40);
  throw Error("unknown op '" + shown + "' (this server understands subscribe, unsubscribe, advertise, unadvertise)");
}

ClientBinary parse_client_binary(std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) throw Error("empty binary message");
  const std::uint8_t opcode = bytes[0];
  if (opcode == 0x01) {
    if (bytes.size() < 5) {
      throw Error("client message data needs at least 5 bytes (opcode and channel id), got " + std::to_string(bytes.size()));
    }
    return ClientMessage{get_u32(bytes.subspan(1, 4)), bytes.subspan(5)};
  }
  if (opcode == 0x02) {
    // opcode, service id, call id, encoding length: 13 bytes; without the ids there is nobody to answer
    constexpr std::size_t kHeader = 13;
    const std::string need = "a service call request needs at least 13 bytes (opcode, service id, call id, encoding length), got " +
                             std::to_string(bytes.size());
    if (bytes.size() < 9) throw Error(need);
    ServiceCallRequest r;
    r.service = get_u32(bytes.subspan(1, 4));
    r.call = get_u32(bytes.subspan(5, 4));
    if (bytes.size() < kHeader) throw ServiceCallError(r.service, r.call, need);
    const std::uint32_t length = get_u32(bytes.subspan(9, 4));
    const std::size_t left = bytes.size() - kHeader;
    if (length > left) {
      throw ServiceCallError(r.service, r.call, "service call request: encoding length " + std::to_string(length) + " runs past the end (" +
                                                    std::to_string(left) + " bytes left)");
    }
    r.encoding.assign(reinterpret_cast<const char*>(bytes.data() + kHeader), length);
    r.payload = bytes.subspan(kHeader + length);
    return r;
  }
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02x", opcode);
  throw Error(std::string("unknown binary opcode ") + hex +
              " (accepted: 0x01 client message data, 0x02 service call request)");
}

msg::Message decode_message(std::string_view encoding, const msg::TypeSupport& type, std::span<const std::uint8_t> payload) {
  if (encoding == "cdr") return msg::from_cdr(type, payload);
  if (encoding == "json") return msg::from_json(type, std::string_view(reinterpret_cast<const char*>(payload.data()), payload.size()));
  throw Error("unsupported encoding '" + std::string(encoding) + "'");
}

msg::Twist decode_twist(std::string_view encoding, std::span<const std::uint8_t> payload) {
  return std::get<msg::Twist>(decode_message(encoding, type_support("geometry_msgs/msg/Twist"), payload));
}

msg::Float64MultiArray decode_multi_array(std::string_view encoding, std::span<const std::uint8_t> payload) {
  if (encoding == "json") {
    // a head command without targets is a mistake, not a command to do nothing
    const json j = parse_json(payload, "std_msgs/Float64MultiArray");
    array_field(j, "data", "std_msgs/Float64MultiArray");
  }
  return std::get<msg::Float64MultiArray>(decode_message(encoding, type_support("std_msgs/msg/Float64MultiArray"), payload));
}

msg::JointState decode_joint_state(std::string_view encoding, std::span<const std::uint8_t> payload) {
  if (encoding == "json") {
    const json j = parse_json(payload, "sensor_msgs/JointState");
    array_field(j, "name", "sensor_msgs/JointState");
  }
  return std::get<msg::JointState>(decode_message(encoding, type_support("sensor_msgs/msg/JointState"), payload));
}

}  // namespace rescuesim::foxglove
