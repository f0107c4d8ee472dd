#pragma once
// A SimControl for the Foxglove services' tests, while the real one (session/run_control) is
// written apart: it records every call, runs posted tasks when the test's stepping thread asks
// (run_posted, between two Simulation steps), counts calls made from any other thread, and
// answers with values worked out by hand (the robot's state below, a state machine of
// PLAYING / PAUSED with the standard's result codes, stepping jobs advanced one step per
// stepped()).

#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bus/sim_control.h"

namespace rescuesim::testing {

class FakeControl final : public control::SimControl {
 public:
  /// The calling thread is the simulation thread: every method but post() must run on it.
  FakeControl() : owner_(std::this_thread::get_id()) {
    robot.stamp_ns = 2'500'000'000;  // 2.5 s
    robot.pose.p = Vec3(1.25, -0.5, 0.1);
    robot.pose.q = Quat(0.8, 0, 0, 0.6);  // w, x, y, z: a unit quaternion (0.36 + 0.64)
    robot.linear = Vec3(0.3, 0, 0);
    robot.angular = Vec3(0, 0, 0.5);
  }

  // ---- the test's side ----

  /// Runs the posted tasks in order (on the owner thread), unless fewer than `hold_until` wait.
  std::size_t run_posted() {
    std::deque<std::function<void(SimControl&)>> now;
    {
      std::lock_guard lock(mutex_);
      if (tasks_.size() < hold_until) return 0;
      now.swap(tasks_);
      hold_until = 0;
    }
    for (auto& t : now) t(*this);
    return now.size();
  }
  /// One step of the simulation has run: advances the stepping job, if any.
  void stepped() {
    note("");
    if (!job_) return;
    ++job_done_;
    ++steps_run;
    if (job_done_ == job_->steps) {
      control::StepJob job = std::move(*job_);
      job_.reset();
      job.done(control::Result::ok(), job_done_);
    }
  }
  /// Later posts are refused (the run has ended).
  void close() {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  std::size_t waiting() const {
    std::lock_guard lock(mutex_);
    return tasks_.size();
  }

  std::size_t hold_until = 0;        ///< run_posted() waits until this many tasks are posted (set before posting starts)
  mutable std::vector<std::string> calls;  ///< "set_run_state 2", "start_steps 5", ... in order
  mutable int foreign_thread_calls = 0;    ///< methods called off the owner thread (must stay 0)
  control::RunState state = control::RunState::playing;
  std::uint64_t steps_run = 0;
  control::EntityState robot;        ///< what entity_state("robot") answers
  control::EntityState last_set;     ///< what set_entity_state was given last

  // ---- SimControl ----

  bool post(std::function<void(SimControl&)> task) override {
    std::lock_guard lock(mutex_);
    if (closed_ || tasks_.size() >= kMaxPosted) return false;
    tasks_.push_back(std::move(task));
    return true;
  }
  control::SimulatorFeatures features() const override {
    note("features");
    namespace f = control::feature;
    return {{f::kSimulationReset, f::kSimulationStateGetting, f::kSimulationStateSetting, f::kSimulationStatePause,
             f::kStepSimulationSingle, f::kStepSimulationMultiple, f::kEntityStateGetting, f::kEntityStateSetting},
            {"urdf", "sdf"},
            "fake"};
  }
  control::RunState run_state() const override {
    note("run_state");
    return state;
  }
  control::Result set_run_state(control::RunState target) override {
    note("set_run_state " + std::to_string(static_cast<int>(target)));
    if (target == state) return control::Result::fail(control::code::kAlreadyInTargetState, "already in that state");
    state = target;
    return control::Result::ok();
  }
  control::Result start_steps(control::StepJob job, bool action) override {
    note("start_steps " + std::to_string(job.steps) + (action ? " action" : ""));
    if (state != control::RunState::paused) {
      return control::Result::fail(action ? control::code::kIncorrectState : control::code::kOperationFailed,
                                   "the simulation is not paused");
    }
    if (job_) return control::Result::fail(control::code::kOperationFailed, "stepping already");
    job_ = std::move(job);
    job_done_ = 0;
    return control::Result::ok();
  }
  bool cancel_steps() override {
    note("cancel_steps");
    return false;
  }
  control::Result reset(std::uint8_t scope) override {
    note("reset " + std::to_string(scope));
    return control::Result::ok();
  }
  control::Result entities(const control::EntityFilters& filters, std::vector<std::string>& names) const override {
    std::string cats;
    for (auto c : filters.categories) {
      cats += ' ';  // (not " " + to_string: GCC 12 warns falsely about that)
      cats += std::to_string(c);
    }
    note("entities '" + filters.filter + "'" + cats);
    names = {"robot"};
    return control::Result::ok();
  }
  control::Result entity_state(const std::string& name, control::EntityState& out) const override {
    note("entity_state " + name);
    if (name != "robot") return control::Result::fail(control::code::kNotFound, "no entity '" + name + "'");
    out = robot;
    return control::Result::ok();
  }
  control::Result set_entity_state(const std::string& name, const control::EntityState& s, bool set_pose, bool set_twist,
                                   bool set_acceleration) override {
    note("set_entity_state " + name + (set_pose ? " pose" : "") + (set_twist ? " twist" : "") + (set_acceleration ? " acceleration" : ""));
    last_set = s;
    return control::Result::ok();
  }
  control::Result entity_info(const std::string&, control::EntityInfo&) const override { return unsupported("entity_info"); }
  control::Result entity_bounds(const std::string&, control::Bounds&) const override { return unsupported("entity_bounds"); }
  control::Result named_poses(const control::TagsFilter&, std::vector<control::NamedPose>&) const override {
    return unsupported("named_poses");
  }
  control::Result named_pose_bounds(const std::string&, control::Bounds&) const override { return unsupported("named_pose_bounds"); }
  control::Result spawnables(const std::vector<std::string>&, std::vector<control::Spawnable>&) const override {
    return unsupported("spawnables");
  }
  /// Spawns nothing: records the request ("spawn <name> <uri> <frame_id> <x>") and names it <name>_1.
  control::Result spawn(const control::SpawnRequest& r, std::string& name) override {
    note("spawn " + r.name + " " + r.uri + " " + r.frame_id + " " + std::to_string(static_cast<int>(r.pose.p.x())));
    name = r.name + "_1";
    return control::Result::ok();
  }
  control::Result remove(const std::string& name) override {
    note("remove " + name);
    return control::Result::ok();
  }
  control::Result available_worlds(const std::vector<std::string>&, std::vector<control::WorldResource>&) const override {
    return unsupported("available_worlds");
  }
  control::Result current_world(control::WorldResource&) const override { return unsupported("current_world"); }
  control::Result load_world(const control::WorldResource&, control::WorldResource&) override { return unsupported("load_world"); }
  control::Result unload_world() override { return unsupported("unload_world"); }
  std::vector<control::ParameterDescriptor> parameter_descriptors() const override { return {}; }
  control::ParameterValue parameter(const std::string&) const override { return {}; }
  control::SetParameterResult set_parameter(const control::Parameter&) override { return {false, "fake"}; }
  std::uint64_t state_hash() const override { return 0; }
  std::int64_t time_ns() const override { return 0; }
  std::int64_t steps_taken() const override { return static_cast<std::int64_t>(steps_run); }

 private:
  /// Records a call (none for "") and whether it came from another thread.
  void note(const std::string& what) const {
    if (std::this_thread::get_id() != owner_) ++foreign_thread_calls;
    if (!what.empty()) calls.push_back(what);
  }
  control::Result unsupported(const char* what) const {
    note(what);
    return control::Result::fail(control::code::kFeatureUnsupported, std::string(what) + ": not in the fake");
  }

  std::thread::id owner_;
  mutable std::mutex mutex_;
  std::deque<std::function<void(SimControl&)>> tasks_;
  bool closed_ = false;
  std::optional<control::StepJob> job_;
  std::uint64_t job_done_ = 0;
};

}  // namespace rescuesim::testing
