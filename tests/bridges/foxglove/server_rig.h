#pragma once
// Test support for the Foxglove bridge: a small inline world, `rescuesim run --foxglove=0`
// started in the background (its port read from its log), node scripts run beside it with the
// pinned npm clients (scripts/install-test-js.sh), and the server's memory read from /proc.

#include <signal.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "core/local_ports.h"
#include "robots/rescue_robot.h"
#include "support/command.h"
#include "world/world.h"
#include "world/world_spec.h"

namespace rescuesim::testing {

/// A 5 m x 3 m room (walls 0.1 m thick, 1 m high, centred on the room's edges), the robot at
/// (1, 1.5) facing east, a victim "alice" by the north wall, a raised area (no ramps) and one
/// rubble block in the south.
inline const char* kRoomSvg = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 500 300">
  <rect x="0" y="0" width="500" height="300" fill="none" stroke="#000000" stroke-width="10"/>
  <circle cx="100" cy="150" r="20" fill="#00c000"/>
  <line x1="100" y1="150" x2="130" y2="150" stroke="#00c000" stroke-width="2"/>
  <rect id="alice" x="300" y="30" width="120" height="40" fill="#1f77b4"/>
  <rect x="150" y="220" width="100" height="50" fill="#e02020" data-ramps="none"/>
  <rect x="340" y="240" width="20" height="20" fill="#ff8c00"/>
</svg>
)";

/// The scenario: no built-in controller, a 180 degree laser with 181 beams (1 degree apart).
inline const char* kRoomYaml = R"(name: fox_room
seed: 5
world:
  svg: room.svg
robots:
  - name: robot
    controller: none
    sensors:
      laser:
        fov: 180
        samples: 181
)";

/// Writes the room scenario into `dir`; returns the YAML's path.
inline std::filesystem::path write_room(const std::filesystem::path& dir) {
  write_text(dir / "room.svg", kRoomSvg);
  write_text(dir / "room.yaml", kRoomYaml);
  return dir / "room.yaml";
}

/// Why node tests cannot run here, or "" when node and the npm clients are there (installing
/// the pinned clients with scripts/install-test-js.sh first when npm is available).
inline std::string node_missing() {
  if (std::system("command -v node >/dev/null 2>&1") != 0) return "node is not installed (scripts/install-deps.sh installs it)";
  const std::filesystem::path js(RESCUESIM_JS_DIR);
  const auto ready = [&] { return std::filesystem::exists(js / "node_modules/@foxglove/ws-protocol/package.json"); };
  if (!ready() && std::system("command -v npm >/dev/null 2>&1") == 0) {
    run_command("timeout 300 '" RESCUESIM_SOURCE_DIR "/scripts/install-test-js.sh' '" + js.string() + "'");
  }
  if (!ready()) return "the npm test clients are missing in " + js.string() + " (run scripts/install-test-js.sh " + js.string() + ")";
  return "";
}

/// A 6 m x 6 m floor with one wall and the built-in robot, compiled: for tests that run the
/// bridge in-process on a Simulation they step themselves.
inline World one_wall_room() {
  WorldSpec spec;
  spec.floor_min = {-3, -3};
  spec.floor_max = {3, 3};
  spec.materials = default_materials();
  spec.walls.push_back({{-3, 3}, {3, 3}, 0.1, 1.0, "wall", {}});
  spec.robots.push_back(RobotPlacement{});
  return compile_world(spec, builtin_models());
}

/// A test that needs node and the npm clients: skipped, saying why, where they are missing.
class NodeClientTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string why = node_missing();
    if (!why.empty()) GTEST_SKIP() << why;
  }
};

/// Runs a node script from tests/bridges/foxglove with the pinned modules.
inline CommandResult node_script(const std::string& script, const std::string& args) {
  return run_command("NODE_PATH='" RESCUESIM_JS_DIR "/node_modules' node '" RESCUESIM_SOURCE_DIR "/tests/bridges/foxglove/" + script +
                     "' " + args);
}


/// `rescuesim` running in the background.
class Background {
 public:
  /// Starts rescuesim with `args` (split on spaces) in `dir`, logging at info level, and waits
  /// until its Foxglove server listens (or it exits, or 60 s pass).
  Background(const std::filesystem::path& dir, const std::string& args) : out_(dir / "rescuesim.out"), err_(dir / "rescuesim.err") {
    std::vector<std::string> words = {RESCUESIM_EXE, "--log-level", "info"};
    std::string word;
    for (char c : args + " ") {
      if (c == ' ') {
        if (!word.empty()) words.push_back(word);
        word.clear();
      } else {
        word += c;
      }
    }
    pid_ = ::fork();
    if (pid_ == 0) {
      const int out = ::open(out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int err = ::open(err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(out, 1);
      ::dup2(err, 2);
      if (::chdir(dir.c_str()) != 0) ::_exit(126);
      std::vector<char*> argv;
      for (auto& w : words) argv.push_back(w.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    const std::regex listening(R"(listening on ws://127\.0\.0\.1:(\d+))");
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline && running()) {
      std::smatch m;
      const std::string log = slurp(err_);
      if (std::regex_search(log, m, listening)) {
        port_ = std::stoi(m[1]);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  ~Background() {
    if (running()) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }

  int port() const { return port_; }
  std::string url() const { return "ws://127.0.0.1:" + std::to_string(port_); }
  pid_t pid() const { return pid_; }
  bool running() {
    if (exit_code_) return false;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      return false;
    }
    return true;
  }
  /// Resident memory (kB), 0 once gone.
  long rss_kb() const {
    const std::string s = slurp("/proc/" + std::to_string(pid_) + "/status");
    const auto at = s.find("VmRSS:");
    return at == std::string::npos ? 0 : std::strtol(s.c_str() + at + 6, nullptr, 10);
  }
  /// Sends a signal (SIGINT: stop like Ctrl-C).
  void signal(int sig) { ::kill(pid_, sig); }
  /// Waits up to `seconds` for the exit; kills it after that. Returns the exit code.
  int wait(double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (running() && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (running()) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
      exit_code_ = 137;
    }
    return *exit_code_;
  }
  std::string out() const { return slurp(out_); }
  std::string err() const { return slurp(err_); }

 private:
  std::filesystem::path out_, err_;
  pid_t pid_ = -1;
  int port_ = 0;
  std::optional<int> exit_code_;
};

}  // namespace rescuesim::testing
