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
  has_latched_.push_back(false);
  rebuild_index();
  return id;
}

void Bus::publish(int topic, msg::Message message) {
  const auto t = static_cast<std::size_t>(topic);
  ++counts_[t];
  for (int s : subscribers_of_[t]) subscribers_[static_cast<std::size_t>(s)].callback(topics_[t], message);
  if (topics_[t].latched) {
    latched_[t] = std::move(message);
    has_latched_[t] = true;
  }
}

int Bus::subscribe(const std::string& name, Callback callback) {
  const int handle = next_handle_++;
  subscribers_.push_back({handle, name, std::move(callback)});
  rebuild_index();
  // latched topics replay their last message to the newcomer
  for (std::size_t t = 0; t < topics_.size(); ++t) {
    if (has_latched_[t] && (name.empty() || name == topics_[t].name)) subscribers_.back().callback(topics_[t], latched_[t]);
  }
  return handle;
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
  for (std::size_t s = 0; s < subscribers_.size(); ++s) {
    for (auto& t : topics_) {
      if (subscribers_[s].name.empty() || subscribers_[s].name == t.name) subscribers_of_[static_cast<std::size_t>(t.id)].push_back(static_cast<int>(s));
    }
  }
}

}  // namespace rescuesim
