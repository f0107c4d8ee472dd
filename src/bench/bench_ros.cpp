// rescuesim bench, ROS part. Latency: a realtime run with one bridge notes the wall clock at
// which each /scan and colour image is published on the Bus; a probe process (a real roscpp
// node, a Cyclone DDS reader, or a Foxglove WebSocket client) notes when it receives each one;
// the two are joined by stamp. Cost: the same lockstep run without bridges, then with --ros1
// --ros2 --foxglove and a probe on each subscribed (to /scan and the image, then to /scan
// alone), each in a child process. roscore runs on a free port with its own ROS_HOME.

#include "bench/bench_ros.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <span>
#include <sstream>
#include <thread>

#include "app/bridge_flags.h"
#include "bench/bench_child.h"
#include "bench/bench_latency.h"
#include "core/error.h"
#include "core/local_ports.h"
#include "msgs/serialize.h"
#include "session/session.h"
#ifdef RESCUESIM_HAS_ROS1
#include "bridges/ros1/ros1_probe.h"
#endif
#ifdef RESCUESIM_HAS_ROS2
#include "bridges/ros2/dds_participant.h"
#include "bridges/ros2/ros2_conventions.h"
#endif
#ifdef RESCUESIM_HAS_FOXGLOVE
#include "bridges/foxglove/foxglove_probe.h"
#endif

extern char** environ;

namespace rescuesim::bench {

using app::Action;
using app::BridgeFlags;
using app::kExitFailure;
using app::kExitOk;

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

/// The topics timed, with their ROS 1 types (the probe needs the DDS type of each).
const std::vector<std::pair<std::string, std::string>> kTimed = {{"/scan", "sensor_msgs/LaserScan"},
                                                                 {"/camera/color/image_raw", "sensor_msgs/Image"}};
/// Publications stamped before this are not timed: the subscriber may still be connecting.
constexpr std::int64_t kWarmupNs = 500'000'000;

std::int64_t realtime_ns() {
  timespec ts{};
  ::clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The last few lines of a log, for error messages.
std::string tail(const std::string& text, std::size_t chars = 400) {
  return text.size() <= chars ? text : "..." + text.substr(text.size() - chars);
}

/// Polls `done` every 50 ms until it holds or `timeout` passes.
template <class F>
bool wait_until(F done, std::chrono::duration<double> timeout) {
  const auto end = Clock::now() + timeout;
  while (!done()) {
    if (Clock::now() > end) return false;
    std::this_thread::sleep_for(50ms);
  }
  return true;
}



bool on_path(const char* tool) { return std::system(("command -v " + std::string(tool) + " >/dev/null 2>&1").c_str()) == 0; }

/// Sets environment variables for this section and puts the old values back at the end.
class EnvGuard {
 public:
  void set(const std::string& name, const std::string& value) {
    const char* old = std::getenv(name.c_str());
    saved_.emplace_back(name, old ? std::optional<std::string>(old) : std::nullopt);
    ::setenv(name.c_str(), value.c_str(), 1);
  }
  ~EnvGuard() {
    for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) {
      if (it->second) ::setenv(it->first.c_str(), it->second->c_str(), 1);
      else ::unsetenv(it->first.c_str());
    }
  }

 private:
  std::vector<std::pair<std::string, std::optional<std::string>>> saved_;
};

/// A child program in a process group of its own, stdout and stderr into files; killed with
/// its group when dropped.
class Spawned {
 public:
  Spawned(const std::vector<std::string>& argv, const fs::path& out, const fs::path& err) : out_(out), err_(err) {
    std::vector<char*> cargv;
    for (const auto& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
    cargv.push_back(nullptr);
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&files, STDERR_FILENO, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);
    if (posix_spawnp(&pid_, cargv[0], &files, &attr, cargv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&files);
    posix_spawnattr_destroy(&attr);
  }
  Spawned(const Spawned&) = delete;
  Spawned& operator=(const Spawned&) = delete;
  ~Spawned() { stop(SIGKILL, 1s); }

  bool running() {
    if (pid_ <= 0) return false;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return false;
    }
    return true;
  }
  /// Sends `sig` to the program; after `grace`, SIGKILL to its whole group.
  void stop(int sig, std::chrono::duration<double> grace) {
    if (!running()) return;
    ::kill(pid_, sig);
    if (!wait_until([&] { return !running(); }, grace)) {
      ::kill(-pid_, SIGKILL);
      int status = 0;
      ::waitpid(pid_, &status, 0);
      pid_ = -1;
    }
  }
  std::string out() const { return slurp(out_); }
  std::string err() const { return slurp(err_); }
  /// CPU seconds all its threads have run so far (the kernel's per-thread run time in
  /// /proc/PID/task/TID/schedstat, in ns); 0 once it has ended. Threads that have ended are not
  /// in it (the probes keep theirs for their whole life).
  double cpu_seconds() const {
    if (pid_ <= 0) return 0;
    double ns = 0;
    std::error_code ec;
    for (const auto& task : fs::directory_iterator(fs::path("/proc") / std::to_string(pid_) / "task", ec)) {
      std::ifstream in(task.path() / "schedstat");
      double run_ns = 0;
      if (in >> run_ns) ns += run_ns;
    }
    return ns * 1e-9;
  }

