#pragma once
/// A scenario as the user asked for it: loaded from YAML (or the built-in default), then changed
/// by command-line style overrides. One place for "the seed override also reseeds a generated
/// maze", so that `rescuesim run`, `snapshot`, `view`, batches and Python agree on what a seed
/// means.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "import/scenario/scenario.h"

namespace rescuesim {

/// What a command line may change in a scenario after loading it; unset fields leave the
/// scenario's own settings.
struct ScenarioOverrides {
  std::optional<std::uint64_t> seed;      ///< run seed; also the generated maze's seed
  std::optional<double> duration;         ///< s of sim time
  std::optional<double> rate;             ///< realtime pace: sim seconds per wall second
  /// non-empty: this world (an SVG drawing, or an SDF world: .sdf, .world) instead of the
  /// scenario's, which is dropped with its includes
  std::string world;
  /// folders searched first for package:// and model:// URIs, before the scenario's own
  std::vector<std::string> resource_paths;
  std::string render_quality;             ///< non-empty: low, medium or high
};

/// Sets the run seed of `s` and, when `reseed_maze` and the world is a generated maze, the
/// maze's seed too (a fixed maze with fresh sensor noise: reseed_maze = false).
void reseed_scenario(Scenario& s, std::uint64_t seed, bool reseed_maze = true);

/// Applies every set override to `s` (seed through reseed_scenario).
void apply_overrides(Scenario& s, const ScenarioOverrides& overrides);

/// The scenario in `file` (empty: the built-in default, worlds/default.yaml) with `overrides`
/// applied. Throws Error naming the file and element for bad YAML, like load_scenario.
Scenario load_scenario_with_overrides(const std::string& file, const ModelMap& models, const ScenarioOverrides& overrides = {});

}  // namespace rescuesim
