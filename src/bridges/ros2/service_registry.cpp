#include "bridges/ros2/service_registry.h"

#include <algorithm>

#include "core/error.h"

namespace rescuesim::ros2 {

ServiceRegistry::ServiceRegistry(DdsParticipant& dds, std::function<std::int64_t()> now_ns) : dds_(dds), now_ns_(std::move(now_ns)) {}

ServiceRegistry::~ServiceRegistry() = default;

void ServiceRegistry::check_new(const std::string& name) const {
  // under mutex_: a service name is served once, whether on its own or inside an action
  for (const auto& s : services_) {
    if (s->topics().name == name) throw Error("ROS 2 bridge: service " + name + " is registered already");
  }
  for (const auto& a : actions_) {
    const ActionTopics& t = a->topics();
    if (t.name == name || t.send_goal.name == name || t.cancel_goal.name == name || t.get_result.name == name) {
      throw Error("ROS 2 bridge: " + name + " is taken by action " + t.name);
    }
  }
}

void ServiceRegistry::changed() {
  std::function<void()> f;
  {
    std::lock_guard lock(mutex_);
    f = on_change_;
  }
  if (f) f();
}

ServiceServer& ServiceRegistry::add_service(const std::string& ros_name, const std::string& srv_type, ServiceHandler handler) {
  return add_service(service_topics(ros_name, srv_type), std::move(handler));
}

ServiceServer& ServiceRegistry::add_service(ServiceTopics topics, ServiceHandler handler) {
  if (!handler) throw Error("ROS 2 bridge: service " + topics.name + " has no handler");
  ServiceServer* server = nullptr;
  {
    std::lock_guard lock(mutex_);
    check_new(topics.name);
    services_.push_back(std::make_unique<ServiceServer>(dds_, std::move(topics), std::move(handler)));
    server = services_.back().get();
  }
  changed();
  return *server;
}

ActionServer& ServiceRegistry::add_action(const std::string& ros_name, const std::string& action_type, ActionCallbacks callbacks,
                                          ActionOptions options) {
  ActionTopics topics = action_topics(ros_name, action_type);
  if (!options.now_ns) options.now_ns = now_ns_;
  ActionServer* server = nullptr;
  {
    std::lock_guard lock(mutex_);
    for (const std::string& n : {topics.name, topics.send_goal.name, topics.cancel_goal.name, topics.get_result.name}) check_new(n);
    actions_.push_back(std::make_unique<ActionServer>(dds_, std::move(topics), std::move(callbacks), std::move(options)));
    server = actions_.back().get();
  }
  changed();
  return *server;
}

void ServiceRegistry::poll() {
  std::vector<ServiceServer*> services;
  std::vector<ActionServer*> actions;
  {
    std::lock_guard lock(mutex_);
    for (const auto& s : services_) services.push_back(s.get());
    for (const auto& a : actions_) actions.push_back(a.get());
  }
  const auto now = std::chrono::steady_clock::now();
  for (ServiceServer* s : services) s->poll(now);
  for (ActionServer* a : actions) a->poll(now);
}

std::chrono::milliseconds ServiceRegistry::poll_within(std::chrono::milliseconds longest) const {
  std::optional<std::chrono::steady_clock::time_point> next;
  const auto earliest = [&](std::optional<std::chrono::steady_clock::time_point> t) {
    if (t && (!next || *t < *next)) next = t;
  };
  {
    std::lock_guard lock(mutex_);
    for (const auto& s : services_) earliest(s->next_poll());
    for (const auto& a : actions_) earliest(a->next_poll());
  }
  if (!next) return longest;
  const auto left = std::chrono::ceil<std::chrono::milliseconds>(*next - std::chrono::steady_clock::now());
  return std::clamp(left, std::chrono::milliseconds(0), longest);
}

void ServiceRegistry::spin_once(std::chrono::milliseconds max_wait) {
  dds_.wait(poll_within(max_wait));
  poll();
}

std::vector<Guid> ServiceRegistry::reader_guids() const {
  std::lock_guard lock(mutex_);
  std::vector<Guid> out;
  for (const auto& s : services_) out.push_back(s->request_reader_guid());
  for (const auto& a : actions_) {
    for (const Guid& g : a->reader_guids()) out.push_back(g);
  }
  return out;
}

std::vector<Guid> ServiceRegistry::writer_guids() const {
  std::lock_guard lock(mutex_);
  std::vector<Guid> out;
  for (const auto& s : services_) out.push_back(s->reply_writer_guid());
  for (const auto& a : actions_) {
    for (const Guid& g : a->writer_guids()) out.push_back(g);
  }
  return out;
}

std::uint64_t ServiceRegistry::malformed() const {
  std::lock_guard lock(mutex_);
  std::uint64_t n = 0;
  for (const auto& s : services_) n += s->malformed();
  for (const auto& a : actions_) n += a->malformed();
  return n;
}

std::size_t ServiceRegistry::size() const {
  std::lock_guard lock(mutex_);
  return services_.size() + actions_.size();
}

void ServiceRegistry::set_on_change(std::function<void()> f) {
  std::lock_guard lock(mutex_);
  on_change_ = std::move(f);
}

}  // namespace rescuesim::ros2
