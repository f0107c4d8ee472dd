#pragma once
// Test support for the ROS 1 bridge: a real roscore on a free port (its own ROS_HOME and log
// folder), `rescuesim run --ros1` as a child process on a small inline world, and the ROS
// command-line tools (rostopic, rosbag, rosparam) run with the same environment. Every external
// command runs under `timeout`, and every child is killed with its process group at the end, so
// a failing test never hangs or leaves processes behind.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "core/local_ports.h"
#include "support/command.h"

extern char** environ;

namespace rescuesim::testing {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

/// How long a ROS tool may take to start and deliver. rostopic, rosbag and roscore are Python
/// programs that take a couple of seconds to start on an idle machine and far longer on a
/// loaded one; waits end as soon as what they wait for happens, so this only bounds failures.
constexpr int kToolSeconds = 60;
constexpr std::chrono::seconds kPatience{kToolSeconds};

/// A 6 m x 4 m room: walls 0.1 m thick centred 5 cm inside the edges (inner faces at x = 0.1,
/// 5.9 and y = 0.1, 3.9), the robot at (1, 2) facing east (+x), a victim in the south-east.
inline const char* kRoomSvg = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 600 400">
  <rect x="5" y="5" width="590" height="390" fill="none" stroke="#000000" stroke-width="10"/>
  <circle cx="100" cy="200" r="30" fill="#00c000"/>
  <line x1="100" y1="200" x2="140" y2="200" stroke="#00c000" stroke-width="4"/>
  <rect id="bob" x="450" y="300" width="100" height="40" fill="#2040ff"/>
</svg>
)";

/// The scenario: no built-in controller, a 180 degree laser with 181 beams (1 degree apart),
/// small cameras so images are cheap to render, record and echo.
inline const char* kRoomYaml = R"(name: ros1_room
seed: 3
world:
  svg: room.svg
  svg_scale: 100
robots:
  - name: robot
    controller: none
    sensors:
      laser: {fov: 180, samples: 181}
      color_camera: {width: 160, height: 120, hfov: 70}
      depth_camera: {width: 80, height: 60}
      thermal_camera: {width: 80, height: 60}
)";

/// Writes the room scenario into `dir`; returns the YAML's path.
inline fs::path write_room(const fs::path& dir) {
  write_text(dir / "room.svg", kRoomSvg);
  write_text(dir / "room.yaml", kRoomYaml);
  return dir / "room.yaml";
}

/// A TurtleBot3 burger from worlds/robots/ (its URDF, meshes and licence) in a small maze, with
/// its wheels as a differential drive and no built-in controller: writes `name`.yaml into `dir`
/// with a link to the project's worlds/robots beside it; returns the YAML's path.
inline fs::path write_turtlebot3(const fs::path& dir, const std::string& name) {
  if (!fs::exists(dir / "robots")) fs::create_directory_symlink(fs::path(RESCUESIM_SOURCE_DIR) / "worlds" / "robots", dir / "robots");
  const fs::path yaml = dir / (name + ".yaml");
  write_text(yaml, "name: " + name + R"(
seed: 3
world: {maze: {cols: 3, rows: 3, cell_size: 1.0, victims: 0}}
resource_paths: [robots]
robots:
  - name: tb3
    urdf: package://turtlebot3_description/urdf/turtlebot3_burger.urdf
    drive: {type: diff_drive, left: [wheel_left_joint], right: [wheel_right_joint], max_linear: 0.22, max_angular: 2.84}
    controller: none
)");
  return yaml;
}

/// Why the ROS 1 tools cannot be used here, or "" when they can.
inline std::string ros1_tools_missing() {
  for (const char* tool : {"roscore", "rostopic", "rosbag", "rosparam", "timeout"}) {
    if (std::system(("command -v " + std::string(tool) + " >/dev/null 2>&1").c_str()) != 0) {
      return std::string(tool) + " is not installed (scripts/install-deps.sh installs the ROS 1 tools)";
    }
  }
  return "";
}

/// Skips the test, with the reason, when the ROS 1 tools are not installed.
#define SKIP_WITHOUT_ROS1()                               \
  do {                                                    \
    const std::string missing = rescuesim::testing::ros1_tools_missing(); \
    if (!missing.empty()) GTEST_SKIP() << missing;        \
  } while (0)



/// Polls `done` every 100 ms until it holds or `timeout` passes.
template <class F>
bool wait_until(F done, std::chrono::duration<double> timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(100ms);
  }
  return true;
}

