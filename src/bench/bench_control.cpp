// rescuesim bench, control part. A child process (the simulation process) builds the default
// scenario twice: a run with the control surface and the ROS 2 bridge, started PAUSED and
// stepping on a thread of its own (as `rescuesim run --ros2 --paused`), and a plain Session of
// the same scenario for the in-process baselines. A client process forked from it calls the
// services and the action over the wire as rmw_cyclonedds does (ros2::ServiceClient,
// ros2::ActionClient) on a Cyclone domain pinned to loopback, so each round trip is client ->
// UDP on lo -> bridge -> simulation thread -> bridge -> UDP on lo -> client. The two talk over
// a pipe: the client says when the lockstep runs are due, so they alternate with its goals.

#include "bench/bench_control.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_child.h"
#include "bench/bench_figures.h"
#include "bench/bench_latency.h"
#include "core/error.h"
#include "session/session.h"
#include "world/state.h"
#ifdef RESCUESIM_HAS_ROS2
#include "bridges/common/cdr_stream.h"
#include "bridges/common/control_cdr.h"
#include "bridges/ros2/dds_action_client.h"
#include "bridges/ros2/dds_participant.h"
#include "bridges/ros2/dds_services.h"
#include "bridges/ros2/ros2_bridge.h"
#include "raycast/free_spot.h"
#include "bridges/ros2/ros2_conventions.h"
#endif

namespace rescuesim::bench {

namespace {

using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// {p50_ms, p99_ms, min_ms, max_ms, calls} of durations in seconds.
json spread_ms(const std::vector<double>& seconds) {
  std::vector<double> ms;
  for (double s : seconds) ms.push_back(s * 1e3);
  if (ms.empty()) return {{"calls", 0}};
  return {{"p50_ms", percentile(ms, 50)}, {"p99_ms", percentile(ms, 99)}, {"min_ms", *std::min_element(ms.begin(), ms.end())},
          {"max_ms", *std::max_element(ms.begin(), ms.end())}, {"calls", ms.size()}};
}

#ifdef RESCUESIM_HAS_ROS2

using namespace control;

/// A DDS domain no test or other bench on this machine holds: the same lock files as the tests'
/// (tests/support/dds_domain.h), /tmp/rescuesim-test-dds-domain-<id>.lock, held with flock until
/// this process exits, so a bench during `ctest -j` never shares a domain with a test.
int lease_dds_domain() {
  constexpr int kFirst = 1, kLast = 232;
  const int span = kLast - kFirst + 1;
  const int start = static_cast<int>(::getpid() % span);
  for (int k = 0; k < span; ++k) {
    const int id = kFirst + (start + k) % span;
    const std::string path = "/tmp/rescuesim-test-dds-domain-" + std::to_string(id) + ".lock";
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return id;  // the descriptor stays open, and the lock with it
    ::close(fd);
  }
  throw Error("bench control: no free DDS domain in 1..232 (every /tmp/rescuesim-test-dds-domain-*.lock is held)");
}

/// A service of the run, called over the wire.
class Caller {
 public:
  Caller(ros2::DdsParticipant& dds, const std::string& name, Interface id)
      : name_(name), client_(dds, ros2::service_topics(name, info(id).ros_type)) {
    if (!client_.wait_for_server(10s)) throw Error("bench control: no server for " + name + " within 10 s");
  }
  /// Calls S with `request`; the decoded response. Throws Error on a timeout or a reply that does not decode.
  template <class S>
  typename S::Response call(const typename S::Request& request, std::chrono::milliseconds timeout = 10s) {
    body_.clear();
    encode_request<S>(request, WireVersion::v1, body_);
    std::string why;
    const auto reply = client_.call(body_, timeout, &why);
    if (!reply) throw Error("bench control: " + why);
    auto decoded = decode_response<S>(*reply, WireVersion::v1);
    if (!decoded.value) throw Error("bench control: " + name_ + ": reply does not decode: " + decoded.problem);
    return *decoded.value;
  }

