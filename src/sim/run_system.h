#pragma once
/// RunSystem: one part of a run that acts around each Simulation step, as gz-sim composes a run
/// from systems with PreUpdate / Update / PostUpdate. A run (session/session.h) lists its systems
/// in order: the built-in controllers, the recorder, the mission, the built-in team. Each step is
///
///   every system's pre_step    in list order  (commands for this step)
///   Simulation::step           PreStep, Physics, PostStep (simulation.h)
///   every system's post_step   in list order  (what the step published and its State)
///
/// A system owns its memory. save() returns a copy of it (copyable, opaque to the run) and
/// load() puts one back, so a run's snapshot is the State plus each system's saved memory, and
/// restoring it and stepping on gives bitwise the same messages. load() is called after the
/// Simulation has been restored and its queued commands dropped, so a system that queued
/// commands for the next step queues them again there.
///
/// Systems run on the stepping thread, between steps; they may command the simulation (queued
/// commands, applied at the next step) and read its State and Bus. When the run ends, each
/// writes its outputs (write_outputs, in list order).

#include <any>
#include <string_view>

namespace rescuesim {

class Simulation;
struct RunOutputs;

class RunSystem {
 public:
  virtual ~RunSystem() = default;
  /// A short name for logs and snapshots ("controllers", "recorder", "mission", "team").
  virtual std::string_view system_name() const = 0;
  /// Before Simulation::step.
  virtual void pre_step(Simulation& /*sim*/) {}
  /// After Simulation::step.
  virtual void post_step(Simulation& /*sim*/) {}
  /// A copy of the system's memory (empty: it keeps none).
  virtual std::any save() const { return {}; }
  /// Puts back what save() returned (from this system).
  virtual void load(const std::any& /*memory*/, Simulation& /*sim*/) {}
  /// When the run ends: writes the system's files and draws its layer of the overview
  /// (sim/run_outputs.h says who writes what). A system that writes nothing keeps this.
  virtual void write_outputs(const Simulation& /*sim*/, RunOutputs& /*out*/) const {}
};

}  // namespace rescuesim
