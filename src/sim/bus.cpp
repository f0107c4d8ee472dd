#include "sim/bus.h"

#include "core/error.h"

namespace rescuesim {

int Bus::advertise(const std::string& name, const std::string& type, double rate, bool latched, int robot) {
  const int existing = find(name);
  if (existing >= 0) {
    if (topics_[static_cast<std::size_t>(existing)].type != type) {
      throw Error({"", 0, "topic " + name}, "advertised as " + type + " but it already carries " + topics_[static_cast<std::size_t>(existing)].type);
    }
    return existing;
  }
  const int id = static_cast<int>(topics_.size());
  topics_.push_back({id, name, type, rate, latched, robot});
  counts_.push_back(0);
  latched_.emplace_back();
  rebuild_index();
  return id;
}

void Bus::publish(int topic, msg::Message message) {
  const auto t = static_cast<std::size_t>(topic);
  ++counts_[t];
  // moved (not copied) into a shared message only when someone keeps it
  SharedMessage shared;
  if (shared_subscribers_[t] > 0 || topics_[t].latched) shared = std::make_shared<const msg::Message>(std::move(message));
  const msg::Message& m = shared ? *shared : message;
  for (int s : subscribers_of_[t]) {
    const Subscriber& sub = subscribers_[static_cast<std::size_t>(s)];
    if (sub.shared) {
      sub.shared(topics_[t], shared);
    } else {
      sub.callback(topics_[t], m);
    }
  }
  if (topics_[t].latched) latched_[t] = std::move(shared);
}

int Bus::subscribe(const std::string& name, Callback callback) {
  subscribers_.push_back({next_handle_++, name, std::move(callback), nullptr});
  rebuild_index();
  deliver_latched(subscribers_.back());
  return subscribers_.back().handle;
}

int Bus::subscribe_shared(const std::string& name, SharedCallback callback) {
  subscribers_.push_back({next_handle_++, name, nullptr, std::move(callback)});
  rebuild_index();
  deliver_latched(subscribers_.back());
  return subscribers_.back().handle;
}

void Bus::deliver_latched(Subscriber& s) {
  // latched topics replay their last message to the newcomer
  for (std::size_t t = 0; t < topics_.size(); ++t) {
    if (!latched_[t] || !(s.name.empty() || s.name == topics_[t].name)) continue;
    if (s.shared) {
      s.shared(topics_[t], latched_[t]);
    } else {
      s.callback(topics_[t], *latched_[t]);
    }
  }
}

void Bus::unsubscribe(int handle) {
  for (std::size_t i = 0; i < subscribers_.size(); ++i) {
    if (subscribers_[i].handle == handle) {
      subscribers_.erase(subscribers_.begin() + static_cast<long>(i));
      break;
    }
  }
  rebuild_index();
}

int Bus::find(const std::string& name) const {
  for (const auto& t : topics_) {
    if (t.name == name) return t.id;
  }
  return -1;
}

void Bus::rebuild_index() {
  subscribers_of_.assign(topics_.size(), {});
  shared_subscribers_.assign(topics_.size(), 0);
  for (std::size_t s = 0; s < subscribers_.size(); ++s) {
    for (auto& t : topics_) {
      if (subscribers_[s].name.empty() || subscribers_[s].name == t.name) {
        subscribers_of_[static_cast<std::size_t>(t.id)].push_back(static_cast<int>(s));
        if (subscribers_[s].shared) ++shared_subscribers_[static_cast<std::size_t>(t.id)];
      }
    }
  }
}

}  // namespace rescuesim
