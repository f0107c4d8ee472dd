#include "session/sync_gate.h"

#include <chrono>

#include "core/log.h"
#include "sim/simulation.h"

namespace rescuesim {

SyncGate::SyncGate(Simulation& sim, double timeout_s) : sim_(sim), timeout_s_(timeout_s), owed_(sim.velocity_commands()) {
  for (std::size_t r = 0; r < sim_.world().robots.size(); ++r) {
    for (const auto& s : sim_.world().robots[r].spec.sensors) {
      if (!s.enabled || s.type != SensorSpec::Type::lidar) continue;
      subscriptions_.push_back(
          sim_.bus().subscribe(sim_.topic_name(RobotIndex::at(r), s.topic), [this](const Topic&, const msg::Message&) { ++owed_; }));
    }
  }
}

SyncGate::~SyncGate() {
  for (SubscriptionId h : subscriptions_) sim_.bus().unsubscribe(h);
}

void SyncGate::wait() {
  if (sim_.velocity_commands() >= owed_) return;
  if (!sim_.wait_for_velocity_commands(owed_, std::chrono::duration<double>(timeout_s_))) {
    if (timeouts_++ == 0) {
      log::warn("sync: no cmd_vel answered the scan at {:.2f} s within {} s of wall time; stepping on (a controller that is "
                "not there yet, or does not answer every scan)",
                sim_.time().seconds(), timeout_s_);
    }
    owed_ = sim_.velocity_commands();  // what was missed is not owed any more
  }
}

}  // namespace rescuesim
