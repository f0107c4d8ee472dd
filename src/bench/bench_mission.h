#pragma once
// rescuesim bench, mission part: what the referee and the radio cost. The team scenario's
// real-time factor with its mission beside the same scenario without one, and the cost of one
// link update (every pair of radios, walls counted through the ray scene) as the team grows.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "bench/bench_urdf.h"  // RunChild

namespace rescuesim::bench {

/// The mission figures of `scenario_file` (worlds/team.yaml): its run for `sim_seconds` with
/// and without its mission (median of 3 each, alternating), and µs per link update for 4, 10
/// and 30 radios in its world. {"skipped": reason} when the file is missing or has no mission.
nlohmann::ordered_json bench_mission(const std::filesystem::path& scenario_file, double sim_seconds, const RunChild& run_child);

}  // namespace rescuesim::bench
