#pragma once
// rescuesim bench, control part (issue 37): what the ROS 2 control surface costs a client on
// loopback. ResetSimulation and StepSimulation(1) round trips, each beside the same operation
// done in-process (Session::restore, one Session step), and a SimulateSteps action beside the
// same steps run lockstep in the same process.

#include <cstdint>

#include <nlohmann/json.hpp>

#include "import/scenario/scenario.h"

namespace rescuesim::bench {

struct BenchControlOptions {
  int resets = 200;                      ///< timed ResetSimulation calls (and Session::restore calls)
  int steps_between_resets = 20;         ///< untimed StepSimulation steps before each reset, so each has work to do
  int steps = 500;                       ///< timed StepSimulation(1) calls (and in-process steps)
  std::uint64_t action_steps = 10'000;   ///< steps of each SimulateSteps goal (and of each lockstep run)
  int action_rounds = 3;                 ///< action and lockstep runs, alternating (the medians count)
  int spawns = 20;                       ///< timed SpawnEntity + DeleteEntity pairs of a rescue robot (and in-process ones)
};

/// The control figures on the default scenario (no cameras, no built-in controllers, started
/// PAUSED, the ROS 2 bridge on a loopback-only Cyclone domain of its own), in a child process
/// whose peak memory is reported: "reset_simulation", "step_simulation", "simulate_steps", "spawn_entity",
/// "peak_memory_mb". Without the ROS 2 bridge in this build: {"skipped": reason}.
nlohmann::ordered_json bench_control(const Scenario& scenario, const ModelMap& models, const BenchControlOptions& options);

}  // namespace rescuesim::bench
