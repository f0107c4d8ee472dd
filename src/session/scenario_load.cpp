#include "session/scenario_load.h"

namespace rescuesim {

void reseed_scenario(Scenario& s, std::uint64_t seed, bool reseed_maze) {
  s.seed = seed;
  if (reseed_maze && s.maze) s.maze->seed = seed;
}

void apply_overrides(Scenario& s, const ScenarioOverrides& o) {
  if (o.seed) reseed_scenario(s, *o.seed);
  if (o.duration) s.duration = *o.duration;
  if (o.rate) s.rate = *o.rate;
  s.resource_paths.insert(s.resource_paths.begin(), o.resource_paths.begin(), o.resource_paths.end());
  // a world given here replaces whatever world the scenario had (a generated maze, an SVG or SDF
  // world, models it included)
  if (!o.world.empty()) {
    s.svg.reset();
    s.maze.reset();
    s.sdf.reset();
    s.includes.clear();
    (is_sdf_path(o.world) ? s.sdf : s.svg) = o.world;
  }
  if (!o.world.empty() || !o.resource_paths.empty()) load_scenario_models(s);
  if (!o.render_quality.empty()) s.render_quality = o.render_quality;
}

Scenario load_scenario_with_overrides(const std::string& file, const ModelMap& models, const ScenarioOverrides& overrides) {
  Scenario s = file.empty() ? default_scenario(models) : load_scenario(file, models);
  apply_overrides(s, overrides);
  return s;
}

}  // namespace rescuesim
