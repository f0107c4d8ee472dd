#pragma once
/// A scenario: which world (an SVG drawing or a generated maze), the run's seed and length,
/// and the settings that importers need. Read from YAML (worlds/default.yaml is the built-in
/// default); every key is checked, and errors name the file, line and key path.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "world/maze/maze.h"
#include "world/svg/svg_world.h"
#include "world/world_spec.h"

namespace rescuesim {

/// A scenario as authored.
struct Scenario {
  std::string name = "default";     ///< names the output folder runs/<name>
  std::string source_file;          ///< the YAML it came from ("" = built in)
  std::uint64_t seed = 1;           ///< run seed: maze, noise streams
  double duration = 180.0;          ///< s of sim time

  /// The world comes from exactly one of these.
  std::optional<std::filesystem::path> svg;  ///< resolved against the scenario file's folder
  std::optional<MazeOptions> maze;
  SvgLoadOptions svg_options;       ///< scale and per-kind defaults for SVG worlds
};

/// Parses scenario YAML; `file` names it in messages and resolves relative paths.
/// Throws Error naming the key path for unknown keys, wrong types and impossible values.
Scenario parse_scenario(const std::string& yaml_text, const std::string& file);

/// Reads a scenario file.
Scenario load_scenario(const std::filesystem::path& file);

/// The built-in default scenario (worlds/default.yaml, compiled in).
Scenario default_scenario();

/// Builds the scenario's world: loads the SVG or generates the maze (seeded from the
/// scenario seed unless the maze sets its own), and adds diagnostics from the import.
WorldSpec build_world(const Scenario& scenario, Diagnostics* diagnostics = nullptr);

}  // namespace rescuesim