 private:
  pid_t pid_ = -1;
  fs::path out_, err_;
};

/// The probe as a child: `rescuesim-bench bench-probe` (this program again) subscribed to the timed topics.
/// With `scan_only`, the probe subscribes to /scan alone.
std::unique_ptr<Spawned> start_probe(const std::string& transport, const fs::path& dir, bool scan_only = false, int foxglove_port = 0) {
  std::vector<std::string> argv = {fs::read_symlink("/proc/self/exe").string(), "bench-probe", "--transport", transport};
  if (transport == "foxglove") {
    argv.push_back("--port");
    argv.push_back(std::to_string(foxglove_port));
  }
  for (const auto& [topic, type] : kTimed) {
    if (scan_only && topic != "/scan") continue;
    argv.push_back("--topic");
    argv.push_back(topic + "=" + type);
  }
  auto p = std::make_unique<Spawned>(argv, dir / ("probe-" + transport + ".out"), dir / ("probe-" + transport + ".err"));
  // ready once subscribed (or gone, when it could not start); a Foxglove client can only
  // subscribe once the run's server is up, which the run's settling time allows for
  if (transport != "foxglove") wait_until([&] { return !p->running() || p->err().find("probe ready") != std::string::npos; }, 20s);
  return p;
}

/// The receipts a probe printed ("topic stamp_ns wall_ns" lines).
std::vector<StampedWallTime> receipts(const std::string& text) {
  std::vector<StampedWallTime> out;
  std::istringstream in(text);
  std::string line;
  // (anything else on the line, such as a log line, is skipped)
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    StampedWallTime r;
    if (fields >> r.topic >> r.stamp_ns >> r.wall_ns && r.topic.starts_with('/')) out.push_back(r);
  }
  return out;
}

/// The bench's scenario for the ROS figures: the default one with the colour camera at 640x480,
/// 10 Hz (depth and thermal off, so the image timed is the only large message).
Scenario ros_scenario(const Scenario& def) {
  Scenario s = def;
  for (auto& rc : s.robots) {
    for (auto& sensor : rc.spec.sensors) {
      if (sensor.type == SensorSpec::Type::color_camera) {
        sensor.enabled = true;
        sensor.camera.width = 640;
        sensor.camera.height = 480;
        sensor.rate = 10;
      } else if (sensor.is_camera()) {
        sensor.enabled = false;
      }
    }
  }
  return s;
}

