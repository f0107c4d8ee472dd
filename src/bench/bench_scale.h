#pragma once
// rescuesim bench --scale: the scale scenario (bench/scale_scenario.h) for N robots
// in turn, each run in a child process: real-time factor, lidar rays/s, peak memory and CPU use
// per core, beside the ideal of N robots costing N times one robot, as JSON and a PNG plot.

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_urdf.h"  // RunChild

namespace rescuesim::bench {

/// Runs the scale scenario for each count of `robots` (`sim_seconds` each, lockstep, no
/// cameras) through `run_child` and returns {"robots": [...], "runs": [{robots, real_time_factor,
/// rays_per_s, peak_memory_mb, cpu_per_core, scaling, ...}]}. `scaling` is the real-time factor
/// over the ideal one, RTF(1 robot) / N (1 when N robots cost exactly N times one; the first
/// count's run stands in for one robot when 1 is not among them). Writes the plot to `png`
/// when not empty.
nlohmann::ordered_json bench_scale(const std::vector<int>& robots, double sim_seconds, const RunChild& run_child,
                                   const std::filesystem::path& png);

}  // namespace rescuesim::bench
