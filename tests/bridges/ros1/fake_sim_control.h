#pragma once
// Test support for the ROS 1 simulation services: a SimControl that records the calls it gets
// and runs posted tasks when the test's "simulation thread" calls tick(), stepping a real
// Simulation while PLAYING or while a stepping job has steps left. Only pause, play, stepping
// and reset are real; everything else answers FEATURE_UNSUPPORTED. (The run's own SimControl is
// session/run_control.h; this one only has to be simple enough to be right by inspection.)

#include <atomic>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "bus/sim_control.h"
#include "sim/simulation.h"

namespace rescuesim::testing {

class FakeSimControl final : public control::SimControl {
 public:
  using Result = control::Result;

  /// Starts PLAYING; reset() goes back to the state `sim` is in now.
  explicit FakeSimControl(Simulation& sim) : sim_(sim), start_(sim.snapshot()) { publish_time(); }

  bool post(std::function<void(SimControl&)> task) override {
    std::lock_guard lock(mutex_);
    if (closed_ || tasks_.size() >= kMaxPosted) return false;
    tasks_.push_back(std::move(task));
    return true;
  }
  /// post() refuses from now on (a run that has ended).
  void close() {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }

  /// The test's simulation thread, once: runs the posted tasks, then takes a step when PLAYING
  /// or when a stepping job has steps left (reporting its end).
  void tick() {
    std::deque<std::function<void(SimControl&)>> tasks;
    {
      std::lock_guard lock(mutex_);
      tasks.swap(tasks_);
    }
    for (auto& t : tasks) t(*this);
    if (state_ != control::RunState::playing && !job_) return;
    sim_.step();
    ++steps_;
    publish_time();
    if (job_ && ++job_completed_ == job_->steps) {
      control::StepJob job = std::move(*job_);
      job_.reset();
      if (job.done) job.done(Result::ok(), job.steps);
    }
  }

  /// The calls so far ("set_run_state(2)", "start_steps(1, service)", "reset(255)"), in order.
  std::vector<std::string> calls() const {
    std::lock_guard lock(mutex_);
    return calls_;
  }
  /// The simulation's time and steps as of the last tick (readable from any thread).
  std::int64_t now_ns() const { return now_ns_.load(); }
  std::int64_t steps() const { return steps_.load(); }
  control::RunState state() const { return state_.load(); }

  control::SimulatorFeatures features() const override { return {}; }
  control::RunState run_state() const override { return state_; }
  Result set_run_state(control::RunState target) override {
    record("set_run_state(" + std::to_string(static_cast<int>(target)) + ")");
    if (target == state_) return Result::fail(control::code::kAlreadyInTargetState, "already in that state");
    if (target != control::RunState::playing && target != control::RunState::paused) {
      return Result::fail(control::code::kIncorrectTransition, "the fake only pauses and plays");
    }
    state_ = target;
    return Result::ok();
  }
  Result start_steps(control::StepJob job, bool action) override {
    record("start_steps(" + std::to_string(job.steps) + (action ? ", action)" : ", service)"));
    if (state_ != control::RunState::paused) {
      return Result::fail(action ? control::code::kIncorrectState : control::code::kOperationFailed,
                          "steps are taken only while the simulation is paused");
    }
    if (job_) return Result::fail(control::code::kOperationFailed, "another stepping job is in progress");
    job_ = std::move(job);
    job_completed_ = 0;
    return Result::ok();
  }
  bool cancel_steps() override { return false; }
  Result reset(std::uint8_t scope) override {
    record("reset(" + std::to_string(scope) + ")");
    sim_.restore(start_);
    publish_time();
    return Result::ok();
  }

  Result entities(const control::EntityFilters&, std::vector<std::string>&) const override { return unsupported(); }
  Result entity_state(const std::string&, control::EntityState&) const override { return unsupported(); }
  Result set_entity_state(const std::string&, const control::EntityState&, bool, bool, bool) override { return unsupported(); }
  Result entity_info(const std::string&, control::EntityInfo&) const override { return unsupported(); }
  Result entity_bounds(const std::string&, control::Bounds&) const override { return unsupported(); }
  Result named_poses(const control::TagsFilter&, std::vector<control::NamedPose>&) const override { return unsupported(); }
  Result named_pose_bounds(const std::string&, control::Bounds&) const override { return unsupported(); }
  Result spawnables(const std::vector<std::string>&, std::vector<control::Spawnable>&) const override { return unsupported(); }
  Result spawn(const control::SpawnRequest&, std::string&) override { return unsupported(); }
  Result remove(const std::string&) override { return unsupported(); }
  Result available_worlds(const std::vector<std::string>&, std::vector<control::WorldResource>&) const override { return unsupported(); }
  Result current_world(control::WorldResource&) const override { return unsupported(); }
  Result load_world(const control::WorldResource&, control::WorldResource&) override { return unsupported(); }
  Result unload_world() override { return unsupported(); }
  std::vector<control::ParameterDescriptor> parameter_descriptors() const override { return {}; }
  control::ParameterValue parameter(const std::string&) const override { return {}; }
  control::SetParameterResult set_parameter(const control::Parameter&) override { return {false, "the fake has no parameters"}; }
  std::uint64_t state_hash() const override { return 0; }
  std::int64_t time_ns() const override { return sim_.time().ns; }
  std::int64_t steps_taken() const override { return steps_; }

 private:
  static Result unsupported() { return Result::fail(control::code::kFeatureUnsupported, "not in the fake"); }
  void record(std::string call) {
    std::lock_guard lock(mutex_);
    calls_.push_back(std::move(call));
  }
  void publish_time() { now_ns_ = sim_.time().ns; }

  Simulation& sim_;
  State start_;
  mutable std::mutex mutex_;
  std::deque<std::function<void(SimControl&)>> tasks_;
  bool closed_ = false;
  std::vector<std::string> calls_;
  std::atomic<control::RunState> state_{control::RunState::playing};
  std::optional<control::StepJob> job_;  ///< simulation thread only
  std::uint64_t job_completed_ = 0;
  std::atomic<std::int64_t> now_ns_{0}, steps_{0};
};

}  // namespace rescuesim::testing
