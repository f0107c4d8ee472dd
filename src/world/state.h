#pragma once
/// State: everything about a simulation that changes — sim time, body poses and velocities,
/// joint states, commands and controller memory, odometry and IMU noise memory, sensor
/// schedules and RNG streams. Plain data: a State can be copied, compared and hashed, which is
/// how resets, replays and the determinism test work. World (world.h) is the part that does
/// not change.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/pose.h"
#include "core/rng.h"
#include "core/sim_time.h"

namespace rescuesim {

/// Pose and velocity of a rigid body in the world frame.
struct BodyState {
  Pose3 X_WB;                 ///< pose of the body frame in the world
  Vec3 v_WB = Vec3::Zero();   ///< linear velocity of the body origin, world frame (m/s)
  Vec3 w_WB = Vec3::Zero();   ///< angular velocity, world frame (rad/s)
};

/// A robot's changing state.
struct RobotState {
  BodyState base;                       ///< base link (chassis)
  Vec3 prev_v_WB = Vec3::Zero();        ///< base velocity one step earlier (for acceleration)
  std::vector<Pose3> X_WL;              ///< every link's pose in the world (links[0] = base)
  std::vector<double> q, qd, effort;    ///< per joint (fixed joints stay 0)

  // commands as received, and what the controllers made of them
  Vec3 cmd_linear = Vec3::Zero();       ///< last cmd_vel linear (m/s, base frame)
  Vec3 cmd_angular = Vec3::Zero();      ///< last cmd_vel angular (rad/s)
  SimTime cmd_time{-1};                 ///< when it arrived (-1: never)
  double drive_v = 0, drive_w = 0;      ///< acceleration-limited set points (m/s, rad/s)
  double yaw_rate_integral = 0;         ///< drive controller: integral of the yaw-rate error (rad)
  std::vector<double> joint_target;     ///< per joint: velocity target (velocity control) or position target
  std::vector<double> head_target;      ///< per head joint (rad)

  // wheel odometry, integrated from wheel joint velocities
  Pose2 odom;                           ///< pose of base_link in odom
  double odom_v = 0, odom_w = 0;        ///< body speed estimated by odometry

  // contacts and statistics
  std::vector<std::string> touching;    ///< objects touching the robot's links this step (sorted)
  int collisions = 0;                   ///< contacts started with walls, obstacles, victims or other robots
  double distance = 0;                  ///< ground-truth path length (m)
};

/// A victim's discovery record.
struct VictimState {
  SimTime first_seen{-1};               ///< -1: not yet seen
  std::string seen_by;                  ///< robot name
};

/// Per sensor: when it is next due, its own random stream, and whatever it remembers between
/// samples (an IMU's biases and last velocity, for example).
struct SensorSlot {
  SimTime next_due;
  Rng rng{0, "unset"};
  std::uint64_t count = 0;              ///< messages produced
  SimTime last_sample{-1};              ///< -1: never sampled
  std::array<Vec3, 3> memory{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
};

/// Numerical trouble found while stepping.
struct Trouble {
  int nan_poses = 0;                    ///< bodies whose pose became NaN
  int escaped = 0;                      ///< bodies flung far outside the world
  std::string first;                    ///< the first problem, as a message
};

/// The whole changing state of a simulation.
struct State {
  SimTime time;                         ///< sim time of this state
  std::int64_t step = 0;                ///< physics steps taken
  std::vector<BodyState> dynamics;      ///< one per World::dynamics (rubble)
  std::vector<RobotState> robots;       ///< one per World::robots
  std::vector<VictimState> victims;     ///< one per World::victims
  std::vector<SensorSlot> sensors;      ///< one per sensor, in Simulation order
  Trouble trouble;
};

/// A 64-bit hash of every number in the state (bitwise: equal hashes mean identical states),
/// for determinism tests.
std::uint64_t state_hash(const State& s);

}  // namespace rescuesim
