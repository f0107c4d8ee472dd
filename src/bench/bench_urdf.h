#pragma once
// rescuesim bench, URDF part: reading a URDF robot with its meshes (beside loading the same
// mesh files alone), convex hull generation (beside the exact hull without a vertex budget),
// and the real-time factor of the robot beside the built-in rescue robot in the same maze.

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "import/scenario/scenario.h"

namespace rescuesim::bench {

/// Runs a scenario in a child process and reports its real-time factor and peak memory.
using RunChild = std::function<nlohmann::ordered_json(const Scenario&, const ModelMap&)>;

/// The URDF figures for the scenario at `scenario_file` (its first robot must be a URDF
/// robot), run for `sim_seconds`; {"skipped": reason} when the file is missing.
nlohmann::ordered_json bench_urdf(const std::filesystem::path& scenario_file, double sim_seconds, const RunChild& run_child);

}  // namespace rescuesim::bench