/// Runs `scenario` in a child process with the bridges of `flags`, after `settle` of wall time
/// for subscribers to connect, with or without the scenario's built-in controllers. Returns its
/// real-time factor, bridge counts and, for each timed topic, the wall clock at which each
/// message was published on the Bus.
json run_bridged(const Scenario& scenario, const ModelMap& models, const BridgeFlags& flags, std::chrono::duration<double> settle,
                 bool controllers = true) {
  ChildReport child = run_in_child([&] {
    json out;
    SessionOptions so;
    so.cameras = true;
    so.controllers = controllers;
    Session session(scenario, models, so);
    // subscribed before the bridges, so the Bus calls it first
    std::vector<StampedWallTime> published;
    published.reserve(4096);
    for (const auto& [topic, type] : kTimed) {
      session.sim().bus().subscribe(topic, [&published](const Topic& t, const msg::Message& m) {
        published.push_back({t.name, msg::stamp_of(m).ns, realtime_ns()});
      });
    }
    auto bridges = app::make_bridges(flags);
    for (auto& b : bridges) b->start(session.sim());
    if (!bridges.empty()) std::this_thread::sleep_for(settle);
    const RunResult r = session.run();
    out = {{"sim_time_s", r.sim_time}, {"wall_time_s", r.wall_time}, {"real_time_factor", r.real_time_factor}};
    for (auto& b : bridges) {
      b->stop();
      const BridgeStats st = b->stats();
      out["bridges"][b->name()] = {{"sent", st.sent}, {"dropped", st.dropped}};
    }
    json pub = json::array();
    for (const auto& p : published) pub.push_back({p.topic, p.stamp_ns, p.wall_ns});
    out["published"] = pub;
    return out;
  });
  json j = std::move(child.report);
  const struct rusage& ru = child.usage;
  // CPU the simulation process used (every thread, set-up included): less sensitive to other load than wall time
  j["cpu_s"] =
      static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + 1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  return j;
}

std::vector<StampedWallTime> publications(const json& run) {
  std::vector<StampedWallTime> out;
  for (const auto& p : run.value("published", json::array()))
    out.push_back({p[0].get<std::string>(), p[1].get<std::int64_t>(), p[2].get<std::int64_t>()});
  return out;
}

json latency_json(const LatencySummary& s) {
  const auto ms = [](double v) { return std::isfinite(v) ? json(std::round(v * 1000) / 1000) : json(nullptr); };
  return {{"median_ms", ms(s.median_ms)}, {"p99_ms", ms(s.p99_ms)}, {"min_ms", ms(s.min_ms)}, {"max_ms", ms(s.max_ms)},
          {"samples", s.matched}, {"published", s.published}};
}

/// One transport's latency run: the probe first, then the simulation in realtime with the bridge.
json measure_latency(const std::string& transport, const Scenario& scenario, const ModelMap& models, const fs::path& dir, double seconds) {
  const int foxglove_port = transport == "foxglove" ? free_local_port() : 0;
  auto probe = start_probe(transport, dir, false, foxglove_port);
  if (!probe->running()) return json{{"error", "the probe did not start: " + tail(probe->err())}};
  Scenario s = scenario;
  s.realtime = true;
  s.rate = 1;
  s.duration = seconds;
  BridgeFlags flags;
  flags.ros1 = transport == "ros1";
  flags.ros2 = transport == "ros2";
  if (foxglove_port > 0) flags.foxglove = foxglove_port;
  // DDS discovery takes longer than a ROS 1 connection or a WebSocket's. Without the built-in
  // controllers, as `rescuesim run --ros2` (or --ros1, --foxglove) runs: the robot's
  // controller is the user's, on the other end of the transport
  const json run = run_bridged(s, models, flags, transport == "ros2" ? 2s : 1s, false);
  // what is still on its way arrives within this (stop() flushed the bridge's queue)
  std::this_thread::sleep_for(300ms);
  probe->stop(SIGTERM, 5s);
  if (run.contains("error")) return json{{"error", run["error"]}};
  const std::vector<StampedWallTime> pub = publications(run);
  const std::vector<StampedWallTime> got = receipts(probe->out());
  json j;
  for (const auto& [topic, type] : kTimed) j[topic] = latency_json(summarize_latency(pub, got, topic, kWarmupNs));
  j["real_time_factor"] = run.value("real_time_factor", 0.0);
  j["bridge"] = run.value("bridges", json::object());
  return j;
}