 private:
  std::string name_;
  ros2::ServiceClient client_;
  std::vector<std::uint8_t> body_;
};

/// Throws when a call was refused: a figure of refused calls would measure nothing.
void demand_ok(const Result& r, const char* what) {
  if (!r.is_ok()) throw Error(std::string("bench control: ") + what + " failed (" + std::to_string(r.result) + "): " + r.error_message);
}

/// The run's state hash, asked for on its simulation thread.
std::uint64_t hash_of_run(SimControl& control) {
  auto promise = std::make_shared<std::promise<std::uint64_t>>();
  std::future<std::uint64_t> hash = promise->get_future();
  if (!control.post([promise](SimControl& c) { promise->set_value(c.state_hash()); }) || hash.wait_for(10s) != std::future_status::ready) {
    throw Error("bench control: the run did not answer for its state hash");
  }
  return hash.get();
}

/// One end of the line-based conversation between the simulation process and the client process.
class Channel {
 public:
  /// Reads `in`, writes `out`; `peer` names the other process in errors.
  Channel(int in, int out, std::string peer) : in_(in), out_(out), peer_(std::move(peer)) {}
  Channel(const Channel&) = delete;
  Channel& operator=(const Channel&) = delete;
  ~Channel() {
    ::close(in_);
    ::close(out_);
  }
  void send(const std::string& line) {
    const std::string text = line + "\n";
    std::size_t done = 0;
    while (done < text.size()) {
      const ssize_t n = ::write(out_, text.data() + done, text.size() - done);
      if (n <= 0) throw Error("bench control: " + peer_ + " has gone (write failed)");
      done += static_cast<std::size_t>(n);
    }
  }
  /// The next line; throws when the other process has gone or said nothing within `timeout`.
  std::string receive(std::chrono::seconds timeout) {
    const auto give_up = Clock::now() + timeout;
    for (;;) {
      if (const auto nl = buffer_.find('\n'); nl != std::string::npos) {
        std::string line = buffer_.substr(0, nl);
        buffer_.erase(0, nl + 1);
        return line;
      }
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(give_up - Clock::now()).count();
      if (left <= 0) throw Error("bench control: " + peer_ + " said nothing within " + std::to_string(timeout.count()) + " s");
      pollfd p{in_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1000))) <= 0) continue;
      char buf[65536];
      const ssize_t n = ::read(in_, buf, sizeof buf);
      if (n <= 0) throw Error("bench control: " + peer_ + " has gone" + (buffer_.empty() ? std::string() : ": " + buffer_));
      buffer_.append(buf, static_cast<std::size_t>(n));
    }
  }

 private:
  int in_, out_;
  std::string peer_;
  std::string buffer_;
};

/// A SimulateSteps goal of `steps` as a CDR message.
std::vector<std::uint8_t> goal_body(std::uint64_t steps) {
  std::vector<std::uint8_t> out;
  cdr::Writer w(out, "simulation_interfaces/action/SimulateSteps_Goal");
  w.value("steps", steps);
  return out;
}

/// CPU seconds of this process so far (every thread).
double process_cpu_seconds() {
  struct rusage ru {};
  ::getrusage(RUSAGE_SELF, &ru);
  const auto s = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return s(ru.ru_utime) + s(ru.ru_stime);
}

