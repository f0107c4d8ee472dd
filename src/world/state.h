#pragma once
/// State: everything about a simulation that changes — sim time, body poses and velocities
/// (and whether rubble sleeps), joint states, commands and controller memory, odometry and IMU
/// noise memory, sensor and publishing schedules and RNG streams. Plain data: a State can be
/// copied, compared and hashed, which is how resets, replays and the determinism tests work.
/// World (world.h) is the part that does not change.
///
/// `visit_fields` below is the one list of State's fields (as msgs/message_fields.h is for
/// messages): the hash walks it, and the test that perturbs every field in turn walks it, so a
/// field added here is hashed as soon as it is added to the list — and the test fails until it is.

#include <concepts>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/index.h"
#include "core/pose.h"
#include "core/rng.h"
#include "core/sim_time.h"

namespace rescuesim {

struct World;

/// Pose and velocity of a rigid body in the world frame.
struct BodyState {
  Pose3 X_WB;                 ///< pose of the body frame in the world
  Vec3 v_WB = Vec3::Zero();   ///< linear velocity of the body origin, world frame (m/s)
  Vec3 w_WB = Vec3::Zero();   ///< angular velocity, world frame (rad/s)
  /// Rubble only (robots never sleep): the physics engine stops integrating a body that has been
  /// still for a while until something touches it.
  enum class Sleep : int { awake = 0, drowsy = 1, asleep = 2 };  ///< drowsy: still long enough, may sleep with its island
  Sleep sleep = Sleep::awake;
  double still_time = 0;      ///< s the body has moved slower than the sleeping thresholds
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
  bool braking = false;                 ///< the drive is at rest and holds its wheels (see update_drive)
  std::vector<double> brake_q;          ///< per joint: the angle a braked wheel is held at (rad)
  std::vector<double> joint_target;     ///< per joint: velocity target (velocity control) or position target
  std::vector<double> head_target;      ///< per head joint (rad)
  bool lights_on = false;               ///< the robot's lamps (RobotSpec::lights), switched by /lights

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
  /// Per robot: when it first saw the victim itself (-1: not yet); empty until the first sighting.
  /// Each robot finds a victim on its own: a team learns of a teammate's finds only by radio.
  std::vector<SimTime> seen_at;

  /// True when robot `r` has seen the victim.
  bool seen_by_robot(std::size_t r) const { return r < seen_at.size() && seen_at[r].ns >= 0; }
  /// Records that robot `r` (named `name`, one of `robots`) sees the victim at `t`: its own
  /// first sighting, and the victim's first when nobody saw it before.
  void saw(std::size_t r, std::size_t robots, const std::string& name, SimTime t) {
    if (seen_at.size() < robots) seen_at.resize(robots, SimTime{-1});
    if (seen_at[r].ns < 0) seen_at[r] = t;
    if (first_seen.ns < 0) {
      first_seen = t;
      seen_by = name;
    }
  }
};

/// What an IMU remembers between samples (sensors/imu.h).
struct ImuMemory {
  Vec3 gyro_bias = Vec3::Zero();        ///< random-walk bias per axis (rad/s)
  Vec3 accel_bias = Vec3::Zero();       ///< random-walk bias per axis (m/s^2)
  Vec3 v_WS = Vec3::Zero();             ///< velocity of the mount point at the previous sample, world frame (m/s)
};

/// What wheel odometry remembers between steps (sensors/odometry.h).
struct OdometryMemory {
  double gyro_bias = 0;                 ///< random-walk bias of the heading gyro (rad/s)
};

/// Per sensor: when it is next due, its own random stream, and whatever it remembers between
/// samples (only the memory of its own kind is used; the others stay zero).
struct SensorSlot {
  SimTime next_due;
  Rng rng{0, "unset"};
  std::uint64_t count = 0;              ///< messages produced
  SimTime last_sample{-1};              ///< -1: never sampled
  ImuMemory imu;                        ///< IMU sensors
  OdometryMemory odometry;              ///< odometry sensors
};

/// When the simulation's own outputs are next due (sensors keep theirs in SensorSlot).
struct Schedule {
  bool started = false;                 ///< the t = 0 outputs (/tf_static, descriptions, first samples) are out
  SimTime next_clock;                   ///< /clock
  SimTime next_tf;                      ///< moving joints on /tf
  SimTime next_victim_check;            ///< line-of-sight victim search
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
  Schedule schedule;
  Trouble trouble;