/// One lockstep run with `flags` and a probe per transport (subscribed to /scan and the image,
/// or /scan alone); its real-time factor, CPU seconds, bridge counts and messages received.
json cost_run(const Scenario& s, const ModelMap& models, const BridgeFlags& flags, const fs::path& dir, bool scan_only) {
  std::vector<std::unique_ptr<Spawned>> probes;
  if (flags.ros1) probes.push_back(start_probe("ros1", dir, scan_only));
  if (flags.ros2) probes.push_back(start_probe("ros2", dir, scan_only));
  BridgeFlags with = flags;
  if (flags.foxglove) {
    with.foxglove = free_local_port();  // a port of this run's own
    probes.push_back(start_probe("foxglove", dir, scan_only, *with.foxglove));
  }
  std::fprintf(stderr, "bench: ROS: real-time factor with%s%s%s, subscribed to %s, %.0f s lockstep ...\n", flags.ros1 ? " --ros1" : "",
               flags.ros2 ? " --ros2" : "", flags.foxglove ? " --foxglove" : "", scan_only ? "/scan" : "/scan and the image", s.duration);
  // the subscribers' CPU over the run (their start-up, before it, not counted)
  const auto probes_cpu = [&probes] {
    double sum = 0;
    for (const auto& p : probes) sum += p->cpu_seconds();
    return sum;
  };
  const double cpu0 = probes_cpu();
  json run = run_bridged(s, models, with, 2s);
  std::this_thread::sleep_for(300ms);
  run["subscribers_cpu_s"] = probes_cpu() - cpu0;
  std::size_t got = 0;
  for (auto& p : probes) {
    p->stop(SIGTERM, 5s);
    got += receipts(p->out()).size();
  }
  run["probe_messages_received"] = got;
  return run;
}

/// The cost figure from the rounds' runs without and with bridges: the best real-time factor of
/// each (other load on the machine only ever slows a run down), and the CPU seconds.
json cost_figure(const std::vector<json>& without, const std::vector<json>& with, double sim_time) {
  std::vector<double> rtf_a, rtf_b, cpu_a, cpu_b, cpu_subscribers;
  std::string error;
  std::size_t best = 0;
  for (const json& r : without) {
    rtf_a.push_back(r.value("real_time_factor", 0.0));
    cpu_a.push_back(r.value("cpu_s", 0.0));
    if (r.contains("error")) error = "without bridges: " + r["error"].get<std::string>();
  }
  for (std::size_t k = 0; k < with.size(); ++k) {
    rtf_b.push_back(with[k].value("real_time_factor", 0.0));
    cpu_b.push_back(with[k].value("cpu_s", 0.0));
    cpu_subscribers.push_back(with[k].value("subscribers_cpu_s", 0.0));
    if (with[k].contains("error")) error = "with bridges: " + with[k]["error"].get<std::string>();
    if (rtf_b[k] > rtf_b[best]) best = k;
  }
  const double a = rtf_a.empty() ? 0.0 : *std::max_element(rtf_a.begin(), rtf_a.end());
  const double b = rtf_b.empty() ? 0.0 : rtf_b[best];
  json f;
  f["value"] = b;
  f["unit"] = "x real time";
  f["baseline"] = a;
  f["baseline_is"] = "the same lockstep run without bridges, in this bench run";
  f["ratio"] = a > 0 ? b / a : 0.0;
  f["target_ratio"] = 0.9;
  f["meets_target"] = a > 0 && b / a >= 0.9;
  f["real_time_factor_without"] = rtf_a;
  f["real_time_factor_with"] = rtf_b;
  f["sim_process_cpu_s_without"] = cpu_a;
  f["sim_process_cpu_s_with"] = cpu_b;
  // the same comparison in CPU seconds of the simulation process (medians), which other load
  // on the machine disturbs far less than wall time; the probes' own CPU is not in it
  const double ca = percentile(cpu_a, 50), cb = percentile(cpu_b, 50);
  f["sim_process_cpu_ratio"] = cb > 0 ? ca / cb : 0.0;
  // and with the subscriber processes' CPU over the run added: what the machine as a whole
  // spends on the bridges and on what they deliver, against the run without them
  f["subscribers_cpu_s"] = cpu_subscribers;
  const double cs = percentile(cpu_subscribers, 50);
  f["cpu_ratio_with_subscribers"] = cb + cs > 0 ? ca / (cb + cs) : 0.0;
  f["extra_cpu_s_per_sim_s"] = sim_time > 0 ? (cb + cs - ca) / sim_time : 0.0;
  if (!with.empty()) {
    f["bridges"] = with[best].value("bridges", json::object());
    f["probe_messages_received"] = with[best].value("probe_messages_received", 0);
  }
  f["sim_time_s"] = sim_time;
  if (!error.empty()) f["error"] = error;
  return f;
}

