#pragma once
// rescuesim bench, SDF part: reading an SDF world (beside loading its mesh files alone), and lidar
// rays/s through a 100k-triangle static mesh beside the same scene built from primitives.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

namespace rescuesim::bench {

/// The SDF figures: `world_file` read with `resource_paths` (median of 5); rays cast for
/// `seconds` through each of the two scenes. {"skipped": reason} when the file is missing.
nlohmann::ordered_json bench_sdf(const std::filesystem::path& world_file, const std::vector<std::filesystem::path>& resource_paths,
                                 double seconds);

}  // namespace rescuesim::bench
