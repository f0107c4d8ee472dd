#pragma once
// rescuesim bench, batch part: trials per hour of the default scenario without cameras at one
// and two jobs (beside the same trials run in this process, the cost of a process per trial),
// and the Python API's step overhead (beside the same steps looped in C++).

#include <nlohmann/json.hpp>

#include "import/scenario/scenario.h"

namespace rescuesim::bench {

/// Trials per hour of `scenario` (run to its full duration, no cameras) at --jobs 1 and 2,
/// `trials` trials each, with the in-process rate as the baseline.
nlohmann::ordered_json bench_batch(const Scenario& scenario, int trials);

/// Runs `python3 -m rescuesim.bench_step` on the built Python package and returns its report,
/// or {"error": ...} when the Python API was not built or the run failed.
nlohmann::ordered_json bench_python_step();

}  // namespace rescuesim::bench
