#pragma once
/// SyncGate: a run synchronous with an outside controller (SessionOptions::sync_timeout, like
/// Webots' synchronous mode). Every laser scan published owes the simulation one velocity
/// command; before each step wait() blocks until every scan so far is answered, or gives up
/// after the timeout (what was missed is then not owed any more, and the first such timeout is
/// logged). The Bus counts scans on the stepping thread, as they are published, before any
/// bridge sends them, so a controller cannot answer a scan before it is owed.

#include <cstdint>
#include <vector>

#include "bus/bus.h"

namespace rescuesim {

class Simulation;

class SyncGate {
 public:
  /// Listens to every enabled lidar of `sim`'s robots now; `timeout_s` wall seconds per wait.
  SyncGate(Simulation& sim, double timeout_s);
  ~SyncGate();
  SyncGate(const SyncGate&) = delete;
  SyncGate& operator=(const SyncGate&) = delete;

  /// Waits until the commands owed have come, or the timeout.
  void wait();
  /// Scans waited for in vain so far.
  std::uint64_t timeouts() const { return timeouts_; }

 private:
  Simulation& sim_;
  double timeout_s_;
  std::uint64_t owed_;
  std::uint64_t timeouts_ = 0;
  std::vector<SubscriptionId> subscriptions_;
};

}  // namespace rescuesim
