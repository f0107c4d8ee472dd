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
  // an SVG world replaces whatever world the scenario had, a generated maze included
  if (!o.world_svg.empty()) {
    s.svg = o.world_svg;
    s.maze.reset();
  }
  if (!o.render_quality.empty()) s.render_quality = o.render_quality;
}

Scenario load_scenario_with_overrides(const std::string& file, const ModelMap& models, const ScenarioOverrides& overrides) {
  Scenario s = file.empty() ? default_scenario(models) : load_scenario(file, models);
  apply_overrides(s, overrides);
  return s;
}

}  // namespace rescuesim
