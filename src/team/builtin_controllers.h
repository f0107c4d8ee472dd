#pragma once
/// The built-in controllers of a run, a RunSystem (sim/run_system.h): an autonomy::Explorer for
/// each robot that asked for one, fed from the Bus. During a step each explorer's odometry,
/// joint states and scans wait in its inbox; after the step (post_step) the explorers hear them
/// on the worker threads (they share nothing) and what they ask for (cmd_vel, the victim
/// camera's swing) is commanded in robot order, for the next step. Their memory (the explorers
/// and the commands they queued, which the Simulation's command queue does not keep in State)
/// is saved and loaded with a run's snapshots.
///
/// Which robot gets which explorer is the session's choice (session/session_setup.cpp).

#include <any>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "autonomy/explorer.h"
#include "core/index.h"
#include "core/pose.h"
#include "msgs/messages.h"
#include "sim/run_system.h"

namespace rescuesim {

class BuiltinControllers final : public RunSystem {
 public:
  /// How an explorer's camera swing is commanded (ExplorerLookConfig::yaw_joint).
  struct Pan {
    msg::JointState joint;     ///< the yaw joint alone, when it is not a head joint
    std::vector<double> head;  ///< every head joint's target, when it is one (the others at their start)
    int in_head = -1;          ///< its index among the head joints, or -1
  };

  /// Room for `robots` robots (the scenario's), none with an explorer yet.
  explicit BuiltinControllers(std::size_t robots);

  /// Gives robot `robot` its explorer: its odom frame lies at X_WO in the world (its start
  /// pose), it hears `topics` (full names; odometry, joint states, the laser, in that order of
  /// subscription) and swings its camera through `pan` (unused when its look config names no joint).
  void attach(Simulation& sim, RobotIndex robot, std::unique_ptr<autonomy::Explorer> explorer, const Pose2& X_WO, Pan pan,
              const std::vector<std::string>& topics);

  std::size_t size() const { return robots_.size(); }
  /// Robot r's explorer, or null when it has none (driven from outside).
  autonomy::Explorer* explorer(std::size_t r) { return robots_[r].explorer.get(); }
  const autonomy::Explorer* explorer(std::size_t r) const { return robots_[r].explorer.get(); }
  /// Where robot r's odom frame (and its explorer's map frame) lies in the world: its start pose.
  const Pose2& X_WO(std::size_t r) const { return robots_[r].X_WO; }
  /// True when any robot has an explorer.
  bool any() const;

  std::string_view system_name() const override { return "controllers"; }
  /// Forgets the commands queued during the last step (those were applied by this one).
  void pre_step(Simulation& sim) override;
  /// The explorers hear the step's messages and their commands are queued for the next step.
  void post_step(Simulation& sim) override;
  std::any save() const override;
  /// The explorers' memory goes back (the objects stay: the Bus feeds them by index) and the
  /// commands they had queued at the snapshot are queued again.
  void load(const std::any& memory, Simulation& sim) override;
  /// Draws each explorer's map (cells at least 65% occupied) on the overview, its map frame
  /// placed at the robot's odom frame.
  void write_outputs(const Simulation& sim, RunOutputs& out) const override;

 private:
  struct Robot {
    std::unique_ptr<autonomy::Explorer> explorer;  // null when none
    std::vector<msg::Message> inbox;               // heard during the step being taken
    Pose2 X_WO;
    Pan pan;
    std::optional<msg::Twist> queued;   // cmd_vel queued during the last step
    std::optional<double> queued_look;  // camera yaw queued during the last step
  };
  struct Memory;
  void command_look(Simulation& sim, std::size_t robot, double yaw);

  std::vector<Robot> robots_;  // never resized after construction: subscriptions refer to it by index
};

}  // namespace rescuesim
