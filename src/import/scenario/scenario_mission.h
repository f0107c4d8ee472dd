#pragma once
// Internal to import/scenario: reading the `mission:` block.

#include "import/scenario/yaml_reader.h"
#include "world/mission_spec.h"

namespace rescuesim {

/// Reads a scenario's `mission:` mapping: `rules` (a preset, robocup or subt) and any of its
/// values, `radio` (model, link_rate, relays_per_robot, antenna_height and the model's own
/// parameters) and `base` ({x, y, z}) or `bases` ([{name, x, y, z}]). Throws Error naming the
/// key for unknown keys, out-of-range values and impossible radio parameters.
MissionSpec read_mission(const YamlNode& node);

}  // namespace rescuesim
