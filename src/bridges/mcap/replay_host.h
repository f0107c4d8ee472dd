#pragma once
/// ReplayHost: what bridges attach to during `rescuesim replay` — a Bus, the recorded run's
/// World and a clock the player sets to each message's log time. Nothing is simulated: there
/// is no physics engine and no ray scene, and the state is the world's start (rubble where the
/// world puts it, no victim found). Commands that bridges take in are counted and discarded.

#include <atomic>
#include <cstdint>

#include "bus/bridge_host.h"

namespace rescuesim {

class ReplayHost final : public BridgeHost {
 public:
  /// `world`: the recorded run's compiled world (robot names and specs); `seed`: the run's.
  ReplayHost(const World& world, std::uint64_t seed);

  /// Moves the clock (the player does, before publishing a message logged at `t`).
  void set_time(SimTime t) { state_.time = t; }
  /// Commands bridges handed in and that were discarded, so far (any thread).
  std::uint64_t discarded() const { return discarded_.load(); }

  Bus& bus() override { return bus_; }
  const World& world() const override { return world_; }
  const State& state() const override { return state_; }
  SimTime time() const override { return state_.time; }
  std::uint64_t seed() const override { return seed_; }
  HostFrames frames() const override { return {}; }
  std::string topic_name(RobotIndex robot, const std::string& relative) const override;
  std::string frame_name(RobotIndex robot, const std::string& frame) const override;
  /// Counted and discarded (accepted: a replay has nothing to apply them to, and says so once).
  CommandOutcome command_velocity(RobotIndex robot, const msg::Twist& twist) override;
  CommandOutcome command_head(RobotIndex robot, const std::vector<double>& positions) override;
  CommandOutcome command_joints(RobotIndex robot, const msg::JointState& command) override;

 private:
  const World& world_;
  std::uint64_t seed_;
  State state_;
  Bus bus_;
  std::atomic<std::uint64_t> discarded_{0};
};

}  // namespace rescuesim
