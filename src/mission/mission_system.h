#pragma once
/// The mission as a run system (sim/run_system.h): Mission::after_step after every step, and
/// its memory (referee, radio network, pictures) in a run's snapshots.

#include <any>

#include "mission/mission.h"
#include "sim/run_system.h"

namespace rescuesim {

class MissionSystem final : public RunSystem {
 public:
  explicit MissionSystem(Mission& mission) : mission_(mission) {}
  std::string_view system_name() const override { return "mission"; }
  void post_step(Simulation&) override { mission_.after_step(); }
  std::any save() const override { return mission_.save(); }
  void load(const std::any& memory, Simulation&) override { mission_.load(std::any_cast<const Mission::Memory&>(memory)); }

 private:
  Mission& mission_;
};

}  // namespace rescuesim
