#pragma once
// Internal to import/scenario: reading the robots section (sensor and head settings).

#include "import/scenario/scenario.h"
#include "import/scenario/yaml_reader.h"

namespace rescuesim {

/// What reading a robot entry needs to know about its scenario.
struct RobotReadContext {
  std::string file;                                   ///< the scenario file ("" or "<built-in>": none)
  std::vector<std::filesystem::path> resource_paths;  ///< where package:// looks first (absolute)
};

/// Reads one entry of `robots:`; `index` names it when it has no name.
RobotConfig read_robot(const YamlNode& node, int index, const ModelMap& models, const RobotReadContext& context = {});

}  // namespace rescuesim