/// The client process: every call over the wire, timed here. Around each SimulateSteps goal it
/// tells the simulation process ("mark" -> "ok" before, "lockstep" after), which counts its CPU
/// over the goal and then runs the same steps lockstep ("<wall s> <same hash 0|1> <CPU s of the
/// goal> <CPU s of the lockstep run>"), so the two alternate. Returns the round trips (s) and
/// the action's figures.
json client_side(int domain, const BenchControlOptions& o, Channel& sim) {
  ros2::DdsParticipant dds(domain, ros2::participant_user_data());
  // "ready <x> <y>": where the floor is clear for a spawned robot
  double spot_x = 0, spot_y = 0;
  if (std::sscanf(sim.receive(std::chrono::seconds(300)).c_str(), "ready %lf %lf", &spot_x, &spot_y) != 2) {
    throw Error("bench control: the simulation process did not start");
  }
  Caller reset(dds, "/reset_simulation", iface::ResetSimulation::id);
  Caller step(dds, "/step_simulation", iface::StepSimulation::id);
  ros2::ActionClient action(dds, ros2::action_topics("/simulate_steps", "simulation_interfaces/action/SimulateSteps"));
  if (!action.wait_for_server(10s)) throw Error("bench control: no server for the /simulate_steps action within 10 s");
  // warm-up: the first replies wait for the server to see the client's reply reader
  for (int k = 0; k < 5; ++k) {
    demand_ok(step.call<iface::StepSimulation>({1}), "StepSimulation");
    demand_ok(reset.call<iface::ResetSimulation>({scope::kDefault}), "ResetSimulation");
  }
  json out;
  // ResetSimulation, each after StepSimulation(steps_between_resets), not timed
  std::fprintf(stderr, "bench: control: %d ResetSimulation round trips, %d steps before each ...\n", o.resets, o.steps_between_resets);
  std::vector<double> resets;
  for (int k = 0; k < o.resets; ++k) {
    demand_ok(step.call<iface::StepSimulation>({static_cast<std::uint64_t>(o.steps_between_resets)}), "StepSimulation");
    const auto t0 = Clock::now();
    const Result r = reset.call<iface::ResetSimulation>({scope::kDefault});
    resets.push_back(since(t0));
    demand_ok(r, "ResetSimulation");
  }
  out["reset_s"] = resets;
  // StepSimulation(1) from PAUSED: answered when the step is done
  std::fprintf(stderr, "bench: control: %d StepSimulation(1) round trips ...\n", o.steps);
  std::vector<double> steps;
  for (int k = 0; k < o.steps; ++k) {
    const auto t0 = Clock::now();
    const Result r = step.call<iface::StepSimulation>({1});
    steps.push_back(since(t0));
    demand_ok(r, "StepSimulation");
  }
  out["step_s"] = steps;
  // SimulateSteps goals, each from the start state, alternating with the lockstep runs
  const auto result_timeout = std::chrono::milliseconds(60'000 + static_cast<std::int64_t>(o.action_steps) * 10);
  std::vector<double> by_action, lockstep, action_cpu, lockstep_cpu;
  bool same_hash = true;
  // round 0 is a warm-up, not counted: the action's first replies wait for their readers to match
  for (int round = 0; round <= o.action_rounds; ++round) {
    std::fprintf(stderr, "bench: control: a %llu-step SimulateSteps goal, then as many lockstep steps in-process (%s%d of %d) ...\n",
                 static_cast<unsigned long long>(o.action_steps), round == 0 ? "warm-up, " : "round ", round, o.action_rounds);
    demand_ok(reset.call<iface::ResetSimulation>({scope::kDefault}), "ResetSimulation");
    sim.send("mark");
    if (sim.receive(std::chrono::seconds(60)) != "ok") throw Error("bench control: the simulation process did not mark its CPU time");
    ros2::GoalId id{};
    id[0] = static_cast<std::uint8_t>(round + 1);
    id[15] = 0xbe;
    std::string why;
    const auto t0 = Clock::now();
    const auto accepted = action.send_goal(id, goal_body(o.action_steps), 10s, &why);
    if (!accepted) throw Error("bench control: SimulateSteps goal: " + why);
    if (!accepted->accepted) throw Error("bench control: SimulateSteps goal rejected");
    const auto result = action.get_result(id, result_timeout, &why);
    const double action_s = since(t0);
    if (!result) throw Error("bench control: SimulateSteps result: " + why);
    const auto res = decode_response<iface::SimulateStepsGetResult>(*result, WireVersion::v1);
    if (!res.value) throw Error("bench control: SimulateSteps result does not decode: " + res.problem);
    if (res.value->status != goal_status::kSucceeded) {
      throw Error("bench control: SimulateSteps ended with status " + std::to_string(res.value->status) + ": " +
                  res.value->result.error_message);
    }
    // the same steps lockstep, in the simulation process (its run stands paused meanwhile)
    sim.send("lockstep");
    double seconds = 0, cpu_goal = 0, cpu_lockstep = 0;
    int same = 0;
    if (std::sscanf(sim.receive(std::chrono::seconds(60) + std::chrono::seconds(o.action_steps / 100)).c_str(), "%lf %d %lf %lf", &seconds,
                    &same, &cpu_goal, &cpu_lockstep) != 4) {
      throw Error("bench control: no lockstep time from the simulation process");
    }
    if (round > 0) {
      by_action.push_back(action_s);
      lockstep.push_back(seconds);
      action_cpu.push_back(cpu_goal);
      lockstep_cpu.push_back(cpu_lockstep);
    }
    same_hash = same_hash && same == 1;
  }
  // SpawnEntity of a built-in rescue robot, then DeleteEntity, from PAUSED (round 0: warm-up)
  std::fprintf(stderr, "bench: control: %d SpawnEntity and DeleteEntity round trips ...\n", o.spawns);
  demand_ok(reset.call<iface::ResetSimulation>({scope::kDefault}), "ResetSimulation");
  Caller spawn(dds, "/spawn_entity", iface::SpawnEntity::id);
  Caller remove(dds, "/delete_entity", iface::DeleteEntity::id);
  std::vector<double> spawns, deletes;
  for (int k = 0; k <= o.spawns; ++k) {
    SpawnRequest r;
    r.name = "bench_robot";
    r.uri = "rescue_robot";
    r.pose = Pose3{Vec3(spot_x, spot_y, 0), Quat::Identity()};
    auto t0 = Clock::now();
    const auto answer = spawn.call<iface::SpawnEntity>(r);
    const double spawn_s = since(t0);
    demand_ok(answer.result, "SpawnEntity");
    t0 = Clock::now();
    demand_ok(remove.call<iface::DeleteEntity>({"bench_robot"}), "DeleteEntity");
    if (k > 0) {
      spawns.push_back(spawn_s);
      deletes.push_back(since(t0));
    }
  }
  out["spawn_s"] = spawns;
  out["delete_s"] = deletes;
  out["action_s"] = by_action;
  out["lockstep_s"] = lockstep;
  out["action_cpu_s"] = action_cpu;
  out["lockstep_cpu_s"] = lockstep_cpu;
  out["same_state_hash"] = same_hash;
  return out;
}

json measure(const Scenario& def, const ModelMap& models, const BenchControlOptions& o) {
  // Cyclone on loopback only, without multicast, on a domain of this process's own
  ::setenv("CYCLONEDDS_URI",
           "<General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces><AllowMulticast>false</AllowMulticast></General>"
           "<Discovery><ParticipantIndex>auto</ParticipantIndex><Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery>",
           1);
  const int domain = lease_dds_domain();
  // a write to a process that has gone is an error to report, not a signal that ends this one
  std::signal(SIGPIPE, SIG_IGN);
  // the client in a process of its own, as a ROS tool is: two participants in one process share
  // Cyclone's domain and deliver to each other in memory, never through the loopback interface.
  // Forked now, before this process has a thread or a participant.
  int to_client[2], to_sim[2];
  if (::pipe(to_client) != 0 || ::pipe(to_sim) != 0) throw Error("bench control: pipe failed");
  const pid_t client = ::fork();
  if (client < 0) throw Error("bench control: fork failed");
  if (client == 0) {
    ::close(to_client[1]);
    ::close(to_sim[0]);
    Channel sim(to_client[0], to_sim[1], "the simulation process");
    json out;
    try {
      out = client_side(domain, o, sim);
    } catch (const std::exception& e) {
      out = {{"error", e.what()}};
    }
    struct rusage ru {};
    ::getrusage(RUSAGE_SELF, &ru);
    out["peak_memory_mb"] = static_cast<double>(ru.ru_maxrss) / 1024.0;
    try {
      sim.send("result " + out.dump());
    } catch (const std::exception&) {
    }
    ::_exit(0);
  }
  ::close(to_client[0]);
  ::close(to_sim[1]);
  struct Reaper {
    pid_t pid;
    ~Reaper() {
      // the client ends on its own once its channel closes; it is waited for so it is no zombie
      int status = 0;
      ::waitpid(pid, &status, 0);
    }
  } reaper{client};
  Channel channel(to_sim[0], to_client[1], "the client process");

  Scenario s = def;
  s.duration = 1e9;  // until stopped
  s.realtime = false;
  SessionOptions so;
  so.cameras = false;
  so.controllers = false;
  so.control = true;
  so.control_options.start_paused = true;

  // the run, as `rescuesim run --ros2 --paused` runs it
  std::fprintf(stderr,
               "bench: control: the default scenario with the ROS 2 bridge, paused, on loopback (domain %d), a client process ...\n",
               domain);
  Session run(s, models, so);
  Ros2Options ro;
  ro.domain_id = domain;
  ro.distro = Ros2Distro::iron_or_newer;  // jazzy, rescuesim's default
  std::unique_ptr<Bridge> bridge = make_ros2_bridge(ro);
  bridge->start(run.sim());
  std::atomic<bool> stop{false};
  std::thread runner([&] { run.run(&stop); });
  struct Joiner {
    std::atomic<bool>& stop;
    std::thread& runner;
    Bridge& bridge;
    ~Joiner() {
      stop = true;
      if (runner.joinable()) runner.join();
      bridge.stop();
    }
  } joiner{stop, runner, *bridge};

  // the plain Session: the in-process baselines
  SessionOptions plain_options = so;
  plain_options.control = false;
  Session plain(s, models, plain_options);
  const SessionSnapshot start = plain.snapshot();
  const SimTime dt = SimTime::from_seconds(plain.sim().dt());
  const auto plain_steps = [&](std::uint64_t n) {
    for (std::uint64_t k = 0; k < n; ++k) plain.step_until(plain.sim().time() + dt);
  };

  // the client's calls, and the lockstep runs it asks for between its goals
  const auto spot = free_spot(run.sim().world(), run.sim().state(), 0.45, {run.sim().world().robots[0].X_W_start.p.head<2>()});
  if (!spot) throw Error("bench control: no free spot for a robot in the default scenario");
  channel.send("ready " + std::to_string(spot->x()) + " " + std::to_string(spot->y()));
  json wire;
  double cpu_mark = 0;
  const auto number = [](double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9f", v);
    return std::string(buf);
  };
  for (;;) {
    const std::string line = channel.receive(std::chrono::seconds(3600));
    if (line == "mark") {
      cpu_mark = process_cpu_seconds();
      channel.send("ok");
    } else if (line == "lockstep") {
      // this process's CPU over the goal: the run's thread and the bridge's (this thread waited)
      const double cpu_goal = process_cpu_seconds() - cpu_mark;
      plain.restore(start);
      const double cpu0 = process_cpu_seconds();
      const auto t0 = Clock::now();
      plain_steps(o.action_steps);
      const double seconds = since(t0);
      const double cpu_lockstep = process_cpu_seconds() - cpu0;
      // N steps from PAUSED are N lockstep steps (issue 37): the same state, bitwise
      const bool same = hash_of_run(*run.control()) == state_hash(plain.sim().state());
      channel.send(number(seconds) + " " + (same ? "1" : "0") + " " + number(cpu_goal) + " " + number(cpu_lockstep));
    } else if (line.starts_with("result ")) {
      wire = json::parse(line.substr(7));
      break;
    } else {
      throw Error("bench control: the client said '" + line + "'");
    }
  }
  if (wire.contains("error")) throw Error(wire["error"].get<std::string>());
  const auto seconds_of = [&](const char* key) { return wire.value(key, std::vector<double>{}); };

  json j;
  // ResetSimulation beside Session::restore alone and beside a rebuild
  {
    std::vector<double> restore;
    for (int k = 0; k < o.resets; ++k) {
      plain_steps(static_cast<std::uint64_t>(o.steps_between_resets));
      const auto t0 = Clock::now();
      plain.restore(start);
      restore.push_back(since(t0));
    }
    // rebuilding: what a client without reset does (restarts the simulator), without the bridge
    std::fprintf(stderr, "bench: control: Session::restore %d times, rebuilding the Session 5 times ...\n", o.resets);
    const double rebuild = median_seconds(5, [&] { Session fresh(s, models, so); });
    const json t = spread_ms(seconds_of("reset_s")), b = spread_ms(restore);
    const double p50 = t.value("p50_ms", 0.0), rebuild_ms = rebuild * 1e3;
    json f = ratio_figure(p50, "ms (round trip, p50)", b.value("p50_ms", 0.0),
                          "Session::restore of the start snapshot alone, in-process, after the same steps (p50)");
    f["round_trip"] = t;
    f["restore"] = b;
    f["rebuild_ms"] = rebuild_ms;
    f["rebuild_is"] = "constructing the Session anew (world, Bullet, Embree, control surface), no bridge; median of 5";
    f["ratio_to_rebuild"] = rebuild_ms > 0 ? p50 / rebuild_ms : 0.0;
    f["steps_before_each_reset"] = o.steps_between_resets;
    f["target_ms"] = 5.0;
    f["meets_target"] = t.value("calls", 0) > 0 && p50 < 5.0;
    j["reset_simulation"] = f;
  }
  // StepSimulation(1) beside one step in-process
  {
    std::fprintf(stderr, "bench: control: %d steps in-process ...\n", o.steps);
    std::vector<double> local;
    plain.restore(start);
    for (int k = 0; k < o.steps; ++k) {
      const auto t0 = Clock::now();
      plain_steps(1);
      local.push_back(since(t0));
    }
    const json t = spread_ms(seconds_of("step_s")), b = spread_ms(local);
    const double p50 = t.value("p50_ms", 0.0);
    json f = ratio_figure(p50, "ms (round trip, p50)", b.value("p50_ms", 0.0), "one Session step (step_until one dt), in-process (p50)");
    f["round_trip"] = t;
    f["in_process_step"] = b;
    f["overhead_ms"] = p50 - b.value("p50_ms", 0.0);
    f["target_ms"] = 1.0;
    f["meets_target"] = t.value("calls", 0) > 0 && p50 < 1.0;
    j["step_simulation"] = f;
  }
  // SpawnEntity and DeleteEntity beside Simulation::add_robot and remove_robot in-process, and
  // the same in a run that renders cameras (its renderer is built afresh for each change)
  {
    std::fprintf(stderr, "bench: control: %d robots added and removed in-process ...\n", o.spawns);
    const auto robot = [&] {
      RobotInstance r = place_robot("bench_robot", models.at("rescue_robot"), Pose3{Vec3(spot->x(), spot->y(), 0), Quat::Identity()});
      r.spawned = true;
      r.ns = r.name;
      return r;
    };
    const auto add_remove = [&](Simulation& sim, std::vector<double>& adds, std::vector<double>& removes, int n) {
      for (int k = 0; k < n; ++k) {
        auto t0 = Clock::now();
        const RobotIndex index = sim.add_robot(robot());
        adds.push_back(since(t0));
        t0 = Clock::now();
        sim.remove_robot(index);
        removes.push_back(since(t0));
      }
    };
    plain.restore(start);
    std::vector<double> adds, removes;
    add_remove(plain.sim(), adds, removes, o.spawns);
    const json t = spread_ms(seconds_of("spawn_s")), d = spread_ms(seconds_of("delete_s")), b = spread_ms(adds), br = spread_ms(removes);
    json f = ratio_figure(t.value("p50_ms", 0.0), "ms (round trip, p50)", b.value("p50_ms", 0.0),
                          "Simulation::add_robot of the same robot in-process, no camera renderer (p50)");
    f["round_trip"] = t;
    f["delete_round_trip"] = d;
    f["add_robot"] = b;
    f["remove_robot"] = br;
    // no target in the issue: Gazebo's spawn service takes a few hundred ms for a robot; ours, tens
    f["target_ms"] = 50.0;
    f["meets_target"] = t.value("calls", 0) > 0 && t.value("p50_ms", 0.0) < 50.0;
    f["what"] = "a built-in rescue_robot (laser, sonars, IMU, cameras) spawned at a clear spot of the default world, then deleted; "
                "the world versions, Bullet and Embree rebuilt each time";
    // with cameras: the run's renderer (EGL) made again for each change
    try {
      SessionOptions co = plain_options;
      co.cameras = true;
      Session cams(s, models, co);
      if (cams.render_device().empty()) throw Error("no renderer");
      std::vector<double> cadds, cremoves;
      add_remove(cams.sim(), cadds, cremoves, 5);
      f["add_robot_with_cameras"] = spread_ms(cadds);
      f["remove_robot_with_cameras"] = spread_ms(cremoves);
      f["render_device"] = cams.render_device();
    } catch (const std::exception& e) {
      f["add_robot_with_cameras"] = std::string("skipped: ") + e.what();
    }
    j["spawn_entity"] = f;
  }
  // SimulateSteps beside the same steps lockstep
  {
    const std::vector<double> by_action = seconds_of("action_s"), lockstep = seconds_of("lockstep_s");
    const double a = median(by_action), b = median(lockstep);
    const double n = static_cast<double>(o.action_steps);
    json f;
    f["value"] = a > 0 ? n / a : 0.0;
    f["unit"] = "steps/s";
    f["baseline"] = b > 0 ? n / b : 0.0;
    f["baseline_is"] =
        "the same steps lockstep (Session::step_until) in the simulation process, on a Session of the same scenario without a bridge";
    f["ratio"] = a > 0 ? b / a : 0.0;
    f["target_ratio"] = 0.9;
    f["meets_target"] = a > 0 && b / a >= 0.9;
    f["steps"] = o.action_steps;
    f["action_wall_s"] = by_action;
    f["lockstep_wall_s"] = lockstep;
    // the same comparison in CPU seconds of the simulation process, which other load on the
    // machine disturbs less than wall time
    const std::vector<double> cpu_a = seconds_of("action_cpu_s"), cpu_b = seconds_of("lockstep_cpu_s");
    f["action_cpu_s"] = cpu_a;
    f["lockstep_cpu_s"] = cpu_b;
    f["cpu_ratio"] = median(cpu_a) > 0 ? median(cpu_b) / median(cpu_a) : 0.0;
    f["same_state_hash"] = wire.value("same_state_hash", false);
    f["note"] = "action wall time from send_goal to the get_result reply, in the client process; alternating rounds (action, "
                "lockstep), each from the start state; medians; ratio = lockstep time / action time (within 10 %: >= 0.9)";
    j["simulate_steps"] = f;
  }
  struct rusage ru {};
  ::getrusage(RUSAGE_SELF, &ru);
  j["peak_memory_mb"] = static_cast<double>(ru.ru_maxrss) / 1024.0;
  j["peak_memory_is"] = "the simulation process: the run with the ROS 2 bridge and the plain Session beside it";
  j["client_peak_memory_mb"] = wire.value("peak_memory_mb", 0.0);
  return j;
}

#endif

}  // namespace

json bench_control(const Scenario& scenario, const ModelMap& models, const BenchControlOptions& options) {
#ifndef RESCUESIM_HAS_ROS2
  (void)scenario;
  (void)models;
  (void)options;
  return json{{"skipped", "built without the ROS 2 bridge (Cyclone DDS not found at build time)"}};
#else
  // in a child process: its peak memory is its own, and nothing of DDS outlives it
  json j = run_in_child([&] { return measure(scenario, models, options); }).report;
  j["note"] = "the default scenario without cameras, built-in controllers off, started PAUSED; the ROS 2 bridge in the "
              "simulation process, the client (rmw_cyclonedds's request/reply wire) in a process of its own, on a "
              "loopback-only Cyclone domain; p50/p99 of single calls, one at a time";
  return j;
#endif
}

}  // namespace rescuesim::bench