/// A child process in its own process group, stdout and stderr into a log file.
class Child {
 public:
  Child() = default;
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() { kill_group(SIGKILL); }

  /// Starts `argv` with `env` added to this process's environment.
  void start(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env, const fs::path& log) {
    log_ = log;
    std::vector<std::string> vars;
    for (char** e = environ; *e; ++e) {
      const std::string kv = *e;
      if (!env.count(kv.substr(0, kv.find('=')))) vars.push_back(kv);
    }
    for (const auto& [k, v] : env) vars.push_back(k + "=" + v);
    std::vector<char*> cargv, cenv;
    for (const auto& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
    cargv.push_back(nullptr);
    for (const auto& v : vars) cenv.push_back(const_cast<char*>(v.c_str()));
    cenv.push_back(nullptr);
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);
    if (posix_spawnp(&pid_, cargv[0], &files, &attr, cargv.data(), cenv.data()) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&files);
    posix_spawnattr_destroy(&attr);
    exit_code_.reset();
  }

  bool running() {
    if (pid_ <= 0 || exit_code_) return false;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      return false;
    }
    return true;
  }
  /// Sends `sig` to the child alone.
  void signal(int sig) {
    if (running()) ::kill(pid_, sig);
  }
  /// Sends `sig` to the child's whole process group (roscore's rosmaster and rosout too).
  void kill_group(int sig) {
    if (pid_ > 0 && !exit_code_) {
      ::kill(-pid_, sig);
      if (sig == SIGKILL) wait(5s);
    }
  }
  /// The exit code (128 + signal), or nothing if it is still running after `timeout`.
  std::optional<int> wait(std::chrono::duration<double> timeout) {
    wait_until([&] { return !running(); }, timeout);
    return exit_code_;
  }
  /// Ctrl-C, then SIGKILL if it has not ended after `timeout`.
  void interrupt(std::chrono::duration<double> timeout = 10s) {
    signal(SIGINT);
    if (!wait(timeout)) kill_group(SIGKILL);
  }
  std::string output() const { return slurp(log_); }
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  fs::path log_;
  std::optional<int> exit_code_;
};

/// A roscore of its own: a free port, ROS_HOME and ROS_LOG_DIR in a test folder.
class RosMaster {
 public:
  explicit RosMaster(const fs::path& dir) : dir_(dir), port_(free_local_port()) { fs::create_directories(dir_ / "ros_home"); }
  RosMaster(const RosMaster&) = delete;
  RosMaster& operator=(const RosMaster&) = delete;
  ~RosMaster() { kill(); }

  /// Starts roscore and waits until the master accepts connections; false after 20 s.
  bool start() {
    core_ = std::make_unique<Child>();
    core_->start({"roscore", "-p", std::to_string(port_)}, env(), dir_ / ("roscore-" + std::to_string(starts_++) + ".log"));
    return wait_until([&] { return local_port_open(port_); }, kPatience);
  }
  /// Stops roscore with its rosmaster and rosout. (roslaunch starts them in sessions of their
  /// own, so only roscore itself can stop them: Ctrl-C, and SIGKILL only if that fails.)
  void kill() {
    if (!core_) return;
    core_->signal(SIGINT);
    if (!core_->wait(15s)) core_->kill_group(SIGKILL);
    wait_until([&] { return !local_port_open(port_); }, 5s);
    core_.reset();
  }
  std::string uri() const { return "http://localhost:" + std::to_string(port_); }
  int port() const { return port_; }
  /// The ROS environment of this master.
  std::map<std::string, std::string> env() const {
    return {{"ROS_MASTER_URI", uri()},
            {"ROS_HOSTNAME", "localhost"},
            {"ROS_HOME", (dir_ / "ros_home").string()},
            {"ROS_LOG_DIR", (dir_ / "ros_home/log").string()}};
  }
  /// "VAR=value ..." for a shell command line.
  std::string env_prefix() const {
    std::string s;
    for (const auto& [k, v] : env()) s += k + "='" + v + "' ";
    return s;
  }
  /// Starts a command (argv, no shell) in the background with this master's environment.
  std::unique_ptr<Child> spawn(const std::vector<std::string>& argv) const {
    static std::atomic<int> counter{0};
    auto child = std::make_unique<Child>();
    std::map<std::string, std::string> e = env();
    e["PYTHONUNBUFFERED"] = "1";
    child->start(argv, e, dir_ / ("spawn-" + std::to_string(counter++) + ".log"));
    return child;
  }
  /// Runs a shell command line with this master's environment (thread-safe), killed after
  /// `seconds` with SIGINT (so rosbag and rostopic hz finish their output), then SIGKILL.
  CommandResult run(const std::string& command, int seconds) const {
    static std::atomic<int> counter{0};
    const auto out = dir_ / ("cmd-" + std::to_string(counter++));
    // (Python tools buffer their output when it goes to a file: unbuffered, an interrupted
    // rostopic hz still leaves what it printed)
    const std::string line = "env PYTHONUNBUFFERED=1 " + env_prefix() + "timeout -s INT -k 5 " + std::to_string(seconds) + " " + command +
                             " >'" + out.string() + ".out' 2>'" + out.string() + ".err'";
    const int status = std::system(line.c_str());
    CommandResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = slurp(out.string() + ".out");
    r.err = slurp(out.string() + ".err");
    return r;
  }

