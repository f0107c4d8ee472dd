#pragma once
/// The mission as a run system (sim/run_system.h): Mission::after_step after every step, its
/// memory (referee, radio network, pictures) in a run's snapshots, and its outputs when the run
/// ends: score.png and reports/ (mission_outputs.cpp).

#include <any>

#include <string>
#include <vector>

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
  /// score.png (the score over the run) and each report's picture in reports/.
  void write_outputs(const Simulation& sim, RunOutputs& out) const override;

 private:
  Mission& mission_;
};

/// Where a report's picture is written, relative to the output folder: the report's id, robot
/// and outcome ("reports/3_r1_accepted.png").
std::string report_picture_file(const ReportPicture& p, const std::vector<std::string>& robot_names);

}  // namespace rescuesim