/// Rounds of: without bridges, with bridges and /scan + image subscribers, with bridges and
/// /scan subscribers only (alternating, so slow spells of other load spread over all three).
json measure_cost(const Scenario& scenario, const ModelMap& models, const BridgeFlags& flags, const fs::path& dir,
                  const BenchRosOptions& o) {
  Scenario s = scenario;
  s.realtime = false;
  s.duration = o.rtf_seconds;
  std::vector<json> without, with, scan_only;
  for (int round = 0; round < o.rtf_rounds; ++round) {
    std::fprintf(stderr, "bench: ROS: real-time factor without bridges, %.0f s lockstep (round %d of %d) ...\n", s.duration, round + 1,
                 o.rtf_rounds);
    without.push_back(run_bridged(s, models, BridgeFlags{}, 0s));
    with.push_back(cost_run(s, models, flags, dir, false));
    scan_only.push_back(cost_run(s, models, flags, dir, true));
  }
  json j;
  j["bridge_cost"] = cost_figure(without, with, s.duration);
  j["bridge_cost"]["note"] =
      "ratio = best real-time factor with the bridges attached (ROS 1, ROS 2, Foxglove) / best without, over the rounds; per "
      "transport a subscriber process on /scan and the colour image (the bridges send only topics somebody subscribes to); the default "
      "scenario "
      "with the colour camera at 640x480 10 Hz, depth and thermal cameras off; subscribers_cpu_s: the subscriber processes' CPU over "
      "each run with bridges, counted in cpu_ratio_with_subscribers and extra_cpu_s_per_sim_s (CPU medians)";
  j["bridge_cost_scan_only"] = cost_figure(without, scan_only, s.duration);
  j["bridge_cost_scan_only"]["note"] = "as bridge_cost, with subscribers on /scan alone: the images are rendered but not sent";
  return j;
}

/// roscore on a free port with the section's ROS_HOME; nothing when it does not come up.
std::unique_ptr<Spawned> start_roscore(int port, const fs::path& dir, std::string* why) {
  auto core =
      std::make_unique<Spawned>(std::vector<std::string>{"roscore", "-p", std::to_string(port)}, dir / "roscore.out", dir / "roscore.err");
  if (!wait_until([&] { return local_port_open(port) || !core->running(); }, 30s) || !local_port_open(port)) {
    *why = "roscore did not come up on port " + std::to_string(port) + ": " + tail(core->out() + core->err());
    core->stop(SIGINT, 10s);
    return nullptr;
  }
  return core;
}

}  // namespace

