#include "app/data_dir.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <system_error>

#include "core/error.h"

#ifndef RESCUESIM_SOURCE_DATA_DIR
#define RESCUESIM_SOURCE_DATA_DIR ""
#endif
#ifndef RESCUESIM_BUILD_DIR
#define RESCUESIM_BUILD_DIR ""
#endif
#ifndef RESCUESIM_INSTALL_DATA_DIR
#define RESCUESIM_INSTALL_DATA_DIR ""
#endif

namespace rescuesim::app {

namespace fs = std::filesystem;

namespace {

bool is_data_dir(const fs::path& p) {
  std::error_code ec;
  return !p.empty() && fs::is_directory(p / "worlds", ec);
}

std::string g_argv0;  // set_program_path

/// The running executable's own path (/proc/self/exe; else argv[0] as the shell resolved it),
/// or "" when neither tells.
fs::path executable() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) return exe;
  if (g_argv0.empty()) return {};
  if (g_argv0.find('/') != std::string::npos) return fs::weakly_canonical(fs::absolute(g_argv0, ec), ec);
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / g_argv0;
    if (end > start && ::access(candidate.c_str(), X_OK) == 0) return fs::weakly_canonical(candidate, ec);
    start = end + 1;
  }
  return {};
}

}  // namespace

void set_program_path(const char* argv0) { g_argv0 = argv0 ? argv0 : ""; }

fs::path sibling_program(const std::string& name) {
  const fs::path exe = executable();
  return exe.empty() ? fs::path() : exe.parent_path() / name;
}

std::optional<fs::path> data_dir(std::vector<std::string>* looked) {
  if (const char* env = std::getenv("RESCUESIM_DATA_DIR"); env && *env) {
    if (!is_data_dir(env)) {
      throw Error(std::string("RESCUESIM_DATA_DIR=") + env + " is not a rescuesim data folder (expected a folder with worlds/ in it, "
                  "such as <prefix>/share/rescuesim of an installed copy, or the source tree); unset it to use the installed one");
    }
    return fs::path(env);
  }
  std::vector<fs::path> candidates;
  const fs::path exe = executable();
  if (!exe.empty()) candidates.push_back(exe.parent_path().parent_path() / "share" / "rescuesim");
  // the source tree only for the program in its own build folder: an installed copy whose data
  // went missing must say so, not quietly read the tree it was built from
  const std::string build_dir = RESCUESIM_BUILD_DIR;
  if (!build_dir.empty() && exe.string().rfind(build_dir + "/", 0) == 0) candidates.emplace_back(RESCUESIM_SOURCE_DATA_DIR);
  candidates.emplace_back(RESCUESIM_INSTALL_DATA_DIR);
  for (const fs::path& c : candidates) {
    if (c.empty()) continue;
    if (is_data_dir(c)) return c.lexically_normal();
    if (looked) looked->push_back(c.lexically_normal().string());
  }
  return std::nullopt;
}

std::string locate_data_file(const std::string& arg) {
  std::error_code ec;
  const fs::path p(arg);
  if (arg.empty() || p.is_absolute() || fs::exists(p, ec)) return arg;
  std::vector<std::string> looked{fs::absolute(p, ec).string()};
  std::vector<std::string> no_data;
  if (const auto dir = data_dir(&no_data)) {
    for (const fs::path& c : {*dir / p, *dir / "worlds" / p}) {
      if (fs::exists(c, ec)) return c.string();
      looked.push_back(c.string());
    }
  } else {
    for (const auto& d : no_data) looked.push_back(d + " (no data folder there)");
  }
  std::string where;
  for (const auto& l : looked) where += "\n  " + l;
  throw Error(arg + ": no such file; looked in:" + where +
              "\n(set RESCUESIM_DATA_DIR to the folder of an installed copy's data, <prefix>/share/rescuesim)");
}

CLI::Validator data_file() {
  return CLI::Validator(
      [](std::string& value) {
        try {
          value = locate_data_file(value);
          return std::string();
        } catch (const Error& e) {
          return e.message();
        }
      },
      "", "DATA_FILE");
}

}  // namespace rescuesim::app
