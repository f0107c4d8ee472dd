#include "bridges/ros2/dds_service_wire.h"

#include <cstdio>
#include <cstring>

#include "bridges/common/cdr_stream.h"
#include "core/error.h"

namespace rescuesim::ros2 {

namespace {

constexpr std::size_t kHeader = cdr::kEncapsulationSize;

}  // namespace

std::optional<ServiceSample> split_service_sample(std::span<const std::uint8_t> sample, std::string* why) {
  const auto fail = [&](std::string text) -> std::optional<ServiceSample> {
    if (why) *why = std::move(text);
    return std::nullopt;
  };
  if (sample.size() < kHeader + kRequestHeaderBytes) {
    return fail(std::to_string(sample.size()) + " bytes, shorter than the encapsulation and request headers (20 bytes)");
  }
  // the header's numbers in the byte order the encapsulation names (00 01 little, 00 00 big endian)
  const std::optional<std::endian> order = cdr::xcdr1_byte_order(sample);
  if (!order) {
    return fail("encapsulation " + std::to_string(sample[0]) + " " + std::to_string(sample[1]) +
                " is not XCDR1 (00 00 big endian or 00 01 little endian)");
  }
  ServiceSample out;
  out.header.guid = cdr::load<std::uint64_t>(sample.data() + kHeader, *order);
  out.header.seq = cdr::load<std::int64_t>(sample.data() + kHeader + 8, *order);
  // the body as a message of its own: same encapsulation header, the bytes after the request
  // header (same alignment: see the file comment of the header)
  out.body.reserve(sample.size() - kRequestHeaderBytes);
  out.body.insert(out.body.end(), sample.begin(), sample.begin() + kHeader);
  out.body.insert(out.body.end(), sample.begin() + kHeader + kRequestHeaderBytes, sample.end());
  return out;
}

std::vector<std::uint8_t> join_service_sample(const RequestHeader& header, std::span<const std::uint8_t> body) {
  const std::optional<std::endian> order = cdr::xcdr1_byte_order(body);
  if (!order) throw Error("service reply or request body: not a CDR message (no XCDR1 encapsulation header)");
  std::vector<std::uint8_t> out(body.size() + kRequestHeaderBytes);
  std::memcpy(out.data(), body.data(), kHeader);
  cdr::store(out.data() + kHeader, header.guid, *order);
  cdr::store(out.data() + kHeader + 8, header.seq, *order);
  if (body.size() > kHeader) {
    std::memcpy(out.data() + kHeader + kRequestHeaderBytes, body.data() + kHeader, body.size() - kHeader);
  }
  return out;
}

std::string absolute_ros_name(const std::string& name) {
  const std::string full = name.starts_with('/') ? name : "/" + name;
  if (full.size() < 2) throw Error("ROS name '" + name + "': empty");
  if (full.ends_with('/')) throw Error("ROS name '" + name + "': ends with '/'");
  if (full.find("//") != std::string::npos) throw Error("ROS name '" + name + "': contains '//'");
  for (const char c : full) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '/';
    if (!ok) throw Error("ROS name '" + name + "': character '" + std::string(1, c) + "' (expected letters, digits, '_' and '/')");
  }
  return full;
}

std::string dds_type_name(const std::string& ros_type) {
  const std::size_t a = ros_type.find('/');
  const std::size_t b = a == std::string::npos ? a : ros_type.find('/', a + 1);
  if (a == std::string::npos || b == std::string::npos || a == 0 || b == a + 1 || b + 1 >= ros_type.size() ||
      ros_type.find('/', b + 1) != std::string::npos) {
    throw Error("ROS type '" + ros_type + "': expected package/kind/Name (e.g. simulation_interfaces/srv/ResetSimulation)");
  }
  return ros_type.substr(0, a) + "::" + ros_type.substr(a + 1, b - a - 1) + "::dds_::" + ros_type.substr(b + 1) + "_";
}

ServiceTopics service_topics_for_dds_base(const std::string& ros_service, const std::string& dds_type_base) {
  ServiceTopics t;
  t.name = absolute_ros_name(ros_service);
  // rmw's make_fqtopic: prefix, the absolute name, suffix ("rq" + "/reset_simulation" + "Request")
  t.request_topic = "rq" + t.name + "Request";
  t.reply_topic = "rr" + t.name + "Reply";
  t.request_type = dds_type_base + "Request_";
  t.reply_type = dds_type_base + "Response_";
  return t;
}

ServiceTopics service_topics(const std::string& ros_service, const std::string& srv_type) {
  const std::string dds = dds_type_name(srv_type);  // "pkg::srv::dds_::Name_"
  if (srv_type.find("/srv/") == std::string::npos) {
    throw Error("service type '" + srv_type + "': expected package/srv/Name");
  }
  return service_topics_for_dds_base(ros_service, dds);
}

EndpointQos service_qos() {
  EndpointQos q;
  q.reliability = Reliability::reliable;
  q.durability = Durability::volatile_local;
  q.depth = 10;
  return q;
}

std::string client_service_id(const Guid& participant, std::uint32_t counter) {
  std::uint8_t id[16];
  std::memcpy(id, participant.data(), 12);
  for (int i = 0; i < 4; ++i) id[12 + i] = static_cast<std::uint8_t>(counter >> (24 - 8 * i));
  // as rmw_cyclonedds's csid_to_string: std::hex, std::setw(2) on the first byte only
  char text[16 * 3 + 1];
  int n = std::snprintf(text, sizeof text, "%2x", static_cast<unsigned>(id[0]));
  for (int i = 1; i < 16; ++i) n += std::snprintf(text + n, sizeof text - static_cast<std::size_t>(n), ".%x", static_cast<unsigned>(id[i]));
  return std::string(text, static_cast<std::size_t>(n));
}

std::string service_user_data(const std::string& id) { return "serviceid=" + id + ";"; }
std::string client_user_data(const std::string& id) { return "clientid=" + id + ";"; }

std::optional<std::string> user_data_value(std::string_view user_data, std::string_view key) {
  while (!user_data.empty()) {
    const std::size_t end = user_data.find(';');
    const std::string_view item = user_data.substr(0, end);
    const std::size_t eq = item.find('=');
    if (eq != std::string_view::npos && item.substr(0, eq) == key) return std::string(item.substr(eq + 1));
    if (end == std::string_view::npos) break;
    user_data.remove_prefix(end + 1);
  }
  return std::nullopt;
}

}  // namespace rescuesim::ros2
