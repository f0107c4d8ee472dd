#include "bridges/ros2/ros2_conventions.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "core/error.h"

namespace rescuesim::ros2 {

std::string dds_topic_name(const std::string& ros_topic) {
  const std::size_t start = ros_topic.find_first_not_of('/');
  return "rt/" + (start == std::string::npos ? std::string() : ros_topic.substr(start));
}

std::size_t queue_capacity(const Topic& topic, std::size_t max) {
  max = std::max<std::size_t>(max, 1);
  if (topic.rate <= 0) return max;
  return std::min(max, std::max<std::size_t>(4, static_cast<std::size_t>(std::ceil(topic.rate))));
}

EndpointQos writer_qos(const Topic& topic) {
  EndpointQos q;
  if (topic.latched) {
    q.durability = Durability::transient_local;
    q.depth = 1;
  } else if (topic.name == "/clock") {
    q.depth = 1;
  }
  return q;
}

EndpointQos command_reader_qos() {
  EndpointQos q;
  q.reliability = Reliability::best_effort;
  return q;
}

EndpointQos discovery_qos() {
  EndpointQos q;
  q.durability = Durability::transient_local;
  q.depth = 1;
  return q;
}

int resolve_domain(int requested) {
  if (requested >= 0) return requested;
  const char* env = std::getenv("ROS_DOMAIN_ID");
  if (env == nullptr || *env == '\0') return 0;
  int value = -1;
  const char* end = env + std::strlen(env);
  const auto [ptr, ec] = std::from_chars(env, end, value);
  if (ec != std::errc() || ptr != end || value < 0 || value > 232) {
    throw Error(std::string("ROS_DOMAIN_ID=") + env + ": expected a whole number from 0 to 232");
  }
  return value;
}

std::string participant_user_data() { return "enclave=/;"; }

std::size_t gid_size(Ros2Distro distro) { return distro == Ros2Distro::humble ? 24 : 16; }

bool distro_changes(const msg::Message& m, Ros2Distro distro) {
  return distro == Ros2Distro::iron_or_newer && std::holds_alternative<msg::Range>(m);
}

void adapt_to_distro(const msg::Message& m, Ros2Distro distro, std::vector<std::uint8_t>& cdr) {
  // Range's last field is a float32 at a 4-byte aligned offset, so variance follows it directly
  if (distro_changes(m, distro)) cdr.insert(cdr.end(), 4, 0);
}

namespace {

// XCDR1 little endian; alignment counts from the end of the encapsulation header
class CdrOut {
 public:
  CdrOut() { bytes_ = {0x00, 0x01, 0x00, 0x00}; }
  void u32(std::uint32_t v) {
    align(4);
    for (int i = 0; i < 4; ++i) bytes_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void string(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size() + 1));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    bytes_.push_back(0);
  }
  void gid(const Guid& g, std::size_t size) {
    for (std::size_t i = 0; i < size; ++i) bytes_.push_back(i < g.size() ? g[i] : 0);
  }
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  void align(std::size_t n) {
    while ((bytes_.size() - 4) % n != 0) bytes_.push_back(0);
  }
  std::vector<std::uint8_t> bytes_;
};

}  // namespace

std::vector<std::uint8_t> encode_discovery_info(const Guid& participant, const std::vector<NodeEntities>& nodes,
                                                std::size_t gid_bytes) {
  CdrOut out;
  out.gid(participant, gid_bytes);
  out.u32(static_cast<std::uint32_t>(nodes.size()));
  for (const NodeEntities& n : nodes) {
    out.string(n.node_namespace);
    out.string(n.node_name);
    out.u32(static_cast<std::uint32_t>(n.readers.size()));
    for (const Guid& g : n.readers) out.gid(g, gid_bytes);
    out.u32(static_cast<std::uint32_t>(n.writers.size()));
    for (const Guid& g : n.writers) out.gid(g, gid_bytes);
  }
  return out.take();
}

}  // namespace rescuesim::ros2
