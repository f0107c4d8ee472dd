#pragma once
// Internal to the extension: the parts of the module, each bound in its own file.

#include <pybind11/pybind11.h>

namespace rescuesim::python {

/// rescuesim._rescuesim.Scenario and the functions that make one (bind_scenario.cpp).
void bind_scenarios(pybind11::module_& m);
/// EnvOptions, EnvCore, VecEnvCore (module.cpp).
void bind_environments(pybind11::module_& m);
/// EnvCore's mission calls: report, send, inbox, comms_status, drop_relay, mission_score (bind_mission.cpp).
void add_mission_methods(pybind11::class_<class EnvCore>& cls);
/// EnvCore's control calls: entities, entity_state, set_entity_state, state_hash, simulator_features,
/// spawn, delete (bind_control.cpp; session/run_control.h beneath).
void add_control_methods(pybind11::class_<class EnvCore>& cls);
/// TrialOptions, run_trial, ResultsFile, merge_results, ... (bind_batch.cpp).
void bind_batch(pybind11::module_& m);

}  // namespace rescuesim::python
