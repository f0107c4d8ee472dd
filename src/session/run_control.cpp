// RunControl: pause, play, step and reset a Session's run, its worlds and its parameters, for
// every front end (see run_control.h); the entities are in run_control_entities.cpp.

#include "session/run_control.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/log.h"
#include "session/session.h"

namespace rescuesim {

using namespace control;

namespace {

const char* state_name(RunState s) {
  switch (s) {
    case RunState::stopped: return "STOPPED";
    case RunState::playing: return "PLAYING";
    case RunState::paused: return "PAUSED";
    case RunState::quitting: return "QUITTING";
    case RunState::no_world: return "NO_WORLD";
    case RunState::loading_world: return "LOADING_WORLD";
  }
  return "unknown";
}

ParameterValue make_bool(bool b) {
  ParameterValue v;
  v.type = ParameterValue::kBool;
  v.bool_value = b;
  return v;
}
ParameterValue make_int(std::int64_t i) {
  ParameterValue v;
  v.type = ParameterValue::kInteger;
  v.integer_value = i;
  return v;
}
ParameterValue make_double(double d) {
  ParameterValue v;
  v.type = ParameterValue::kDouble;
  v.double_value = d;
  return v;
}
ParameterValue make_string(std::string s) {
  ParameterValue v;
  v.type = ParameterValue::kString;
  v.string_value = std::move(s);
  return v;
}

const char* type_name(std::uint8_t t) {
  static const char* names[] = {"not set", "bool", "integer", "double", "string", "byte array", "bool array",
                                "integer array", "double array", "string array"};
  return t < 10 ? names[t] : "unknown type";
}

constexpr double kMaxRate = 1000;  ///< the fastest realtime pace a parameter may ask for

}  // namespace

RunControl::RunControl(Session& session, RunControlOptions options) : session_(session), options_(std::move(options)) {
  realtime_ = session_.scenario().realtime;
  rate_ = session_.scenario().rate;
  state_ = options_.start_paused ? RunState::paused : RunState::playing;
  rebuild_entities();
}

void RunControl::rebuild_entities() {
  entities_.clear();
  const World& w = session_.sim().world();
  std::set<std::string> taken;
  const auto add = [&](Entity::Kind kind, std::size_t i, const std::string& name) {
    // names are the handles of the standard: each is listed once (a later namesake is left out)
    if (name.empty() || !taken.insert(name).second) return;
    entities_.push_back({kind, i, name});
  };
  for (std::size_t i = 0; i < w.robots.size(); ++i) add(Entity::Kind::robot, i, w.robots[i].name);
  for (std::size_t i = 0; i < w.victims.size(); ++i) add(Entity::Kind::victim, i, w.victims[i].name);
  for (std::size_t i = 0; i < w.dynamics.size(); ++i) add(Entity::Kind::rubble, i, w.dynamics[i].name);
  for (std::size_t i = 0; i < w.statics.size(); ++i) {
    const StaticObject& s = w.statics[i];
    if (s.victim.valid() || s.kind == ObjectKind::floor) continue;  // a victim's parts belong to the victim
    add(Entity::Kind::fixed, i, s.name);
  }
}

RunControl::~RunControl() { close(); }

void RunControl::arm() {
  if (!start_) start_ = std::make_unique<SessionSnapshot>(session_.snapshot());
}

bool RunControl::post(std::function<void(SimControl&)> task) {
  {
    std::lock_guard lock(mutex_);
    if (closed_ || tasks_.size() >= kMaxPosted) return false;
    tasks_.push_back(std::move(task));
  }
  posted_.notify_one();
  return true;
}

void RunControl::run_tasks() {
  for (;;) {
    std::function<void(SimControl&)> task;
    {
      std::lock_guard lock(mutex_);
      if (tasks_.empty()) return;
      task = std::move(tasks_.front());
      tasks_.pop_front();
    }
    try {
      task(*this);
    } catch (const std::exception& e) {
      // a front end's closure failing must not end the run
      log::warn("a control request failed: {}", e.what());
    }
    ++tasks_run_;
  }
}

bool RunControl::before_step(const std::atomic<bool>* stop) {
  arm();
  for (;;) {
    run_tasks();
    if (state_ == RunState::quitting) return false;
    if (stop && stop->load(std::memory_order_relaxed)) return false;
    if (state_ == RunState::playing) return true;
    if (job_ && job_->completed < job_->job.steps) return true;
    // paused or stopped with nothing to step: wait for a request (and look at `stop` now and then)
    std::unique_lock lock(mutex_);
    posted_.wait_for(lock, std::chrono::milliseconds(50), [&] { return !tasks_.empty(); });
  }
}

void RunControl::after_step() {
  if (!job_) return;
  Job& j = *job_;
  ++j.completed;
  const std::uint64_t remaining = j.job.steps - j.completed;
  if (j.job.feedback && j.job.feedback_every > 0 && (j.completed % j.job.feedback_every == 0 || remaining == 0)) {
    j.job.feedback(j.completed, remaining);
  }
  if (remaining == 0) end_job(Result::ok());
}

void RunControl::end_job(const Result& result) {
  if (!job_) return;
  Job j = std::move(*job_);
  job_.reset();
  ++pacing_epoch_;
  if (j.job.done) j.job.done(result, j.completed);
}

void RunControl::close() {
  end_job(Result::fail(code::kOperationFailed, "the run ended before the steps were taken"));
  run_tasks();
  std::lock_guard lock(mutex_);
  closed_ = true;
  tasks_.clear();
}

SimulatorFeatures RunControl::features() const {
  SimulatorFeatures f;
  f.features = {feature::kEntityCategories,       feature::kEntityBounds,           feature::kEntityBoundsBox,
                feature::kEntityStateGetting,     feature::kEntityStateSetting,     feature::kEntityInfoGetting,
                feature::kNamedPoses,             feature::kSimulationReset,        feature::kSimulationResetTime,
                feature::kSimulationResetState,   feature::kSimulationStateGetting, feature::kSimulationStateSetting,
                feature::kSimulationStatePause,   feature::kStepSimulationSingle,   feature::kStepSimulationMultiple,
                feature::kStepSimulationAction,   feature::kWorldInfoGetting,       feature::kAvailableWorlds,
                feature::kSpawning,               feature::kDeleting,               feature::kSpawningResourceString,
                feature::kSpawnables,             feature::kSimulationResetSpawned};
  // URDF and SDF robots, and rescuesim's own: a scenario's robot entry in YAML (docs/ros.md, "Spawning")
  f.spawn_formats = {"urdf", "sdf", "yaml"};
  f.custom_info =
      "rescuesim: resets restore the start snapshot bitwise (the state hash after a reset equals the hash at the "
      "start); steps from PAUSED are the lockstep steps; entity names are robots, victims (HUMAN), rubble "
      "(DYNAMIC_OBJECT) and walls/obstacles (STATIC_OBJECT); bounds filters: sphere and box";
  return f;
}

Result RunControl::set_run_state(RunState target) {
  if (target == state_) return Result::fail(code::kAlreadyInTargetState, std::string("the simulation is already ") + state_name(state_));
  switch (target) {
    case RunState::playing:
    case RunState::paused:
      if (job_) end_job(Result::fail(code::kOperationFailed, std::string("cancelled: the simulation was set ") + state_name(target)));
      state_ = target;
      ++pacing_epoch_;
      return Result::ok();
    case RunState::stopped: {
      // STOPPED is PAUSED and reset to the start (the standard's words)
      if (job_) end_job(Result::fail(code::kOperationFailed, "cancelled: the simulation was stopped"));
      restore_start();
      state_ = RunState::stopped;
      return Result::ok();
    }
    case RunState::quitting:
      if (job_) end_job(Result::fail(code::kOperationFailed, "cancelled: the simulation is quitting"));
      state_ = RunState::quitting;
      return Result::ok();
    case RunState::no_world:
    case RunState::loading_world:
      break;
  }
  return Result::fail(code::kIncorrectTransition,
                      std::string(state_name(target)) + " cannot be asked for: worlds are not loaded or unloaded while a run goes on");
}

Result RunControl::start_steps(StepJob job, bool action) {
  const std::uint8_t refused = action ? code::kIncorrectState : code::kOperationFailed;
  if (state_ != RunState::paused && state_ != RunState::stopped) {
    return Result::fail(refused, std::string("steps are taken only while PAUSED; the simulation is ") + state_name(state_));
  }
  if (job_)
    return Result::fail(refused,
                        "another stepping request is in progress (" + std::to_string(job_->job.steps - job_->completed) + " steps left)");
  if (job.steps == 0) {
    if (job.done) job.done(Result::ok(), 0);
    return Result::ok();
  }
  // stepping from STOPPED leaves it: the run is then PAUSED where the steps left it
  state_ = RunState::paused;
  job_ = Job{std::move(job), 0};
  return Result::ok();
}

bool RunControl::cancel_steps() {
  if (!job_) return false;
  end_job(Result::fail(code::kOperationFailed, "cancelled after " + std::to_string(job_->completed) + " of " +
                                                   std::to_string(job_->job.steps) + " steps"));
  return true;
}

void RunControl::restore_start() {
  arm();
  session_.restore(*start_);
  ++pacing_epoch_;
}

Result RunControl::reset(std::uint8_t scope_bits) {
  if (job_) end_job(Result::fail(code::kOperationFailed, "cancelled: the simulation was reset"));
  const bool all = scope_bits == scope::kDefault || scope_bits == scope::kAll;
  const bool time = all || (scope_bits & scope::kTime);
  const bool state = all || (scope_bits & scope::kState);
  const bool spawned = all || (scope_bits & scope::kSpawned);
  if ((scope_bits & ~(scope::kTime | scope::kState | scope::kSpawned)) != 0 && !all) {
    return Result::fail(code::kFeatureUnsupported, "unknown reset scope bits " + std::to_string(scope_bits));
  }
  arm();
  Simulation& sim = session_.sim();
  // what was spawned goes first (the start had none of it); unless SPAWNED is in the scope it
  // comes back after the reset: at its spawn pose when STATE is, else where it is now
  const State now = sim.state();
  const std::size_t base_robots = sim.base_robots(), base_bodies = sim.base_bodies();
  std::vector<RobotInstance> robots(sim.world().robots.begin() + static_cast<long>(base_robots), sim.world().robots.end());
  std::vector<DynamicObject> bodies(sim.world().dynamics.begin() + static_cast<long>(base_bodies), sim.world().dynamics.end());
  sim.remove_spawned();
  if (time && state) {
    restore_start();
  } else if (state) {
    // STATE: every body back where it started; the clock, the schedules and the sensors go on
    State s = sim.state();
    s.robots = start_->state.robots;
    s.dynamics = start_->state.dynamics;
    s.victims = start_->state.victims;
    sim.restore(s);
  } else if (time) {
    // TIME: the clock and everything timed back to the start, the bodies where they are now
    session_.restore(*start_);
    State s = sim.state();
    std::copy(now.robots.begin(), now.robots.begin() + static_cast<long>(base_robots), s.robots.begin());
    std::copy(now.dynamics.begin(), now.dynamics.begin() + static_cast<long>(base_bodies), s.dynamics.begin());
    sim.restore(s);
  }
  if (!spawned && (!robots.empty() || !bodies.empty())) {
    for (RobotInstance& r : robots) sim.add_robot(std::move(r));
    for (DynamicObject& b : bodies) sim.add_body(std::move(b));
    if (!state) {
      State s = sim.state();
      std::copy(now.robots.begin() + static_cast<long>(base_robots), now.robots.end(), s.robots.begin() + static_cast<long>(base_robots));
      std::copy(now.dynamics.begin() + static_cast<long>(base_bodies), now.dynamics.end(),
                s.dynamics.begin() + static_cast<long>(base_bodies));
      sim.restore(s);
    }
  }
  rebuild_entities();
  if (time && state && state_ == RunState::stopped) state_ = RunState::paused;
  ++pacing_epoch_;
  return Result::ok();
}

Result RunControl::available_worlds(const std::vector<std::string>& sources, std::vector<WorldResource>& out) const {
  out.clear();
  std::vector<std::filesystem::path> dirs = options_.world_dirs;
  for (const std::string& s : sources) {
    std::string p = s.starts_with("file://") ? s.substr(7) : s;
    if (!std::filesystem::is_directory(p)) return Result::fail(code::kOperationFailed, "'" + s + "' is no folder");
    dirs.emplace_back(p);
  }
  for (const auto& d : dirs) {
    std::error_code ec;
    std::vector<std::filesystem::path> files;
    for (const auto& f : std::filesystem::directory_iterator(d, ec)) {
      if (f.path().extension() == ".yaml") files.push_back(f.path());
    }
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      WorldResource r;
      r.name = f.stem().string();
      r.uri = "file://" + std::filesystem::absolute(f).lexically_normal().string();
      r.description = "scenario " + f.filename().string();
      r.tags = {"scenario"};
      out.push_back(std::move(r));
    }
  }
  return Result::ok();
}

