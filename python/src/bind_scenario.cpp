// rescuesim._rescuesim.Scenario: a parsed scenario together with the YAML it came from (the
// text identifies a batch). Read-only from Python: to change one, write new YAML.

#include <pybind11/stl.h>

#include <optional>

#include "bindings.h"
#include "robots/rescue_robot.h"
#include "batch/batch_trial.h"

namespace py = pybind11;

namespace rescuesim::python {

void bind_scenarios(py::module_& m) {
  py::class_<BatchScenario>(m, "Scenario", "A scenario: world (maze or SVG), robots, seed, duration (read-only; see docs/worlds.md)")
      .def_property_readonly("name", [](const BatchScenario& b) { return b.scenario.name; })
      .def_property_readonly("seed", [](const BatchScenario& b) { return b.scenario.seed; }, "run seed: maze and every noise stream")
      .def_property_readonly("duration", [](const BatchScenario& b) { return b.scenario.duration; }, "s of sim time")
      .def_property_readonly("physics_dt", [](const BatchScenario& b) { return b.scenario.physics_dt; }, "s per physics step")
      .def_property_readonly("stop_when_all_found", [](const BatchScenario& b) { return b.scenario.stop_when_all_found; })
      .def_property_readonly("is_maze", [](const BatchScenario& b) { return b.scenario.maze.has_value(); })
      .def_property_readonly("svg", [](const BatchScenario& b) -> std::optional<std::string> {
        if (!b.scenario.svg) return std::nullopt;
        return b.scenario.svg->string();
      })
      .def_property_readonly("robots", [](const BatchScenario& b) {
        std::vector<std::string> names;
        for (const auto& r : b.scenario.robots) names.push_back(r.name);
        return names;
      }, "robot names as the scenario lists them (empty: one default robot per start in the world)")
      .def_property_readonly("text", [](const BatchScenario& b) { return b.text; }, "the YAML it came from")
      .def_property_readonly("file", [](const BatchScenario& b) { return b.file; }, "the file it came from, or <built-in>/<python>")
      .def("__repr__", [](const BatchScenario& b) {
        return "<rescuesim.Scenario '" + b.scenario.name + "' from " + b.file + ", seed " + std::to_string(b.scenario.seed) + ">";
      });
  m.def(
      "load_scenario", [](std::optional<std::string> file) { return load_batch_scenario(file.value_or(""), builtin_models()); },
      py::arg("file") = py::none(), "reads a scenario YAML file (None: the built-in default); raises rescuesim.Error for bad input");
  m.def(
      "parse_scenario", [](const std::string& text, const std::string& file) { return parse_batch_scenario(text, file, builtin_models()); },
      py::arg("text"), py::arg("file") = "<python>",
      "a scenario from YAML text; `file` names it in messages and resolves relative paths");
  m.def("default_scenario_text", &default_scenario_text, "the YAML of the built-in default scenario");
}

}  // namespace rescuesim::python
