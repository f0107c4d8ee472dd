#pragma once
/// A run: a scenario's simulation with its built-in controllers attached, what it recorded,
/// and the files it leaves (summary.json, overview.png, trajectory.csv, sensors/*.png). The
/// `rescuesim run` command, batches and the Python API all run scenarios through this.

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "autonomy/explorer.h"
#include "import/scenario/scenario.h"
#include "mission/mission.h"
#include "mission/mission_system.h"
#include "sensors/camera/render_camera_service.h"
#include "session/recorder.h"
#include "session/run_control.h"
#include "sim/run_system.h"
#include "sim/simulation.h"
#include "team/builtin_controllers.h"
#include "team/builtin_team.h"

namespace rescuesim {

/// How a victim fared.
struct VictimResult {
  std::string name;
  bool found = false;
  double time = -1;       ///< sim time first seen (s)
  std::string by;         ///< robot that saw it
};

/// What a run measured.
struct RunResult {
  std::string scenario;
  std::uint64_t seed = 0;
  double sim_time = 0;          ///< s simulated
  double wall_time = 0;         ///< s it took
  double real_time_factor = 0;  ///< sim_time / wall_time
  std::string stop_reason;      ///< "duration", "all victims found", "interrupted", or the trouble message
  bool trouble = false;         ///< numerical trouble stopped the run
  std::vector<VictimResult> victims;
  int victims_found = 0;
  std::string victim_detection;  ///< "thermal images" (cameras rendered) or "line of sight" (no cameras)
  double coverage = 0;          ///< fraction of free floor passed within 1 m of (see docs/outputs.md)
  int collisions = 0;           ///< contacts begun with walls, obstacles, victims, robots
  double distance = 0;          ///< m driven (ground truth)
  std::vector<std::pair<std::string, std::uint64_t>> message_counts;  ///< per topic
  std::uint64_t state_hash = 0; ///< of the final State (determinism checks)
  std::optional<MissionResult> mission;  ///< the referee's score and the radio's figures, with a mission
  /// What each built-in explorer did (robot name, its counters), for the robots that have one.
  std::vector<std::pair<std::string, autonomy::ExplorerStats>> explorers;
};

/// Settings of a run beyond its scenario.
struct SessionOptions {
  bool controllers = true;      ///< attach the scenario's built-in controllers
  bool cameras = true;          ///< render camera sensors (false: every camera sensor is switched off)
  double trajectory_rate = 10;  ///< Hz
  /// Most trajectory samples kept (all robots together; 80 bytes each, so 10.5 MB by default:
  /// 3.6 h of one robot at 10 Hz). When a run reaches it, every other sample time is dropped
  /// and the rate halves from there, so a run of any length keeps its whole path, evenly
  /// thinned, in bounded memory (trajectory.csv then has the coarser spacing).
  std::size_t trajectory_max_points = std::size_t{1} << 17;
  /// Sim seconds between returns of freed memory to the system during run() (core/memory.h); 0: never.
  double return_memory_every = 60;
  /// > 0: synchronous with an outside controller (a ROS node), like Webots' synchronous mode:
  /// after each step that published laser scans, run() waits up to this many wall seconds for
  /// as many velocity commands before stepping on, so the command answering a scan is applied
  /// at the very next step, however fast or slow the controller is.
  double sync_timeout = 0;
  SimOptions sim;               ///< seed and physics are filled from the scenario
  /// Offer the control surface (reset, pause, step, teleport, parameters: session/run_control.h)
  /// to the bridges. It takes a snapshot at the start of run() (the state a reset goes back to).
  bool control = false;
  RunControlOptions control_options;
};

/// Everything Session::restore needs to go back to a moment of a run: the simulation's State
/// and what lives beside it (camera frames in flight, and each run system's memory: the
/// built-in controllers', the recorder's, the mission's, the team's). Copyable; only for the
/// Session that made it.
struct SessionSnapshot {
  State state;
  std::shared_ptr<const struct SessionExtras> extras;  ///< the rest, opaque (session_snapshot.cpp)
};

/// A run is a Simulation and a list of run systems (sim/run_system.h) stepped around it, as
/// gz-sim composes a run from systems: the built-in controllers (team/builtin_controllers.h),
/// the recorder (session/recorder.h), and with a mission the mission (mission/mission_system.h)
/// and the built-in team (team/builtin_team.h), in that order; add_system() appends more.
class Session {
 public:
  /// Builds the world, validates it (throws Error listing the problems), compiles and sets up.
  Session(const Scenario& scenario, const ModelMap& models, SessionOptions options = {});
  ~Session();