 private:
  fs::path dir_;
  int port_;
  int starts_ = 0;
  std::unique_ptr<Child> core_;
};

/// `rescuesim run --ros1` on the room scenario in the background.
class Simulator {
 public:
  /// Starts rescuesim on `master` with extra `args` and waits until the bridge has started.
  bool start(const RosMaster& master, const fs::path& dir, const std::vector<std::string>& args) {
    return start(master, dir, write_room(dir), args);
  }
  /// The same with a scenario file of the caller's.
  bool start(const RosMaster& master, const fs::path& dir, const fs::path& yaml, const std::vector<std::string>& args) {
    std::vector<std::string> argv = {RESCUESIM_EXE, "run", yaml.string(), "--ros1", "--quiet", "--out", (dir / "out").string()};
    argv.insert(argv.end(), args.begin(), args.end());
    child_.start(argv, master.env(), dir / "rescuesim.log");
    return wait_until([&] { return output().find("bridge        ros1 started") != std::string::npos || !child_.running(); }, kPatience) &&
           child_.running();
  }
  std::string output() const { return child_.output(); }
  bool running() { return child_.running(); }
  /// Ctrl-C: the run ends cleanly and writes its outputs; the exit code.
  std::optional<int> interrupt() {
    child_.signal(SIGINT);
    return child_.wait(20s);
  }
  /// Waits until the output contains `text`.
  bool says(const std::string& text, std::chrono::duration<double> timeout) {
    return wait_until([&] { return output().find(text) != std::string::npos; }, timeout);
  }

 private:
  Child child_;
};

/// The value after "key: " on the first line that has it (quotes stripped), or "".
inline std::string field(const std::string& yaml, const std::string& key, std::size_t from = 0) {
  const std::regex re("(^|\\n)\\s*" + key + ": ([^\\n]*)");
  std::smatch m;
  const std::string rest = yaml.substr(std::min(from, yaml.size()));
  if (!std::regex_search(rest, m, re)) return "";
  std::string v = m[2];
  if (v.size() >= 2 && v.front() == '"' && v.back() == '"') v = v.substr(1, v.size() - 2);
  return v;
}

/// A numeric field, NaN when missing.
inline double number(const std::string& yaml, const std::string& key, std::size_t from = 0) {
  const std::string v = field(yaml, key, from);
  try {
    return v.empty() ? NAN : std::stod(v);
  } catch (...) {
    return NAN;
  }
}

/// The numbers of a flow list "[1.0, 2.0, inf]" given as the value of `key`.
inline std::vector<double> numbers(const std::string& yaml, const std::string& key) {
  std::string v = field(yaml, key);
  std::vector<double> out;
  if (v.size() < 2 || v.front() != '[') return out;
  v = v.substr(1, v.size() - 2);
  std::size_t pos = 0;
  while (pos < v.size()) {
    const std::size_t comma = v.find(',', pos);
    const std::string item = v.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    try {
      out.push_back(std::stod(item));
    } catch (...) {
      out.push_back(NAN);
    }
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return out;
}

/// The messages of a multi-message rostopic echo, split at its "---" lines.
inline std::vector<std::string> messages(const std::string& echo) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos < echo.size()) {
    const std::size_t end = echo.find("---\n", pos);
    out.push_back(echo.substr(pos, end == std::string::npos ? std::string::npos : end - pos));
    if (end == std::string::npos) break;
    pos = end + 4;
  }
  if (!out.empty() && out.back().find_first_not_of(" \n") == std::string::npos) out.pop_back();
  return out;
}

/// Sim time of a stamped message as rostopic prints it (header.stamp secs + nsecs).
inline double stamp_of(const std::string& yaml) { return number(yaml, "secs") + 1e-9 * number(yaml, "nsecs"); }

}  // namespace rescuesim::testing