json bench_ros(const Scenario& def, const ModelMap& models, const BenchRosOptions& o) {
  json j;
  double load[1] = {0};
  if (::getloadavg(load, 1) == 1) j["load_average_1min_at_start"] = load[0];
  std::string no_ros1, no_ros2;
#ifndef RESCUESIM_HAS_ROS1
  no_ros1 = "built without the ROS 1 bridge (roscpp not found at build time)";
#else
  if (!on_path("roscore")) no_ros1 = "roscore is not installed (scripts/install-deps.sh installs it)";
#endif
#ifndef RESCUESIM_HAS_ROS2
  no_ros2 = "built without the ROS 2 bridge (Cyclone DDS not found at build time)";
#endif
  std::string no_foxglove;
#ifndef RESCUESIM_HAS_FOXGLOVE
  no_foxglove = "built without the Foxglove bridge (Boost.Beast not found at build time)";
#endif
  const fs::path dir = fs::temp_directory_path() / ("rescuesim-bench-ros-" + std::to_string(::getpid()));
  fs::create_directories(dir / "ros_home/log");
  EnvGuard env;
  const int port = free_local_port();
  env.set("ROS_MASTER_URI", "http://localhost:" + std::to_string(port));
  env.set("ROS_HOSTNAME", "localhost");
  env.set("ROS_HOME", (dir / "ros_home").string());
  env.set("ROS_LOG_DIR", (dir / "ros_home/log").string());
  // Cyclone on loopback only, without multicast, on a domain of this run's own
  {
    std::ofstream(dir / "cyclonedds.xml")
        << "<CycloneDDS><Domain Id=\"any\"><General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
           "<AllowMulticast>false</AllowMulticast></General><Discovery><ParticipantIndex>auto</ParticipantIndex>"
           "<Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery></Domain></CycloneDDS>\n";
  }
  env.set("CYCLONEDDS_URI", "file://" + (dir / "cyclonedds.xml").string());
  env.set("ROS_DOMAIN_ID", std::to_string(100 + ::getpid() % 100));

  std::unique_ptr<Spawned> core;
  if (no_ros1.empty()) {
    std::fprintf(stderr, "bench: ROS: roscore on port %d ...\n", port);
    core = start_roscore(port, dir, &no_ros1);
  }
  const Scenario scenario = ros_scenario(def);
  json lat;
  for (const auto& [transport, missing] :
       {std::pair<std::string, std::string>{"ros1", no_ros1}, {"ros2", no_ros2}, {"foxglove", no_foxglove}}) {
    if (!missing.empty()) {
      lat[transport] = {{"skipped", missing}};
      continue;
    }
    std::fprintf(stderr, "bench: ROS: %s latency, %.0f s realtime ...\n", transport.c_str(), o.latency_seconds);
    lat[transport] = measure_latency(transport, scenario, models, dir, o.latency_seconds);
  }
  lat["note"] = "wall clock (CLOCK_REALTIME) from publication on the Bus to receipt in a subscriber process on loopback, "
                "matched by header stamp; realtime runs without the built-in controllers (as rescuesim run with a live bridge), "
                "colour camera 640x480 rgb8 at 10 Hz, /scan at 10 Hz; "
                "ROS 1: a roscpp node (TCPROS, tcp_nodelay); ROS 2: a Cyclone DDS reader (reliable, depth 10); "
                "Foxglove: a WebSocket client (Boost.Beast) subscribed to the cdr channels";
  j["latency"] = lat;

  // the real-time factor with every bridge (and a subscriber on each) beside none
  if (no_ros1.empty() || no_ros2.empty() || no_foxglove.empty()) {
    BridgeFlags flags;
    flags.ros1 = no_ros1.empty();
    flags.ros2 = no_ros2.empty();
    if (no_foxglove.empty()) flags.foxglove = 0;  // cost_run picks a free port per run
    json costs = measure_cost(scenario, models, flags, dir, o);
    for (const char* key : {"bridge_cost", "bridge_cost_scan_only"}) {
      if (!no_ros1.empty()) costs[key]["ros1_skipped"] = no_ros1;
      if (!no_ros2.empty()) costs[key]["ros2_skipped"] = no_ros2;
      if (!no_foxglove.empty()) costs[key]["foxglove_skipped"] = no_foxglove;
      j[key] = costs[key];
    }
  } else {
    j["bridge_cost"] = {{"skipped", "no bridge can run here: " + no_ros1 + "; " + no_ros2 + "; " + no_foxglove}};
  }
  if (core) core->stop(SIGINT, 15s);
  std::error_code ec;
  fs::remove_all(dir, ec);
  return j;
}

