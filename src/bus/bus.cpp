#include "bus/bus.h"

#include <string>

#include "core/error.h"

namespace rescuesim {

namespace {

/// Counts a delivery under way for as long as it lives (exceptions included).
class Delivering {
 public:
  explicit Delivering(int& depth) : depth_(depth) { ++depth_; }
  ~Delivering() { --depth_; }
  Delivering(const Delivering&) = delete;
  Delivering& operator=(const Delivering&) = delete;

 private:
  int& depth_;
};

}  // namespace

void Bus::demand_unlocked(const char* function) const {
  if (delivering_ > 0) {
    const std::string why = std::string("Bus::") + function +
                            ": called from inside a subscriber callback; the Bus is locked while it delivers (subscribe, "
                            "unsubscribe and advertise before publishing starts, or between publishes)";
    demand_failed("delivering_ == 0", __FILE__, __LINE__, why.c_str());
  }
}

std::size_t Bus::index(TopicId topic, const char* function) const {
  const auto t = static_cast<std::size_t>(topic);
  if (topic == kNoTopic || t >= topics_.size()) {
    const std::string why = std::string("Bus::") + function + ": no topic " + std::to_string(static_cast<int>(topic)) +
                            " (this Bus has " + std::to_string(topics_.size()) + ")";
    demand_failed("topic < topics().size()", __FILE__, __LINE__, why.c_str());
  }
  return t;
}

TopicId Bus::advertise(const std::string& name, const std::string& type, double rate, bool latched, RobotIndex robot) {
  demand_unlocked("advertise");
  const TopicId existing = find(name);
  if (existing != kNoTopic) {
    Topic& t = topics_[static_cast<std::size_t>(existing)];
    if (t.type != type) {
      throw Error({"", 0, "topic " + name}, "advertised as " + type + " but it already carries " + t.type);
    }
    if (robot.valid()) t.robot = robot;  // a robot's index changes when a robot before it is removed
    if (t.retired) {
      // back (a robot of that name spawned again): with this advertisement's description
      t.rate = rate;
      t.latched = latched;
      t.robot = robot;
      t.retired = false;
    }
    return existing;
  }
  const TopicId id{static_cast<int>(topics_.size())};
  topics_.push_back({id, name, type, rate, latched, robot, false});
  counts_.push_back(0);
  latched_.emplace_back();
  rebuild_index();
  return id;
}

void Bus::publish(TopicId topic, msg::Message message) {
  const std::size_t t = index(topic, "publish");
  const Delivering lock(delivering_);
  ++counts_[t];
  // moved (not copied) into a shared message only when someone keeps it
  SharedMessage shared;
  if (shared_subscribers_[t] > 0 || topics_[t].latched) shared = std::make_shared<const msg::Message>(std::move(message));
  const msg::Message& m = shared ? *shared : message;
  for (std::size_t s : subscribers_of_[t]) {
    const Subscriber& sub = subscribers_[s];
    if (const auto* keep = std::get_if<SharedCallback>(&sub.callback)) {
      (*keep)(topics_[t], shared);
    } else {
      std::get<Callback>(sub.callback)(topics_[t], m);
    }
  }
  if (topics_[t].latched) latched_[t] = std::move(shared);
}

SubscriptionId Bus::subscribe(const std::string& name, Callback callback) { return add(name, std::move(callback)); }

SubscriptionId Bus::subscribe_shared(const std::string& name, SharedCallback callback) { return add(name, std::move(callback)); }

SubscriptionId Bus::add(const std::string& name, std::variant<Callback, SharedCallback> callback) {
  demand_unlocked("subscribe");
  const SubscriptionId handle{next_handle_++};
  subscribers_.push_back({handle, name, std::move(callback)});
  rebuild_index();
  deliver_latched(subscribers_.back());
  return handle;
}

void Bus::deliver_latched(const Subscriber& s) {
  // latched topics replay their last message to the newcomer (locked: the newcomer is
  // subscribers_.back(), which a subscribe from its callback would move)
  const Delivering lock(delivering_);
  for (std::size_t t = 0; t < topics_.size(); ++t) {
    if (!latched_[t] || !(s.name.empty() || s.name == topics_[t].name)) continue;
    if (const auto* keep = std::get_if<SharedCallback>(&s.callback)) {
      (*keep)(topics_[t], latched_[t]);
    } else {
      std::get<Callback>(s.callback)(topics_[t], *latched_[t]);
    }
  }
}

void Bus::retire(TopicId topic) {
  demand_unlocked("retire");
  const std::size_t t = index(topic, "retire");
  topics_[t].retired = true;
  latched_[t].reset();
}

SubscriptionId Bus::watch_layout(std::function<void()> callback) {
  demand_unlocked("watch_layout");
  const SubscriptionId handle{next_handle_++};
  layout_watchers_.emplace_back(handle, std::move(callback));
  return handle;
}

void Bus::layout_changed() {
  demand_unlocked("layout_changed");
  ++layout_version_;
  const Delivering lock(delivering_);
  for (const auto& [handle, callback] : layout_watchers_) callback();
}

void Bus::unsubscribe(SubscriptionId handle) {
  demand_unlocked("unsubscribe");
  std::erase_if(layout_watchers_, [&](const auto& w) { return w.first == handle; });
  for (std::size_t i = 0; i < subscribers_.size(); ++i) {
    if (subscribers_[i].handle == handle) {
      subscribers_.erase(subscribers_.begin() + static_cast<long>(i));
      break;
    }
  }
  rebuild_index();
}

const Topic& Bus::topic(TopicId id) const { return topics_[index(id, "topic")]; }

TopicId Bus::find(const std::string& name) const {
  for (const auto& t : topics_) {
    if (t.name == name) return t.id;
  }
  return kNoTopic;
}

std::uint64_t Bus::count(TopicId topic) const { return counts_[index(topic, "count")]; }

void Bus::rebuild_index() {
  subscribers_of_.assign(topics_.size(), {});
  shared_subscribers_.assign(topics_.size(), 0);
  for (std::size_t s = 0; s < subscribers_.size(); ++s) {
    for (std::size_t t = 0; t < topics_.size(); ++t) {
      if (subscribers_[s].name.empty() || subscribers_[s].name == topics_[t].name) {
        subscribers_of_[t].push_back(s);
        if (std::holds_alternative<SharedCallback>(subscribers_[s].callback)) ++shared_subscribers_[t];
      }
    }
  }
}

}  // namespace rescuesim
