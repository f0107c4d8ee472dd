#include "session/session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include "core/log.h"
#include "core/memory.h"
#include "sensors/camera/render_camera_service.h"
#include "session/realtime_pacer.h"
#include "session/sync_gate.h"

namespace rescuesim {

Session::Session(const Scenario& scenario, const ModelMap& models, SessionOptions options)
    : scenario_(scenario), options_(std::move(options)) {
  if (!(options_.trajectory_rate > 0)) throw Error("SessionOptions::trajectory_rate must be > 0 Hz");
  spec_ = build_world(scenario_, &diagnostics_);
  Diagnostics problems = validate(spec_);
  diagnostics_.append(problems);
  if (diagnostics_.has_errors()) diagnostics_.throw_if_errors();
  for (const auto& c : scenario_.robots) diagnostics_.append(c.diagnostics);
  World world = compile_scenario(scenario_, spec_, models);
  bool any_camera = false;
  for (auto& robot : world.robots) {
    for (auto& sensor : robot.spec.sensors) {
      const bool camera = sensor.is_camera();
      if (camera && !options_.cameras) sensor.enabled = false;
      any_camera = any_camera || (camera && sensor.enabled);
    }
  }
  SimOptions sim_options = options_.sim;
  sim_options.seed = scenario_.seed;
  sim_options.physics.dt = scenario_.physics_dt;
  sim_options.physics.solver_iterations = scenario_.solver_iterations;
  sim_options.physics.groups = scenario_.physics_groups;
  sim_ = std::make_unique<Simulation>(std::move(world), sim_options);
  if (any_camera) {
    const std::string& quality = scenario_.render_quality;
    camera_options_.quality = quality == "high" ? Quality::high : quality == "medium" ? Quality::medium : Quality::low;
    camera_options_.latency = scenario_.render_latency;
    try {
      cameras_ = std::make_unique<RenderCameraService>(sim_->world(), camera_options_);
    } catch (const Error& e) {
      throw Error({scenario_.source_file, 0, "camera sensors"},
                  std::string(e.what()) + "\n(the cameras need OpenGL 4.5 through EGL; run without them with --no-cameras)");
    }
    sim_->set_camera_service(cameras_.get());
    sim_->set_world_changed([this] { rebuild_cameras(); });
  }
  // victim detection, picked once: in the thermal images when cameras render and a robot has
  // a thermal camera, else by line of sight (the Simulation's default)
  if (cameras_ && thermal_images_render()) {
    std::vector<bool> rendered(sim_->world().robots.size());
    for (std::size_t r = 0; r < rendered.size(); ++r) rendered[r] = cameras_->detects_victims(RobotIndex::at(r));
    sim_->set_victim_detector(std::make_unique<ThermalImageDetector>(rendered));
  }
  if (scenario_.mission) {
    try {
      mission_ = std::make_unique<Mission>(*scenario_.mission, *sim_);
      mission_->enable_map_scoring(spec_);
    } catch (const Error& e) {
      throw Error({scenario_.source_file, 0, "mission"}, e.what());
    }
  }
  // the run's systems, in step order (sim/run_system.h): the built-in controllers command what
  // they heard during the step; the recorder samples; the mission moves its radios and judges;
  // the built-in team reports, relays and talks through it
  recorder_ = std::make_unique<Recorder>(*sim_, spec_, options_.trajectory_rate, options_.trajectory_max_points);
  controllers_ = std::make_unique<BuiltinControllers>(sim_->world().robots.size());
  if (options_.controllers) attach_controllers(models);
  systems_ = {controllers_.get(), recorder_.get()};
  if (mission_) {
    mission_system_ = std::make_unique<MissionSystem>(*mission_);
    team_ = std::make_unique<BuiltinTeam>(*mission_, *controllers_, sim_->world().robots.size(), sim_->world().victims.size(),
                                          [this](RobotIndex robot) { return victim_picture(robot); });
    systems_.push_back(mission_system_.get());
    systems_.push_back(team_.get());
  }
  recorder_->record(*sim_);
  if (options_.control) {
    control_ = std::make_unique<RunControl>(*this, options_.control_options);
    sim_->set_control(control_.get());
  }
}

Session::~Session() {
  // the simulation holds a pointer to the camera service: detach it before either goes
  if (sim_) sim_->set_camera_service(nullptr);
  if (sim_) sim_->set_control(nullptr);
}

bool Session::thermal_images_render() const {
  // the scenario's robots (the camera service renders no spawned robot's cameras)
  for (std::size_t r = 0; r < sim_->base_robots(); ++r) {
    if (cameras_->detects_victims(RobotIndex::at(r))) return true;
  }
  return false;
}

void Session::rebuild_cameras() {
  // robots spawned or deleted: the renderer draws the world it was made with, so it is made
  // again (its frames in flight were published already, its last frames start afresh)
  const bool thermal = sim_->victim_detector().name() == "thermal images";
  sim_->set_camera_service(nullptr);
  cameras_.reset();
  cameras_ = std::make_unique<RenderCameraService>(sim_->world(), camera_options_);
  sim_->set_camera_service(cameras_.get());
  if (thermal) {
    std::vector<bool> rendered(sim_->world().robots.size());
    for (std::size_t r = 0; r < rendered.size(); ++r) rendered[r] = cameras_->detects_victims(RobotIndex::at(r));
    sim_->set_victim_detector(std::make_unique<ThermalImageDetector>(rendered));
  }
}

std::string Session::render_device() const { return cameras_ ? cameras_->device() : std::string(); }

double Session::coverage() const { return recorder_->coverage(); }

void Session::add_system(std::unique_ptr<RunSystem> system) {
  RS_DEMAND(system != nullptr, "Session::add_system: no system");
  systems_.push_back(system.get());
  added_systems_.push_back(std::move(system));
}

void Session::step_once() {
  for (RunSystem* system : systems_) system->pre_step(*sim_);
  sim_->step();
  for (RunSystem* system : systems_) system->post_step(*sim_);
}

bool Session::step_until(SimTime t) {
  while (sim_->time() < t) {
    step_once();
    if (sim_->in_trouble()) return false;
  }
  return true;
}

RunResult Session::result() const {
  const State& s = sim_->state();
  RunResult r;
  r.scenario = scenario_.name;
  r.seed = scenario_.seed;
  r.sim_time = s.time.seconds();
  r.wall_time = wall_time_;
  r.real_time_factor = wall_time_ > 0 ? r.sim_time / wall_time_ : 0;
  r.stop_reason = stop_reason_;
  r.trouble = sim_->in_trouble();
  for (std::size_t v = 0; v < s.victims.size(); ++v) {
    VictimResult vr;
    vr.name = sim_->world().victims[v].name;
    vr.found = s.victims[v].first_seen.ns >= 0;
    vr.time = vr.found ? s.victims[v].first_seen.seconds() : -1;
    vr.by = s.victims[v].seen_by;
    r.victims_found += vr.found;
    r.victims.push_back(vr);
  }
  r.victim_detection = std::string(sim_->victim_detector().name());
  r.coverage = coverage();
  for (std::size_t k = 0; k < controllers_->size(); ++k) {
    if (const autonomy::Explorer* ex = controllers_->explorer(k)) r.explorers.emplace_back(sim_->world().robots[k].name, ex->stats());
  }
  for (const auto& rs : s.robots) {
    r.collisions += rs.collisions;
    r.distance += rs.distance;
  }
  for (const auto& t : sim_->bus().topics()) r.message_counts.emplace_back(t.name, sim_->bus().count(t.id));
  r.state_hash = state_hash(s);
  if (mission_) r.mission = mission_->result();
  return r;
}

RunResult Session::run(const std::atomic<bool>* stop, const std::function<void(const RunResult&)>& progress) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const double wall_before = wall_time_;
  // an infinite duration runs until `stop` (rescuesim run --ros1 without --duration)
  const SimTime end = std::isfinite(scenario_.duration) ? SimTime::from_seconds(scenario_.duration)
                                                        : SimTime{std::numeric_limits<std::int64_t>::max()};
  auto last_report = t0;
  stop_reason_ = "duration";
  const auto all_found = [&] {
    // with a mission, found means reported and accepted by the referee
    if (mission_)
      return mission_->referee().victim_count() > 0 && mission_->referee().victims_found() == mission_->referee().victim_count();
    for (const auto& v : sim_->state().victims) {
      if (v.first_seen.ns < 0) return false;
    }
    return !sim_->state().victims.empty();
  };
  // synchronous with an outside controller: each scan waits for the command that answers it
  std::optional<SyncGate> sync;
  if (options_.sync_timeout > 0) sync.emplace(*sim_, options_.sync_timeout);
  // long runs give freed memory back now and then (threads' malloc arenas keep it otherwise)
  const SimTime trim_every = SimTime::from_seconds(options_.return_memory_every > 0 ? options_.return_memory_every : 0);
  SimTime next_trim = sim_->time() + trim_every;
  // realtime: the one pacing rule (session/realtime_pacer.h), which starts afresh whenever the
  // control surface says so (after a pause, a reset, a new rate) and drops lag beyond max_lag
  RealtimePacer pacer;
  std::uint64_t pace_epoch = control_ ? control_->pacing_epoch() : 0;
  const auto wall_now = [&] { return std::chrono::duration<double>(clock::now() - t0).count(); };
  while (sim_->time() < end) {
    if (trim_every.ns > 0 && sim_->time() >= next_trim) {
      return_free_memory();
      next_trim = sim_->time() + trim_every;
    }
    if (stop && stop->load(std::memory_order_relaxed)) {
      stop_reason_ = "interrupted";
      break;
    }
    // the control surface: requests run here, between steps; while paused this waits
    bool stepping_job = false;
    if (control_) {
      if (!control_->before_step(stop)) {
        stop_reason_ = control_->run_state() == control::RunState::quitting ? "quit by request" : "interrupted";
        break;
      }
      stepping_job = control_->run_state() != control::RunState::playing;
      if (control_->pacing_epoch() != pace_epoch || stepping_job) {
        pace_epoch = control_->pacing_epoch();
        pacer.restart();
      }
    }
    const bool realtime = control_ ? control_->realtime() : scenario_.realtime;
    // (anchors the pacer at the time before this step; steps asked for while paused are taken
    // at once, as lockstep steps)
    if (realtime && !stepping_job) pacer.target(wall_now(), sim_->time(), control_ ? control_->rate() : scenario_.rate, false);
    if (sync) sync->wait();
    step_once();
    if (control_) control_->after_step();
    if (sim_->in_trouble()) {
      stop_reason_ = sim_->state().trouble.first;
      log::warn("run stopped: {}", stop_reason_);
      break;
    }
    if (scenario_.stop_when_all_found && all_found()) {
      stop_reason_ = "all victims found";
      break;
    }
    // realtime: wait for the wall clock to reach the sim time just stepped to; a run that falls
    // behind owes at most the pacer's max_lag and then goes on at its own speed
    if (realtime && !stepping_job) {
      const double due = pacer.wall_due(sim_->time()), now = wall_now();
      if (due > now) std::this_thread::sleep_for(std::chrono::duration<double>(due - now));
    }
    if (progress && (sim_->state().step & 63) == 0) {
      const auto now = clock::now();
      if (now - last_report > std::chrono::milliseconds(100)) {
        last_report = now;
        wall_time_ = wall_before + std::chrono::duration<double>(now - t0).count();
        progress(result());
      }
    }
  }
  if (control_) control_->close();
  if (sync) {
    sync_timeouts_ += sync->timeouts();
    if (sync->timeouts() > 1) log::warn("sync: {} scans in all got no cmd_vel in time", sync->timeouts());
    sync.reset();
  }
  // frames still being rendered belong to this run
  sim_->flush_cameras();
  wall_time_ = wall_before + std::chrono::duration<double>(clock::now() - t0).count();
  return result();
}

}  // namespace rescuesim