namespace {

std::atomic<bool> g_probe_stop{false};
void on_probe_signal(int) { g_probe_stop = true; }

struct ProbeOptions {
  std::string transport;
  int port = 8765;                  ///< Foxglove: the server's port on 127.0.0.1
  std::vector<std::string> topics;  ///< "name=ros1/Type"
  double seconds = 120;
};

int run_probe(const ProbeOptions& o) {
  std::signal(SIGTERM, on_probe_signal);
  std::signal(SIGINT, on_probe_signal);
  std::vector<std::string> names, types;
  for (const auto& t : o.topics) {
    const auto eq = t.find('=');
    names.push_back(t.substr(0, eq));
    types.push_back(eq == std::string::npos ? "" : t.substr(eq + 1));
  }
  // one line per message, flushed at once: the bench reads them after stopping the probe
  const auto report = [&](std::size_t i, std::int64_t stamp_ns) {
    const std::int64_t now = realtime_ns();
    std::printf("%s %lld %lld\n", names[i].c_str(), static_cast<long long>(stamp_ns), static_cast<long long>(now));
    std::fflush(stdout);
  };
  const auto ready = [] { std::fprintf(stderr, "probe ready\n"); };
  try {
    if (o.transport == "foxglove") {
#ifdef RESCUESIM_HAS_FOXGLOVE
      run_foxglove_probe("127.0.0.1", o.port, names, report, ready, g_probe_stop, o.seconds);
      return kExitOk;
#else
      throw Error("bench-probe: built without the Foxglove bridge");
#endif
    }
    if (o.transport == "ros1") {
#ifdef RESCUESIM_HAS_ROS1
      run_ros1_probe("rescuesim_bench_probe", names, report, ready, g_probe_stop, o.seconds);
      return kExitOk;
#else
      throw Error("bench-probe: built without the ROS 1 bridge");
#endif
    }
#ifdef RESCUESIM_HAS_ROS2
    ros2::DdsParticipant dds(ros2::resolve_domain(-1), ros2::participant_user_data());
    std::vector<int> readers;
    for (std::size_t i = 0; i < names.size(); ++i) {
      const msg::TypeSupport* type = msg::find_type(types[i]);
      if (!type) throw Error("bench-probe: unknown type '" + types[i] + "' for " + names[i]);
      // a ROS 2 subscriber's default QoS: reliable, volatile, keep last 10
      readers.push_back(dds.create_reader(ros2::dds_topic_name(names[i]), type->dds_name, ros2::EndpointQos{}));
    }
    ready();
    const auto end = Clock::now() + std::chrono::duration<double>(o.seconds);
    while (!g_probe_stop && Clock::now() < end) {
      dds.wait(100ms);
      for (std::size_t i = 0; i < readers.size(); ++i) {
        dds.take(readers[i], [&](std::span<const std::uint8_t> b) {
          // XCDR1: 4-byte encapsulation header, then the Header's stamp (int32 sec, uint32 nanosec)
          if (b.size() < 12) return;
          const auto u32 = [&](std::size_t at) {
            return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 |
                   static_cast<std::uint32_t>(b[at + 2]) << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
          };
          report(i, static_cast<std::int64_t>(static_cast<std::int32_t>(u32(4))) * 1'000'000'000 + u32(8));
        });
      }
    }
    return kExitOk;
#else
    throw Error("bench-probe: built without the ROS 2 bridge");
#endif
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return kExitFailure;
  }
}

}  // namespace

void add_bench_probe_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<ProbeOptions>();
  CLI::App* cmd = app.add_subcommand("bench-probe", "the subscriber process of `rescuesim bench` (internal)");
  cmd->group("");  // hidden: not listed in --help
  cmd->add_option("--transport", o->transport, "ros1, ros2 or foxglove")->required()->check(CLI::IsMember({"ros1", "ros2", "foxglove"}));
  cmd->add_option("--port", o->port, "foxglove: the server's port on 127.0.0.1")->capture_default_str();
  cmd->add_option("--topic", o->topics, "TOPIC=ROS1_TYPE to subscribe to (repeatable)")->required();
  cmd->add_option("--seconds", o->seconds, "give up after this many wall seconds")->capture_default_str();
  cmd->final_callback([o, &action] { action = [o] { return run_probe(*o); }; });
}

}  // namespace rescuesim::bench
