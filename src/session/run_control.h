#pragma once
/// RunControl: the one implementation of control::SimControl (bus/sim_control.h) beneath every
/// front end (ROS 2 services and actions, ROS 1 services, Foxglove services, Python). It lives
/// beside a Session and is driven by Session::run(): before each step the run loop calls
/// before_step(), which runs the tasks front ends posted and, while the run is paused, waits
/// for more (or for steps to take); after each step, after_step() advances a stepping job.
///
/// Reset goes back to the snapshot taken when the run started (Session::snapshot), so a reset
/// is bitwise exact: the state hash after it equals the hash at the start, and the same
/// commands after it give the same messages. Teleports (set_entity_state) edit the State and
/// restore it into the engine (Simulation::restore), the way a snapshot is restored. Spawning
/// (run_control_spawn.cpp) adds robots and loose bodies to the running simulation
/// (Simulation::add_robot, add_body); a reset of spawned entities, or of everything, removes them.

#include <atomic>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "bus/sim_control.h"

namespace rescuesim {

class Session;
struct SessionSnapshot;

/// Where a run finds what GetAvailableWorlds lists, and how it starts.
struct RunControlOptions {
  std::vector<std::filesystem::path> world_dirs;  ///< folders of shipped scenarios and worlds (*.yaml, *.svg)
  bool start_paused = false;                      ///< PAUSED before the first step (like gz sim without -r)
};

class RunControl final : public control::SimControl {
 public:
  RunControl(Session& session, RunControlOptions options = {});
  ~RunControl() override;
  RunControl(const RunControl&) = delete;
  RunControl& operator=(const RunControl&) = delete;

  // ---- for Session::run (the simulation thread) ----

  /// Takes the start snapshot (once, before the first step of the run).
  void arm();
  /// Runs the posted tasks; while PAUSED or STOPPED without steps to take, waits for tasks until
  /// `stop` is set. True: take a step now. False: the run is to end (QUITTING, or `stop`).
  bool before_step(const std::atomic<bool>* stop);
  /// After a step: counts it against the stepping job in progress (feedback, done).
  void after_step();
  /// The run has ended: the job in progress fails ("the run ended"), tasks still posted run once
  /// (so their clients get answers), and post() refuses from now on.
  void close();
  /// Bumped whenever pacing must start afresh (after a pause, a reset, a change of rate).
  std::uint64_t pacing_epoch() const { return pacing_epoch_; }
  /// The realtime pace (sim s per wall s) and whether to pace at all; parameters can change them.
  bool realtime() const { return realtime_; }
  double rate() const { return rate_; }
  /// Posted tasks that ran, and requests refused because the queue was full or closed.
  std::uint64_t tasks_run() const { return tasks_run_; }

  // ---- control::SimControl ----
  bool post(std::function<void(SimControl&)> task) override;
  control::SimulatorFeatures features() const override;
  control::RunState run_state() const override { return state_; }
  control::Result set_run_state(control::RunState target) override;
  control::Result start_steps(control::StepJob job, bool action) override;
  bool cancel_steps() override;
  control::Result reset(std::uint8_t scope) override;
  control::Result entities(const control::EntityFilters& filters, std::vector<std::string>& names) const override;
  control::Result entity_state(const std::string& name, control::EntityState& out) const override;
  control::Result set_entity_state(const std::string& name, const control::EntityState& state, bool set_pose,
                                   bool set_twist, bool set_acceleration) override;
  control::Result entity_info(const std::string& name, control::EntityInfo& out) const override;
  control::Result entity_bounds(const std::string& name, control::Bounds& out) const override;
  control::Result named_poses(const control::TagsFilter& tags, std::vector<control::NamedPose>& out) const override;
  control::Result named_pose_bounds(const std::string& name, control::Bounds& out) const override;
  control::Result spawnables(const std::vector<std::string>& sources, std::vector<control::Spawnable>& out) const override;
  control::Result spawn(const control::SpawnRequest& request, std::string& entity_name) override;
  control::Result remove(const std::string& name) override;
  control::Result available_worlds(const std::vector<std::string>& sources,
                                   std::vector<control::WorldResource>& out) const override;
  control::Result current_world(control::WorldResource& out) const override;
  control::Result load_world(const control::WorldResource& world, control::WorldResource& loaded) override;
  control::Result unload_world() override;
  std::vector<control::ParameterDescriptor> parameter_descriptors() const override;
  control::ParameterValue parameter(const std::string& name) const override;
  control::SetParameterResult set_parameter(const control::Parameter& p) override;
  std::uint64_t state_hash() const override;
  std::int64_t time_ns() const override;
  std::int64_t steps_taken() const override;

 private:
  /// An entity: what kind and which index in the World.
  struct Entity {
    enum class Kind { robot, victim, rubble, fixed };
    Kind kind;
    std::size_t index;
    std::string name;
  };
  const Entity* find(const std::string& name) const;
  /// Why a pose is no pose (not finite, not a unit quaternion), or "": INVALID_POSE's message.
  static std::string pose_problem(const Pose3& X);
  /// entities_ from the world now (after a spawn, a delete, a reset).
  void rebuild_entities();
  void run_tasks();
  void end_job(const control::Result& result);
  void restore_start();

  Session& session_;
  RunControlOptions options_;
  std::vector<Entity> entities_;  ///< robots, victims, rubble, then fixed objects, in World order
  std::unique_ptr<SessionSnapshot> start_;
  control::RunState state_ = control::RunState::playing;
  bool realtime_ = false;
  double rate_ = 1.0;
  std::uint64_t pacing_epoch_ = 0;
  std::uint64_t tasks_run_ = 0;

  struct Job {
    control::StepJob job;
    std::uint64_t completed = 0;
  };
  std::optional<Job> job_;

  std::mutex mutex_;
  std::condition_variable posted_;
  std::deque<std::function<void(SimControl&)>> tasks_;  ///< guarded by mutex_
  bool closed_ = false;                                 ///< guarded by mutex_
};

}  // namespace rescuesim
