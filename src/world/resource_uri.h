#pragma once
/// Where `package://`, `model://`, `file://` and relative URIs in robot and world descriptions
/// point: searched in the scenario's resource paths first, then the ROS environment
/// (ROS_PACKAGE_PATH, AMENT_PREFIX_PATH's share/<pkg>) and, for model://, Gazebo's
/// (GZ_SIM_RESOURCE_PATH, IGN_GAZEBO_RESOURCE_PATH, GAZEBO_MODEL_PATH). An unresolved URI is an
/// Error naming the URI, the file and line that used it, and every place searched.

#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"

namespace rescuesim {

/// Finds the files that URIs name.
class ResourceResolver {
 public:
  /// Only the environment's folders (ROS and Gazebo variables).
  ResourceResolver() = default;
  /// `search` are folders searched first (a scenario's resource_paths, already absolute or
  /// relative to the working directory); `use_environment` adds the ROS and Gazebo variables.
  explicit ResourceResolver(std::vector<std::filesystem::path> search, bool use_environment = true);

  /// The file a URI names. `where` is the referring file and element (relative URIs resolve
  /// against the folder of where.file). Throws Error when nothing matches.
  std::filesystem::path resolve(const std::string& uri, const SourceRef& where) const;

  /// The folders a `package://<pkg>/...` URI is looked for in, in order (for messages and docs).
  std::vector<std::filesystem::path> package_candidates(const std::string& package) const;

  /// The folders a `model://<name>` URI is looked for in, in order: package_candidates, then
  /// <dir>/<name> for each folder of GZ_SIM_RESOURCE_PATH, IGN_GAZEBO_RESOURCE_PATH and
  /// GAZEBO_MODEL_PATH (when the environment is used).
  std::vector<std::filesystem::path> model_candidates(const std::string& name) const;

  const std::vector<std::filesystem::path>& search_paths() const { return search_; }

 private:
  std::vector<std::filesystem::path> search_;
  bool use_environment_ = true;
};

}  // namespace rescuesim
