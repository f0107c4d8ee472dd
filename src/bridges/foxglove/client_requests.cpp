// What Foxglove clients ask for, on the server's I/O thread: subscriptions (with the latched
// message of a channel sent at once), client channels for /cmd_vel, /head/command and
// /joint_command and for the host's inputs (a mission's reports, datagrams, relay drops and
// map), and their messages, checked and passed to the simulation. Anything malformed or refused
// is answered with a status error to that client only. Service calls (binary 0x02) go on to
// service_calls.cpp.

#include <cmath>
#include <optional>
#include <variant>

#include "bridges/foxglove/bridge_impl.h"
#include "core/error.h"
#include "core/log.h"
#include "bus/bridge_host.h"

namespace rescuesim::foxglove {

namespace {

/// The ROS 2 and ROS 1 names of the message type a command topic takes.
std::pair<std::string, std::string> schema_names(const CommandTarget& target) {
  switch (target.kind) {
    case CommandTarget::Kind::twist: return {"geometry_msgs/msg/Twist", "geometry_msgs/Twist"};
    case CommandTarget::Kind::head:
    case CommandTarget::Kind::flippers: return {"std_msgs/msg/Float64MultiArray", "std_msgs/Float64MultiArray"};
    case CommandTarget::Kind::joints: return {"sensor_msgs/msg/JointState", "sensor_msgs/JointState"};
    case CommandTarget::Kind::host: return {target.type->ros2_name, target.type->ros1_name};
  }
  return {};
}

}  // namespace

std::string FoxgloveBridge::accepted_topics(RobotIndex robot) const {
  std::string t = twist_topics_[robot] + " (geometry_msgs/msg/Twist)";
  if (head_sizes_[robot] > 0) t += ", " + head_topics_[robot] + " (std_msgs/msg/Float64MultiArray)";
  if (joints_commandable_[robot]) t += ", " + joint_topics_[robot] + " (sensor_msgs/msg/JointState)";
  if (flipper_sizes_[robot] > 0) t += ", " + flipper_topics_[robot] + " (std_msgs/msg/Float64MultiArray)";
  for (const HostInput& in : host_inputs_) {
    if (in.robot != robot) continue;
    const msg::TypeSupport* type = msg::find_type(in.type);
    t += ", " + in.topic + " (" + (type ? type->ros2_name : in.type) + ")";
  }
  return t;
}

std::string FoxgloveBridge::accepted_topics() const {
  std::string all;
  for (RobotIndex r : twist_topics_.indices()) all += (all.empty() ? "" : ", ") + accepted_topics(r);
  for (const HostInput& in : host_inputs_) {
    const msg::TypeSupport* type = msg::find_type(in.type);
    if (!in.robot.valid()) all += ", " + in.topic + " (" + (type ? type->ros2_name : in.type) + ")";
  }
  return all;
}

void FoxgloveBridge::on_open(ClientId client, const std::string&) {
  std::lock_guard lock(mutex_);
  clients_.try_emplace(client);
  std::vector<Channel> all;
  for (const auto& [id, c] : channels_) all.push_back(c.channel);
  server_->send_control(client, server_info_);
  server_->send_control(client, advertise(all));
  if (!services_advertisement_.empty()) server_->send_control(client, services_advertisement_);
}

void FoxgloveBridge::on_close(ClientId client) {
  std::lock_guard lock(mutex_);
  const auto it = clients_.find(client);
  if (it == clients_.end()) return;
  for (const auto& [sub, channel] : it->second.subscriptions) {
    auto c = channels_.find(channel);
    if (c == channels_.end()) continue;
    c->second.subscribers.erase(client);
    if (c->second.topic != kNoTopic && static_cast<std::size_t>(c->second.topic) < kMaxTopics) {
      --wanted_[static_cast<std::size_t>(c->second.topic)];
    }
  }
  clients_.erase(it);
}

void FoxgloveBridge::reply(ClientId client, StatusLevel level, const std::string& message) {
  server_->send_status(client, status(level, message));
  std::uint64_t held = 0;
  if (level == StatusLevel::error && client_log_.allow(&held)) log::info("foxglove: client {}: {}", client, message);
}

void FoxgloveBridge::reject(ClientId client, const std::string& message) {
  ++rejected_;
  reply(client, StatusLevel::error, message);
}

void FoxgloveBridge::on_text(ClientId client, std::string_view text) {
  ClientRequest request;
  try {
    request = parse_client_text(text);
  } catch (const Error& e) {
    reply(client, StatusLevel::error, e.message());
    return;
  }
  std::visit(
      [&](const auto& r) {
        using T = std::decay_t<decltype(r)>;
        if constexpr (std::is_same_v<T, Subscribe>) {
          subscribe(client, r);
        } else if constexpr (std::is_same_v<T, Unsubscribe>) {
          unsubscribe(client, r);
        } else if constexpr (std::is_same_v<T, ClientAdvertise>) {
          client_advertise(client, r);
        } else if constexpr (std::is_same_v<T, ClientUnadvertise>) {
          client_unadvertise(client, r);
        } else {
          std::string caps;
          for (const std::string& c : capabilities_) caps += (caps.empty() ? "" : ", ") + c;
          reply(client, StatusLevel::error, "op '" + r.op + "' is not supported by rescuesim (capabilities: " + caps + ")");
        }
      },
      request);
}

void FoxgloveBridge::subscribe(ClientId client, const Subscribe& s) {
  std::vector<std::string> errors;
  {
    std::lock_guard lock(mutex_);
    const auto cit = clients_.find(client);
    if (cit == clients_.end()) return;
    ClientState& cs = cit->second;
    for (const auto& [sub, channel] : s.subscriptions) {
      if (cs.subscriptions.count(sub)) {
        errors.push_back("subscribe: subscription id " + std::to_string(sub) + " is already in use");
        continue;
      }
      const auto it = channels_.find(channel);
      if (it == channels_.end()) {
        errors.push_back("subscribe: unknown channel id " + std::to_string(channel));
        continue;
      }
      ChannelState& c = it->second;
      if (c.subscribers.count(client)) {
        errors.push_back("subscribe: channel " + std::to_string(channel) + " (" + c.channel.topic +
                         ") is already subscribed with subscription id " + std::to_string(c.subscribers.at(client)));
        continue;
      }
      cs.subscriptions[sub] = channel;
      c.subscribers[client] = sub;
      if (c.topic != kNoTopic && static_cast<std::size_t>(c.topic) < kMaxTopics) ++wanted_[static_cast<std::size_t>(c.topic)];
      // latched channels (the scene, /tf_static) start with their last message
      if (c.last) server_->send_data(client, message_data_header(sub, c.last_stamp), c.last);
    }
  }
  for (const auto& e : errors) reply(client, StatusLevel::error, e);
}

void FoxgloveBridge::unsubscribe(ClientId client, const Unsubscribe& u) {
  std::vector<std::string> errors;
  {
    std::lock_guard lock(mutex_);
    const auto cit = clients_.find(client);
    if (cit == clients_.end()) return;
    ClientState& cs = cit->second;
    for (std::uint32_t sub : u.subscription_ids) {
      const auto it = cs.subscriptions.find(sub);
      if (it == cs.subscriptions.end()) {
        errors.push_back("unsubscribe: unknown subscription id " + std::to_string(sub));
        continue;
      }
      auto c = channels_.find(it->second);
      if (c != channels_.end()) {
        c->second.subscribers.erase(client);
        if (c->second.topic != kNoTopic && static_cast<std::size_t>(c->second.topic) < kMaxTopics) {
          --wanted_[static_cast<std::size_t>(c->second.topic)];
        }
      }
      cs.subscriptions.erase(it);
    }
  }
  for (const auto& e : errors) reply(client, StatusLevel::error, e);
}

void FoxgloveBridge::client_advertise(ClientId client, const ClientAdvertise& a) {
  std::vector<std::string> errors;
  {
    std::lock_guard lock(mutex_);
    const auto cit = clients_.find(client);
    if (cit == clients_.end()) return;
    ClientState& cs = cit->second;
    for (const ClientChannel& ch : a.channels) {
      const std::string where = "advertise: channel " + std::to_string(ch.id) + " (" + ch.topic + "): ";
      if (cs.publishers.count(ch.id)) {
        errors.push_back(where + "channel id already advertised; unadvertise it first");
        continue;
      }
      if (ch.encoding != "cdr" && ch.encoding != "json") {
        errors.push_back(where + "encoding '" + ch.encoding + "' is not supported (use cdr or json)");
        continue;
      }
      CommandTarget target;
      target.channel = ch;
      bool found = robot_command(ch.topic, target);
      for (std::size_t i = 0; i < host_inputs_.size() && !found; ++i) {
        if (ch.topic != host_inputs_[i].topic) continue;
        target.type = msg::find_type(host_inputs_[i].type);
        if (target.type == nullptr) break;  // a type with no serialiser here: not taken
        target.kind = CommandTarget::Kind::host;
        target.robot = host_inputs_[i].robot;
        target.host_input = i;
        found = true;
      }
      if (!found) {
        errors.push_back(where + "rescuesim does not take this topic; it takes " + accepted_topics());
        continue;
      }
      // a robot whose moving joints are all driven otherwise (wheels, head) or not at all
      if (target.kind == CommandTarget::Kind::joints && !joints_commandable_[target.robot]) {
        const RobotIndex robot = target.robot;
        // the world may be a step ahead of the command topics (a robot deleted, the layout
        // watchers not called yet)
        const World& world = host_->world();
        errors.push_back(where + "robot '" + (world.has_robot(robot) ? world.robot(robot).name : ch.topic) +
                         "' has no joints that joint_command can drive (drive wheels take cmd_vel, head joints head/command; fixed, "
                         "passive and mimic joints take nothing); it takes " +
                         accepted_topics(robot));
        continue;
      }
      const auto [ros2, ros1] = schema_names(target);
      if (!ch.schema_name.empty() && ch.schema_name != ros2 && ch.schema_name != ros1) {
        errors.push_back(where + "schema '" + ch.schema_name + "' does not match " + ros2);
        continue;
      }
      cs.publishers[ch.id] = std::move(target);
    }
  }
  for (const auto& e : errors) reply(client, StatusLevel::error, e);
}

bool FoxgloveBridge::robot_command(const std::string& topic, CommandTarget& target) const {
  for (RobotIndex r : twist_topics_.indices()) {
    const bool twist = topic == twist_topics_[r];
    const bool head = topic == head_topics_[r] && head_sizes_[r] > 0;
    const bool joints = topic == joint_topics_[r];
    const bool flippers = topic == flipper_topics_[r] && flipper_sizes_[r] > 0;
    if (!twist && !head && !joints && !flippers) continue;
    target.kind = twist      ? CommandTarget::Kind::twist
                  : head     ? CommandTarget::Kind::head
                  : flippers ? CommandTarget::Kind::flippers
                             : CommandTarget::Kind::joints;
    target.robot = r;
    return true;
  }
  return false;
}

void FoxgloveBridge::client_unadvertise(ClientId client, const ClientUnadvertise& u) {
  std::vector<std::string> errors;
  {
    std::lock_guard lock(mutex_);
    const auto cit = clients_.find(client);
    if (cit == clients_.end()) return;
    for (std::uint32_t id : u.channel_ids) {
      if (cit->second.publishers.erase(id) == 0) errors.push_back("unadvertise: unknown client channel id " + std::to_string(id));
    }
  }
  for (const auto& e : errors) reply(client, StatusLevel::error, e);
}

void FoxgloveBridge::on_binary(ClientId client, std::span<const std::uint8_t> bytes) {
  ClientBinary frame;
  try {
    frame = parse_client_binary(bytes);
  } catch (const ServiceCallError& e) {
    return fail_call(client, e.service, e.call, e.message());
  } catch (const Error& e) {
    reject(client, e.message());
    return;
  }
  if (const auto* call = std::get_if<ServiceCallRequest>(&frame)) return service_call(client, *call);
  const ClientMessage& m = std::get<ClientMessage>(frame);
  std::optional<CommandTarget> target;
  std::string gone;
  {
    // the robot's index as the last layout change left it (on_layout); a layout change between
    // here and the host taking the command is not covered: the host moves only commands
    // already queued
    std::lock_guard lock(mutex_);
    const auto cit = clients_.find(client);
    if (cit == clients_.end()) return;
    const auto it = cit->second.publishers.find(m.channel);
    if (it != cit->second.publishers.end()) target = it->second;
    if (target && target->kind != CommandTarget::Kind::host && !target->robot.valid()) {
      gone = target->channel.topic + ": rescuesim does not take this topic now (its robot was deleted); it takes " + accepted_topics();
    }
  }
  if (!target) {
    reject(client, "client message data on unknown channel id " + std::to_string(m.channel) + " (advertise the channel first)");
    return;
  }
  if (!gone.empty()) return reject(client, gone);
  apply(client, *target, m.payload);
}

void FoxgloveBridge::apply(ClientId client, const CommandTarget& target, std::span<const std::uint8_t> payload) {
  const std::string& topic = target.channel.topic;
  try {
    // decoded here; checked, handed to the host and warned about by the gate every bridge shares
    CommandOutcome r;
    if (target.kind == CommandTarget::Kind::twist) {
      r = gate_->velocity(target.robot, topic, decode_twist(target.channel.encoding, payload));
    } else if (target.kind == CommandTarget::Kind::head) {
      r = gate_->head(target.robot, topic, decode_multi_array(target.channel.encoding, payload).data);
    } else if (target.kind == CommandTarget::Kind::flippers) {
      r = gate_->flippers(target.robot, topic, decode_multi_array(target.channel.encoding, payload).data);
    } else if (target.kind == CommandTarget::Kind::host) {
      r = gate_->input(target.host_input, topic, decode_message(target.channel.encoding, *target.type, payload));
    } else {
      r = gate_->joints(target.robot, topic, decode_joint_state(target.channel.encoding, payload));
    }
    if (!r) return reject(client, topic + ": rejected: " + r.reason);
  } catch (const Error& e) {
    return reject(client, topic + ": " + e.message());
  }
  ++received_;
}

void FoxgloveBridge::on_oversize(ClientId client, std::size_t size, bool text) {
  const std::string what = std::string(text ? "text" : "binary") + " message of " + std::to_string(size) + " bytes exceeds the limit of " +
                           std::to_string(options_.max_client_frame) + " bytes and was discarded";
  if (text) {
    reply(client, StatusLevel::error, what);
  } else {
    reject(client, what);
  }
}
}  // namespace rescuesim::foxglove