Result RunControl::current_world(WorldResource& out) const {
  const Scenario& sc = session_.scenario();
  out = WorldResource{};
  out.name = sc.name;
  if (!sc.source_file.empty() && sc.source_file != "<built-in>") {
    out.uri = "file://" + std::filesystem::absolute(sc.source_file).lexically_normal().string();
  }
  out.description = "scenario '" + sc.name + "', world '" + session_.sim().world().name + "', seed " + std::to_string(sc.seed);
  return Result::ok();
}

Result RunControl::load_world(const WorldResource& world, WorldResource&) {
  return Result::fail(code::kFeatureUnsupported, "loading a world while a run goes on is not supported: start `rescuesim run " +
                                                     (world.uri.empty() ? world.name : world.uri) + "` instead");
}

Result RunControl::unload_world() {
  return Result::fail(code::kFeatureUnsupported, "unloading the world is not supported: end the run (SetSimulationState QUITTING)");
}

std::vector<ParameterDescriptor> RunControl::parameter_descriptors() const {
  return {
      {"duration", ParameterValue::kDouble, "sim seconds the run lasts (the scenario's duration)", true, {}},
      {"real_time_factor", ParameterValue::kDouble, "realtime pace: sim seconds per wall second (with realtime true)", false,
       std::pair{1e-3, kMaxRate}},
      {"realtime", ParameterValue::kBool, "paced to the wall clock (true) or as fast as possible, lockstep (false)", false, {}},
      {"scenario", ParameterValue::kString, "the scenario's name (its output folder runs/<name>)", true, {}},
      {"scenario_file", ParameterValue::kString, "the scenario file the run was started from", true, {}},
      {"seed", ParameterValue::kInteger, "the run's seed (noise streams, generated mazes)", true, {}},
      {"step_size", ParameterValue::kDouble, "the physics step (s)", true, {}},
      {"use_sim_time", ParameterValue::kBool, "rescuesim is the clock: every stamp is sim time, published on /clock", true, {}},
      {"world", ParameterValue::kString, "the compiled world's name", true, {}},
  };
}

