#include "world/resource_uri.h"

#include <cstdlib>
#include <system_error>

namespace rescuesim {

namespace fs = std::filesystem;

namespace {

/// The entries of a colon-separated environment variable (empty ones dropped).
std::vector<fs::path> env_list(const char* name) {
  std::vector<fs::path> out;
  const char* v = std::getenv(name);
  if (!v) return out;
  std::string s = v;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = s.find(':', start);
    const std::string item = s.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!item.empty()) out.emplace_back(item);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

std::string quoted_list(const std::vector<fs::path>& paths) {
  std::string out;
  for (const auto& p : paths) out += "\n  " + p.string();
  return out.empty() ? "\n  (nowhere: no resource_paths, ROS_PACKAGE_PATH or AMENT_PREFIX_PATH set)" : out;
}

}  // namespace

ResourceResolver::ResourceResolver(std::vector<fs::path> search, bool use_environment)
    : search_(std::move(search)), use_environment_(use_environment) {}

std::vector<fs::path> ResourceResolver::package_candidates(const std::string& package) const {
  // a folder holds packages as sub-folders (like a ROS workspace's src) or is the package itself
  std::vector<fs::path> out;
  auto add_root = [&](const fs::path& root) {
    out.push_back(root / package);
    if (root.filename() == package) out.push_back(root);
  };
  for (const auto& root : search_) add_root(root);
  if (use_environment_) {
    for (const auto& root : env_list("ROS_PACKAGE_PATH")) add_root(root);
    for (const auto& prefix : env_list("AMENT_PREFIX_PATH")) out.push_back(prefix / "share" / package);
  }
  return out;
}

std::vector<fs::path> ResourceResolver::model_candidates(const std::string& name) const {
  std::vector<fs::path> out = package_candidates(name);
  if (use_environment_) {
    for (const char* var : {"GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "GAZEBO_MODEL_PATH"}) {
      for (const auto& root : env_list(var)) out.push_back(root / name);
    }
  }
  return out;
}

fs::path ResourceResolver::resolve(const std::string& uri, const SourceRef& where) const {
  const fs::path base = where.file.empty() ? fs::current_path() : fs::path(where.file).parent_path();
  auto fail = [&](const std::string& why) -> fs::path { throw Error(where, "cannot find '" + uri + "': " + why); };
  if (uri.empty()) return fail("the URI is empty");

  for (const char* scheme : {"package://", "model://"}) {
    const std::string prefix = scheme;
    if (uri.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = uri.substr(prefix.size());
    const std::size_t slash = rest.find('/');
    const std::string package = rest.substr(0, slash);
    const std::string inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
    if (package.empty()) return fail("no package name after " + prefix);
    const std::vector<fs::path> roots = prefix == "model://" ? model_candidates(package) : package_candidates(package);
    std::vector<fs::path> tried;
    for (const auto& root : roots) {
      const fs::path candidate = inside.empty() ? root : root / inside;
      tried.push_back(candidate);
      if (is_file(candidate)) return candidate;
    }
    return fail("searched" + quoted_list(tried) + "\n(add the folder holding '" + package +
                "' to the scenario's resource_paths, or to ROS_PACKAGE_PATH)");
  }
  if (uri.compare(0, 7, "file://") == 0) {
    const fs::path p = uri.substr(7);
    const fs::path full = p.is_absolute() ? p : base / p;
    if (is_file(full)) return full;
    return fail("no such file " + full.string());
  }
  if (uri.find("://") != std::string::npos) return fail("only package://, model://, file:// and plain paths are understood");
  const fs::path p = uri;
  const fs::path full = p.is_absolute() ? p : base / p;
  if (is_file(full)) return full;
  return fail("no such file " + full.string() + " (relative paths are taken from the folder of " +
              (where.file.empty() ? std::string("the working directory") : where.file) + ")");
}

}  // namespace rescuesim
