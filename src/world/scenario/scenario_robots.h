#pragma once
// Internal to world/scenario: reading the robots section (sensor and head settings).

#include "world/scenario/scenario.h"
#include "world/scenario/yaml_reader.h"

namespace rescuesim {

/// Reads one entry of `robots:`; `index` names it when it has no name.
RobotConfig read_robot(const YamlNode& node, int index, const ModelMap& models);

}  // namespace rescuesim
