// rescuesim run: the main job. Runs a scenario headless and writes its outputs.

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "app/bridge_flags.h"
#include "app/data_dir.h"
#include "app/commands.h"
#include "core/log.h"
#include "core/process_clock.h"
#include "robots/rescue_robot.h"
#include "session/run_mode.h"
#include "session/scenario_load.h"
#include "session/session.h"
#include "bus/bridge.h"

namespace rescuesim::app {

namespace {

std::atomic<bool> g_interrupted{false};
extern "C" void on_sigint(int) { g_interrupted.store(true); }

struct RunCommand {
  std::string scenario;
  std::string world;
  std::vector<std::string> resource_paths;
  std::string out;
  std::optional<std::uint64_t> seed;
  std::optional<double> duration;
  bool realtime = false;
  std::optional<double> rate;
  bool quiet = false;
  bool no_cameras = false;
  std::string quality;
  bool no_controllers = false;
  bool paused = false;         ///< --paused: start PAUSED (a live bridge's client plays or steps it)
  std::optional<double> sync;  ///< --sync[=SECONDS]
  BridgeFlags bridges;
};


/// One line of progress: a bar, sim time, real-time factor, victims.
void print_progress(const RunResult& r, double duration, bool tty) {
  const double f = duration > 0 ? std::min(1.0, r.sim_time / duration) : 0;
  char bar[31];
  const int filled = static_cast<int>(f * 30);
  for (int i = 0; i < 30; ++i) bar[i] = i < filled ? '#' : '-';
  bar[30] = 0;
  const std::string score =
      r.mission ? fmt::format("  score {:g} ({}/{} reported)", r.mission->score, r.mission->victims_found, r.mission->victims)
                : std::string();
  std::fprintf(stderr, "%s[%s] %6.1f/%.0f s  %5.1fx real time  victims %d/%zu  collisions %d%s%s", tty ? "\r" : "", bar, r.sim_time,
               duration, r.real_time_factor, r.victims_found, r.victims.size(), r.collisions, score.c_str(), tty ? "  " : "\n");
  std::fflush(stderr);
}

int run(const RunCommand& c) {
  namespace fs = std::filesystem;
  // the scenario with the command line's overrides, then the run mode (session/run_mode.h)
  const ModelMap models = builtin_models();
  Scenario s = load_scenario_with_overrides(
      c.scenario, models, {.seed = c.seed, .duration = c.duration, .rate = c.rate, .world = c.world,
                  .resource_paths = c.resource_paths, .render_quality = c.quality});
  const RunMode mode = resolve_run_mode({.scenario_realtime = s.realtime,
                                         .realtime = c.realtime,
                                         .lockstep = c.bridges.lockstep,
                                         .sync = c.sync,
                                         .live_bridge = c.bridges.live(),
                                         .no_controllers = c.no_controllers,
                                         .keep_controllers = c.bridges.keep_controllers,
                                         .duration_given = c.duration.has_value()});
  SessionOptions so;
  so.cameras = !c.no_cameras;
  apply_run_mode(mode, s, so);
  // a live bridge offers the control surface (reset, pause, step, teleport, parameters; docs/ros.md)
  so.control = c.bridges.live();
  so.control_options.start_paused = c.paused;
  if (const auto data = data_dir()) so.control_options.world_dirs.push_back(*data / "worlds");
  if (c.paused && !so.control) throw Error("--paused needs a live bridge (--ros1, --ros2 or --foxglove) to play or step the run");
  Session session(s, models, so);
  auto bridges = make_bridges(c.bridges, {&session.scenario(), &session.world_spec(), so.cameras});
  print_diagnostics(session.diagnostics());
  const fs::path out = c.out.empty() ? fs::path("runs") / s.name : fs::path(c.out);
  const WorldSpec& w = session.world_spec();
  const bool forever = !std::isfinite(s.duration);
  std::printf("scenario %s (seed %llu, %s, %s): world %s\n%s", s.name.c_str(), static_cast<unsigned long long>(s.seed),
              pacing_name(mode.pacing), forever ? "until Ctrl-C" : fmt::format("{:.0f} s", s.duration).c_str(),
              w.name.c_str(), world_summary(w).c_str());
  if (s.mission) std::printf("%s", mission_summary(*s.mission, w).c_str());
  if (!session.render_device().empty())
    std::printf("  cameras on    %s, %s quality\n", session.render_device().c_str(), s.render_quality.c_str());
  if (!so.controllers) std::printf("  controllers   off (robots wait for cmd_vel)\n");
  for (auto& b : bridges) {
    b->start(session.sim());
    std::printf("  bridge        %s started\n", b->name().c_str());
  }
  std::fflush(stdout);
  // the cold start: from the exec of this process to the first laser scan on the Bus (printed
  // at the end; `rescuesim bench --cold-start` reads it). Only the laser topics are watched, so
  // the rest of the run's messages pass no extra subscriber
  double first_scan_s = -1;
  std::string first_scan_topic;
  std::vector<std::string> scan_topics;
  for (const Topic& t : session.sim().bus().topics()) {
    if (t.type == "sensor_msgs/LaserScan") scan_topics.push_back(t.name);
  }
  std::vector<SubscriptionId> first_scan;
  for (const std::string& name : scan_topics) {
    first_scan.push_back(session.sim().bus().subscribe(name, [&](const Topic& topic, const msg::Message&) {
      if (first_scan_s >= 0) return;
      first_scan_s = seconds_since_process_start();
      first_scan_topic = topic.name;
    }));
  }

  // Ctrl-C stops the run cleanly: the outputs of what ran are still written
  g_interrupted = false;
  std::signal(SIGINT, on_sigint);
  const bool tty = ::isatty(STDERR_FILENO);
  double next_line = 0;
  std::signal(SIGTERM, on_sigint);
  // progress lines every tenth of the run, or every 10 s of sim time when it runs until stopped
  const double line_every = forever ? 10.0 : s.duration / 10;
  const RunResult r = session.run(&g_interrupted, [&](const RunResult& p) {
    if (c.quiet) return;
    if (tty || p.sim_time >= next_line) {
      print_progress(p, forever ? 0 : s.duration, tty);
      next_line = p.sim_time + line_every;
    }
  });
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  for (SubscriptionId id : first_scan) session.sim().bus().unsubscribe(id);
  if (session.sync_timeouts() > 0) {
    std::printf("sync: %llu scans got no cmd_vel within %g s\n", static_cast<unsigned long long>(session.sync_timeouts()),
                mode.sync_timeout);
  }
  for (auto& b : bridges) {
    b->stop();
    const BridgeStats st = b->stats();
    std::printf("bridge %s: %llu messages sent, %llu dropped (slow subscribers), %llu commands received, %llu rejected\n",
                b->name().c_str(), static_cast<unsigned long long>(st.sent), static_cast<unsigned long long>(st.dropped),
                static_cast<unsigned long long>(st.received), static_cast<unsigned long long>(st.rejected));
  }
  if (!c.quiet) {
    print_progress(r, forever ? 0 : s.duration, tty);
    if (tty) std::fprintf(stderr, "\n");
  }
  session.write_outputs(out, r);
  std::printf("%.1f s simulated in %.2f s (%.1fx real time); stopped: %s\n", r.sim_time, r.wall_time, r.real_time_factor,
              r.stop_reason.c_str());
  if (first_scan_s >= 0)
    std::printf("cold start: first scan (%s) %.2f s after the process started\n", first_scan_topic.c_str(), first_scan_s);
  std::printf("victims found %d/%zu", r.victims_found, r.victims.size());
  for (const auto& v : r.victims) {
    if (v.found) std::printf(", %s at %.1f s", v.name.c_str(), v.time);
  }
  std::printf("\ncoverage %.0f%%, distance %.1f m, collisions %d\n", 100 * r.coverage, r.distance, r.collisions);
  if (r.mission) {
    const MissionResult& m = *r.mission;
    std::printf("mission score %g: %d/%d victims reported, %llu false, %llu duplicate, %llu out of contact", m.score, m.victims_found,
                m.victims, static_cast<unsigned long long>(m.counts[ReportOutcome::false_report]),
                static_cast<unsigned long long>(m.counts[ReportOutcome::duplicate]),
                static_cast<unsigned long long>(m.counts[ReportOutcome::out_of_contact]));
    std::printf("; radio contact");
    for (std::size_t i = 0; i < m.robot_names.size(); ++i) std::printf(" %s %.0f%%", m.robot_names[i].c_str(), 100 * m.contact_fraction[i]);
    std::printf("\n");
  }
  std::printf("wrote %s/{summary.json, overview.png,%s%s trajectory.csv, world.svg, sensors/}\n", out.string().c_str(),
              r.mission ? " score.png," : "", r.mission && !r.mission->pictures.empty() ? " reports/," : "");
  return r.trouble ? kExitFailure : kExitOk;
}

}  // namespace

void add_run_command(CLI::App& app, Action& action) {
  auto c = std::make_shared<RunCommand>();
  CLI::App* cmd = app.add_subcommand("run", "Run a scenario headless and write its outputs to runs/<name>/");
  cmd->footer(
      "Without SCENARIO, runs the built-in default (worlds/default.yaml): a seeded 8x8 maze with\n"
      "victims, rubble and raised areas, the rescue robot with laser, sonars, IMU and odometry,\n"
      "exploring on its own (wall following + A* to frontiers) for 180 s of sim time.\n\n"
      "Outputs: summary.json (victims found, coverage, collisions, distance, real-time factor,\n"
      "message counts), overview.png (map, path, laser map, victims), trajectory.csv, world.svg,\n"
      "sensors/laser.png; with a mission: block, score.png and reports/ (the reports' pictures).\n"
      "Ctrl-C stops early and still writes them.\n\n"
      "Examples:\n"
      "  rescuesim run\n"
      "  rescuesim run worlds/arena.yaml --seed 3\n"
      "  rescuesim run --world worlds/office.svg --duration 60 --out runs/office\n"
      "  rescuesim run --world worlds/rescue_yard.sdf --resource-path worlds/models   a Gazebo world (docs/worlds.md)\n\n"
      "As a ROS simulator (docs/ros.md): --ros1 and/or --ros2 run in realtime until Ctrl-C, with\n"
      "the built-in controllers off, so ROS nodes drive the robot through /cmd_vel:\n"
      "  roscore &  rescuesim run --ros1 --use-sim-time\n"
      "  rescuesim run --ros2 --ros-domain 7 --duration 600\n"
      "  rescuesim run worlds/arena.yaml --ros1 --ros2 --keep-controllers\n"
      "  rescuesim run --ros1 --use-sim-time --sync     lockstep with your node: each scan waits for its cmd_vel\n\n"
      "Modes, first match wins: --sync (lockstep, waiting for cmd_vel); --lockstep; --realtime or a\n"
      "live bridge (--ros1, --ros2, --foxglove): realtime; else the scenario's realtime: setting\n"
      "(default lockstep). --realtime with --sync or --lockstep is an error (exit 2).\n\n"
      "Watch in Foxglove or Lichtblick (docs/foxglove.md), record for later (docs/recording.md):\n"
      "  rescuesim run --foxglove --keep-controllers     then open ws://127.0.0.1:8765\n"
      "  rescuesim run --record runs/default.mcap        lockstep, lossless, byte-identical per seed\n"
      "  rescuesim recover runs/default.mcap.part        a killed recording, indexed again up to its last chunk");
  cmd->add_option("scenario", c->scenario,
                  "scenario YAML file (default: built-in); a relative path not found here is looked for in the installed worlds")
      ->transform(data_file());
  cmd->add_option("--world", c->world, "use this world instead of the scenario's: an SVG drawing, or an SDF world (.sdf, .world)")
      ->transform(data_file());
  cmd->add_option("--resource-path", c->resource_paths,
                  "a folder where package:// and model:// URIs are looked for first (repeatable; then the scenario's resource_paths, "
                  "then ROS_PACKAGE_PATH, AMENT_PREFIX_PATH and, for model://, GZ_SIM_RESOURCE_PATH, IGN_GAZEBO_RESOURCE_PATH, "
                  "GAZEBO_MODEL_PATH)")
      ->allow_extra_args(false);
  cmd->add_option("--seed", c->seed, "run seed (overrides the scenario's; also reseeds a generated maze)");
  cmd->add_option("--duration", c->duration, "sim time in seconds")->check(CLI::PositiveNumber);
  cmd->add_option("--sync", c->sync,
                  "with --ros1/--ros2: synchronous with your ROS controller, like Webots' synchronous mode: lockstep, but after "
                  "each laser scan the simulation waits (up to SECONDS of wall time) for the cmd_vel answering it, so a run goes "
                  "as fast as the controller and the command lands at the next step")
      ->expected(0, 1)
      ->default_str("1")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--realtime", c->realtime, "pace the run to the wall clock (default: lockstep, as fast as possible)");
  cmd->add_option("--rate", c->rate, "realtime pace: sim seconds per wall second")->check(CLI::PositiveNumber);
  cmd->add_option("--out,-o", c->out, "output folder (default runs/<scenario name>)");
  cmd->add_flag("--quiet,-q", c->quiet, "no progress bar");
  cmd->add_flag("--no-cameras", c->no_cameras, "switch off the colour, depth and thermal cameras (no OpenGL needed; faster)");
  cmd->add_option("--quality", c->quality, "camera rendering quality")->check(CLI::IsMember({"low", "medium", "high"}));
  add_bridge_flags(cmd, c->bridges);
  cmd->add_option("--record-chunk-seconds", c->bridges.record_chunk_seconds,
                  "with --record: write a chunk once it spans this much sim time (0: only at 1 MiB), so a killed run "
                  "loses at most about this much; 'rescuesim recover' saves the rest of its .part file")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--record-chunk-wall-seconds", c->bridges.record_chunk_wall_seconds,
                  "with --record in realtime: also write a chunk once it is this many wall seconds old (0: off; lockstep "
                  "recordings ignore it so they stay byte-identical per seed)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--paused", c->paused,
                "with a live bridge: start PAUSED; a client plays it (SetSimulationState, /unpause_physics) or steps it "
                "(StepSimulation, the SimulateSteps action; docs/ros.md \"Controlling a run\")");
  cmd->add_flag("--no-controllers", c->no_controllers, "switch the scenario's built-in controllers off (robots wait for cmd_vel)");
  cmd->final_callback([c, &action] { action = [c] { return run(*c); }; });
}

}  // namespace rescuesim::app