  Simulation& sim() { return *sim_; }
  const Scenario& scenario() const { return scenario_; }
  const WorldSpec& world_spec() const { return spec_; }
  /// The GL device rendering the cameras, or "" when there are none.
  std::string render_device() const;
  /// True when camera sensors render (a camera service runs): a robot spawned with cameras gets images.
  bool renders_cameras() const { return cameras_ != nullptr; }
  /// Warnings from importing the world.
  const Diagnostics& diagnostics() const { return diagnostics_; }

  /// Steps until the scenario's duration, all victims found (when asked), trouble, or `stop`.
  /// `progress` is called from the stepping thread about every 0.1 s of wall time.
  RunResult run(const std::atomic<bool>* stop = nullptr, const std::function<void(const RunResult&)>& progress = nullptr);

  /// Steps to sim time `t` (no further when already there), recording the trajectory and
  /// coverage as run() does; for callers that drive the robots between steps (the Python API).
  /// Returns false as soon as numerical trouble stops the simulation.
  bool step_until(SimTime t);

  /// The run as it is now, to restore() later: Simulation::snapshot (a synchronisation point
  /// for the physics engine, see there) plus the camera frames in flight, the built-in
  /// controllers (their memory and the commands they queued for the next step), the mission
  /// and the recordings. Restoring it and stepping on with the same commands gives bitwise the
  /// same messages, images included. Not while run() is stepping.
  SessionSnapshot snapshot();
  /// Goes back to `snapshot` (from this Session): frames in flight now are dropped and the
  /// snapshot's are rendered anew; commands queued now (bridges' too) are dropped and the
  /// built-in controllers' queued at the snapshot are queued again. The Bus's message counts,
  /// the wall time and the last camera frames (sensors/*.png) are not rewound.
  void restore(const SessionSnapshot& snapshot);

  /// Appends a run system: its pre_step and post_step run around every step after the built-in
  /// ones', and its memory is part of snapshots from now on. Not while run() is stepping.
  void add_system(std::unique_ptr<RunSystem> system);

  /// The control surface (SessionOptions::control), or null.
  RunControl* control() { return control_.get(); }

  /// The run's mission (referee and radio), or null when the scenario has none.
  Mission* mission() { return mission_.get(); }
  const Mission* mission() const { return mission_.get(); }

  /// Scans a synchronous run (SessionOptions::sync_timeout) waited for in vain.
  std::uint64_t sync_timeouts() const { return sync_timeouts_; }
  /// The result so far (also valid during or after a run).
  RunResult result() const;
  /// Fraction of free floor passed within 1 m of so far (see docs/outputs.md).
  double coverage() const;
  /// Samples at record_interval() (see SessionOptions::trajectory_max_points), robots in order per time.
  const std::vector<TrajectoryPoint>& trajectory() const { return recorder_->trajectory(); }
  SimTime record_interval() const { return recorder_->record_interval(); }

  /// Writes summary.json, overview.png, trajectory.csv, world.svg, sensors/laser.png and, with
  /// a mission, score.png into `dir` (atomically, file by file).
  void write_outputs(const std::filesystem::path& dir, const RunResult& result) const;

 private:
  /// One Simulation step with the run systems around it.
  void step_once();
  /// Gives each robot that asked for a built-in controller its explorer (session_setup.cpp).
  void attach_controllers(const ModelMap& models);
  void write_camera_frames(const std::filesystem::path& dir) const;
  /// Robot `robot`'s last thermal frame as mono8 through its sensor's temperature window (the
  /// picture of a built-in report), or nothing when its thermal camera does not render.
  std::optional<msg::Image> victim_picture(RobotIndex robot) const;
  /// True when a scenario robot's thermal camera renders, so victims are found in its images.
  bool thermal_images_render() const;
  /// The camera service, built afresh for the world now (robots spawned or deleted), and the
  /// victim detector that reads its thermal images.
  void rebuild_cameras();

  Scenario scenario_;
  WorldSpec spec_;
  Diagnostics diagnostics_;
  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<Mission> mission_;  ///< after sim_ (it refers to it), before the systems that use it
  CameraServiceOptions camera_options_;
  std::unique_ptr<RenderCameraService> cameras_;  ///< attached to sim_ (not owned there); detached in ~Session
  std::unique_ptr<RunControl> control_;           ///< attached to sim_ (not owned there); detached in ~Session
  SessionOptions options_;
  // the run systems (session.cpp builds them; systems_ lists them in step order, the added ones last)
  std::unique_ptr<BuiltinControllers> controllers_;
  std::unique_ptr<Recorder> recorder_;
  std::unique_ptr<MissionSystem> mission_system_;  ///< with a mission
  std::unique_ptr<BuiltinTeam> team_;              ///< with a mission
  std::vector<std::unique_ptr<RunSystem>> added_systems_;
  std::vector<RunSystem*> systems_;
  double wall_time_ = 0;
  std::string stop_reason_;
  std::uint64_t sync_timeouts_ = 0;
};

}  // namespace rescuesim