ParameterValue RunControl::parameter(const std::string& name) const {
  const Scenario& sc = session_.scenario();
  if (name == "duration") return make_double(sc.duration);
  if (name == "real_time_factor") return make_double(rate_);
  if (name == "realtime") return make_bool(realtime_);
  if (name == "scenario") return make_string(sc.name);
  if (name == "scenario_file") return make_string(sc.source_file);
  if (name == "seed") return make_int(static_cast<std::int64_t>(sc.seed));
  if (name == "step_size") return make_double(session_.sim().dt());
  if (name == "use_sim_time") return make_bool(true);
  if (name == "world") return make_string(session_.sim().world().name);
  return {};
}

SetParameterResult RunControl::set_parameter(const Parameter& p) {
  const auto descriptors = parameter_descriptors();
  const auto d = std::find_if(descriptors.begin(), descriptors.end(), [&](const ParameterDescriptor& x) { return x.name == p.name; });
  if (d == descriptors.end()) return {false, "parameter '" + p.name + "' is not declared by /rescuesim"};
  if (d->read_only) return {false, "parameter '" + p.name + "' is read-only: " + d->description};
  if (p.value.type != d->type) {
    return {false, "parameter '" + p.name + "' is a " + type_name(d->type) + "; got a " + type_name(p.value.type)};
  }
  if (p.name == "realtime") {
    realtime_ = p.value.bool_value;
  } else if (p.name == "real_time_factor") {
    const double r = p.value.double_value;
    if (!(r >= d->range->first && r <= d->range->second)) {
      return {false, "parameter 'real_time_factor' must be within [" + std::to_string(d->range->first) + ", " +
                         std::to_string(d->range->second) + "]; got " + std::to_string(r)};
    }
    rate_ = r;
  }
  ++pacing_epoch_;
  return {true, ""};
}

std::uint64_t RunControl::state_hash() const { return rescuesim::state_hash(session_.sim().state()); }
std::int64_t RunControl::time_ns() const { return session_.sim().time().ns; }
std::int64_t RunControl::steps_taken() const { return session_.sim().state().step; }

}  // namespace rescuesim
