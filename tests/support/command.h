#pragma once
// Test support: run a command line, capture exit code, stdout and stderr; make temp folders.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rescuesim::testing {

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

/// A fresh folder under the build tree, removed first if it exists.
inline std::filesystem::path temp_dir(const std::string& name) {
  const auto p = std::filesystem::path(RESCUESIM_BINARY_DIR) / "test-tmp" / (name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void write_text(const std::filesystem::path& p, const std::string& text) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

/// A path in single quotes, for a command line (the paths tests make hold no quotes).
inline std::string quoted(const std::filesystem::path& p) {
  std::string out = "'";
  out += p.string();
  out += "'";
  return out;
}

/// Runs `command` through the shell (arguments must already be quoted), in `cwd` if given.
inline CommandResult run_command(const std::string& command, const std::filesystem::path& cwd = {}) {
  static int counter = 0;
  const auto dir = std::filesystem::path(RESCUESIM_BINARY_DIR) / "test-tmp" / "cmd";
  std::filesystem::create_directories(dir);
  const std::string stem = std::to_string(::getpid()) + "-" + std::to_string(counter++);
  const auto out = dir / (stem + ".out"), err = dir / (stem + ".err");
  std::string full = command + " >" + out.string() + " 2>" + err.string();
  if (!cwd.empty()) full = "cd '" + cwd.string() + "' && " + full;
  const int status = std::system(full.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

#ifdef RESCUESIM_EXE
/// The rescuesim executable with arguments appended.
inline CommandResult rescuesim(const std::string& args, const std::filesystem::path& cwd = {}) {
  return run_command(std::string("'") + RESCUESIM_EXE + "' " + args, cwd);
}
#endif

}  // namespace rescuesim::testing
