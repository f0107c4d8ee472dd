#pragma once
/// The engine behind `rescuesim.Env`: one simulation (its own World, State, physics and
/// sensors: nothing shared with other environments) stepped a control period at a time, with
/// the controlled robot's sensor messages copied into fixed observation buffers and a small
/// rescue task scoring each step. No Python types here: src/module.cpp binds it.
///
/// The task (docs/python.md): reward = victim_reward × victims this robot found first during the
/// step − collision_penalty × collisions it began − time_penalty × seconds simulated. An episode
/// terminates when every victim has been found (or numerical trouble stops the simulation) and
/// is truncated at `max_time` seconds of sim time.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/pose.h"
#include "import/scenario/scenario.h"
#include "msgs/messages.h"

namespace rescuesim {

class Session;
struct SessionSnapshot;

namespace python {

/// Settings of an environment beyond its scenario.
struct EnvOptions {
  bool cameras = false;                ///< render the colour, depth and thermal cameras (needs OpenGL; slower)
  double control_period = 0.1;         ///< s of sim time per step()
  std::optional<double> max_time;      ///< s of sim time per episode (default: the scenario's duration)
  std::string robot;                   ///< name of the robot the actions drive ("" = the first)
  bool fixed_world = false;            ///< reset(seed) reseeds only the noise; the world keeps the scenario's seed
  std::string controller;              ///< "" = the actions drive; "explorer" or "wall_follower" = that controller drives (actions ignored)
  double victim_reward = 10.0;         ///< per victim found
  double collision_penalty = 1.0;      ///< per collision begun
  double time_penalty = 0.01;          ///< per second of sim time
  std::vector<std::string> observations;  ///< keys to observe (empty = every available one)
};

/// One observation: a key, an element type and a shape; stored contiguously (C order).
struct ObsField {
  enum class Kind { lidar, sonar, imu, odometry, color, depth, thermal };
  std::string key;                     ///< "laser", "sonar", "imu", "odometry", "color_camera", ...
  std::string dtype;                   ///< numpy dtype name: float32, float64, uint8, uint16
  std::vector<std::size_t> shape;
  std::size_t item = 4;                ///< bytes per element
  Kind kind = Kind::lidar;
  std::vector<int> sensors;            ///< indices into the robot's RobotSpec::sensors feeding it (several sonars)
  std::string depth_encoding;          ///< depth cameras: 32FC1 or 16UC1
  std::size_t bytes() const;
};

/// What one step gave.
struct StepOutcome {
  double reward = 0;
  bool terminated = false;
  bool truncated = false;
};

/// The state of an episode, for the info dict.
struct EpisodeInfo {
  std::uint64_t seed = 0;
  double sim_time = 0;                  ///< s
  int steps = 0;                        ///< steps since reset
  int victims_found = 0, victims_total = 0;  ///< all robots
  int collisions = 0;                   ///< the controlled robot's
  double distance = 0;                  ///< m, the controlled robot's
  double coverage = 0;                  ///< fraction of free floor passed within 1 m of
  Pose2 pose;                           ///< ground truth pose of the controlled robot in the world
  std::vector<std::string> new_victims; ///< found by this robot during the last step
  std::string trouble;                  ///< numerical trouble that stopped the simulation ("" when none)
};

/// One simulation as an environment.
class EnvCore {
 public:
  /// Builds the scenario once (with its own seed) to learn the observation layout; throws
  /// Error for a bad scenario or options.
  EnvCore(Scenario scenario, ModelMap models, EnvOptions options);
  ~EnvCore();
  EnvCore(const EnvCore&) = delete;
  EnvCore& operator=(const EnvCore&) = delete;

  const EnvOptions& options() const { return options_; }
  const Scenario& scenario() const { return scenario_; }
  /// Observation fields, fixed for the life of the environment.
  const std::vector<ObsField>& fields() const { return fields_; }
  /// Where field k is written (fields()[k].bytes() bytes). Stable for the life of the
  /// environment unless bind() moves it.
  std::uint8_t* buffer(std::size_t k) const { return buffers_[k]; }
  /// Writes the observations into caller-owned memory from now on (one pointer per field).
  void bind(const std::vector<std::uint8_t*>& buffers);

  /// Lowest and highest forward speed (m/s) and turn rate (rad/s) the drive accepts.
  double max_linear() const { return max_linear_; }
  double max_angular() const { return max_angular_; }

  /// Starts an episode with run seed `seed`, observations of t = 0. With the seed of the last
  /// episode the simulation goes back to the snapshot taken when it was built (exact: the
  /// episode replays bitwise under the same actions, and costs no rebuild of the world,
  /// Bullet, Embree or GL); with another seed it is built anew.
  void reset(std::uint64_t seed);
  /// Drives at `linear` m/s and `angular` rad/s for one control period and scores it. Throws
  /// Error before the first reset() or for non-finite commands.
  StepOutcome step(double linear, double angular);
  /// True once an episode has terminated or been truncated (step() then throws until reset()).
  bool done() const { return done_; }
  /// How many times the simulation was built: once per seed change, not per reset.
  int builds() const { return builds_; }
  EpisodeInfo info() const;
  /// Index of the robot the actions drive (and that reports in a mission).
  RobotIndex robot_index() const { return robot_; }
  /// The simulation of the current episode (null before the first reset()).
  Session* session() const { return session_.get(); }

 private:
  void build(std::uint64_t seed);
  void subscribe();
  void clear_buffers();

  Scenario scenario_;
  ModelMap models_;
  EnvOptions options_;
  std::vector<ObsField> fields_;
  std::vector<std::vector<std::uint8_t>> own_;   // storage unless bind() gave other memory
  std::vector<std::uint8_t*> buffers_;
  std::unique_ptr<Session> session_;
  std::unique_ptr<SessionSnapshot> start_;  // session_ as built, before its first step
  RobotIndex robot_{0};
  std::string robot_name_;
  std::uint64_t seed_ = 0;
  bool fresh_ = false;     // the session was built but not stepped
  int builds_ = 0;
  bool ready_ = false;     // reset() has been called
  bool done_ = false;
  int steps_ = 0;
  std::int64_t period_ns_ = 0;
  std::vector<std::uint8_t> found_;  // per victim: seen already
  int collisions_ = 0;
  std::vector<std::string> new_victims_;
  double max_linear_ = 1.0, max_angular_ = 1.0;
  double max_time_ = 0;
};

}  // namespace python
}  // namespace rescuesim