  /// Robot `r`'s state, checked (std::out_of_range when there is none).
  RobotState& robot(RobotIndex r) { return robots.at(r.slot()); }
  const RobotState& robot(RobotIndex r) const { return robots.at(r.slot()); }
};

/// The state at the start, without a physics engine (MuJoCo's mj_resetData): rubble at rest
/// where the world puts it, robots at their start poses with joints at their initial
/// positions (links placed by forward kinematics), position targets at those positions,
/// one empty record per victim; no sensor slots (the simulation makes those, from its seed).
State initial_state(const World& world);

/// A 64-bit hash of every field of the state (bitwise: equal hashes mean identical states; +0
/// and -0 hash alike), for determinism tests.
std::uint64_t state_hash(const State& s);

/// The hash split into parts, for telling which part of two states differs: one entry per
/// field path cut at two levels ("time", "dynamics[0]", "robots[0].joints", "sensors[3]",
/// "schedule", ...), in field-list order.
std::vector<std::pair<std::string, std::uint64_t>> state_part_hashes(const State& s);

/// True when S is T, possibly const.
template <class S, class T>
concept StatePart = std::same_as<std::remove_const_t<S>, T>;

/// The one field list of State. A visitor `v` provides:
///   v(name, leaf)            a leaf: SimTime, std::int64_t, std::uint64_t, int, double, bool,
///                            BodyState::Sleep, Vec3, Pose3, Pose2, Rng, std::string, or a
///                            std::vector of double, Pose3 or std::string
///   v.group(name, f)         named fields that belong together; f(v) visits them
///   v.items(name, vector, f) one record per element; f(v, element) visits one
/// S may be const (readers such as the hash) or not (the perturbation test).
template <StatePart<BodyState> S, class V>
void visit_fields(S& b, V& v) {
  v("X_WB", b.X_WB);
  v("v_WB", b.v_WB);
  v("w_WB", b.w_WB);
  v("sleep", b.sleep);
  v("still_time", b.still_time);
}

template <StatePart<RobotState> S, class V>
void visit_fields(S& r, V& v) {
  v.group("base", [&](auto& w) {
    visit_fields(r.base, w);
    w("prev_v_WB", r.prev_v_WB);
  });
  v.group("links", [&](auto& w) { w("X_WL", r.X_WL); });
  v.group("joints", [&](auto& w) {
    w("q", r.q);
    w("qd", r.qd);
    w("effort", r.effort);
  });
  v.group("commands", [&](auto& w) {
    w("cmd_linear", r.cmd_linear);
    w("cmd_angular", r.cmd_angular);
    w("cmd_time", r.cmd_time);
    w("drive_v", r.drive_v);
    w("drive_w", r.drive_w);
    w("yaw_rate_integral", r.yaw_rate_integral);
    w("braking", r.braking);
    w("brake_q", r.brake_q);
    w("joint_target", r.joint_target);
    w("head_target", r.head_target);
    w("lights_on", r.lights_on);
  });
  v.group("odometry", [&](auto& w) {
    w("odom", r.odom);
    w("odom_v", r.odom_v);
    w("odom_w", r.odom_w);
  });
  v.group("contacts", [&](auto& w) {
    w("touching", r.touching);
    w("collisions", r.collisions);
    w("distance", r.distance);
  });
}

template <StatePart<SensorSlot> S, class V>
void visit_fields(S& s, V& v) {
  v("next_due", s.next_due);
  v("rng", s.rng);
  v("count", s.count);
  v("last_sample", s.last_sample);
  v("imu.gyro_bias", s.imu.gyro_bias);
  v("imu.accel_bias", s.imu.accel_bias);
  v("imu.v_WS", s.imu.v_WS);
  v("odometry.gyro_bias", s.odometry.gyro_bias);
}

template <StatePart<State> S, class V>
void visit_fields(S& s, V& v) {
  v("time", s.time);
  v("step", s.step);
  v.items("dynamics", s.dynamics, [](auto& w, auto& b) { visit_fields(b, w); });
  v.items("robots", s.robots, [](auto& w, auto& r) { visit_fields(r, w); });
  v.items("victims", s.victims, [](auto& w, auto& victim) {
    w("first_seen", victim.first_seen);
    w("seen_by", victim.seen_by);
    w("seen_at", victim.seen_at);
  });
  v.items("sensors", s.sensors, [](auto& w, auto& slot) { visit_fields(slot, w); });
  v.group("schedule", [&](auto& w) {
    w("started", s.schedule.started);
    w("next_clock", s.schedule.next_clock);
    w("next_tf", s.schedule.next_tf);
    w("next_victim_check", s.schedule.next_victim_check);
  });
  v.group("trouble", [&](auto& w) {
    w("nan_poses", s.trouble.nan_poses);
    w("escaped", s.trouble.escaped);
    w("first", s.trouble.first);
  });
}

}  // namespace rescuesim
