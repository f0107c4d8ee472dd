#pragma once
// rescuesim bench, reset part: going back to the start of an episode by restoring a snapshot
// (what Python's Env.reset does with an unchanged seed) beside building the Session again (what
// it did before, and still does for a new seed), and what a snapshot costs the live run.

#include <nlohmann/json.hpp>

#include "import/scenario/scenario.h"

namespace rescuesim::bench {

/// Resets per second of `scenario` (no cameras) by Session::restore, with rebuilding the Session
/// as the baseline (ratio = how many times faster), and the mean Session::snapshot time (ms).
nlohmann::ordered_json bench_reset(const Scenario& scenario, const ModelMap& models);

}  // namespace rescuesim::bench
