#pragma once
/// A reactive wall follower on planar laser scans (the reactive half of the seed's navigation
/// demo): it keeps a set distance to the wall on one side, slows and turns away when
/// something is ahead, and arcs toward the wall side when the wall ends (a corner).
/// Sign conventions (REP-103): linear.x > 0 drives forward, angular.z > 0 turns
/// counter-clockwise (left).

#include <vector>

#include "autonomy/scan_points.h"
#include "core/pose.h"
#include "core/sim_time.h"
#include "msgs/messages.h"

namespace rescuesim::autonomy {

/// The side the followed wall is on.
enum class WallSide { right, left };

/// What the wall follower did on its last command.
enum class WallFollowerState {
  no_data,         ///< the scan had no beams: stand still
  seeking,         ///< no wall near on its side for a while: drive straight to find one
  following,       ///< tracking the wall's distance and direction
  turning_corner,  ///< the wall just ended: arc toward its side
  avoiding,        ///< something ahead: slowing and turning away from the wall side
  blocked,         ///< something close ahead: turning on the spot
};

/// Settings of a WallFollower.
struct WallFollowerConfig {
  WallSide side = WallSide::right;   ///< follow the wall on this side
  double target_distance = 0.55;     ///< m, from the base origin to the wall
  double max_linear = 0.5;           ///< m/s
  double max_angular = 1.2;          ///< rad/s
  double robot_radius = 0.35;        ///< m
  double front_margin = 0.05;        ///< m of side clearance wanted when looking ahead along the turn's heading
  double slow_distance = 0.8;        ///< m of free travel (along the turn's coming heading) below which it slows and turns away
  double stop_distance = 0.2;        ///< m of free travel straight ahead below which it stops and turns on the spot
  double wall_lost_distance = 1.5;   ///< m; no return on the wall side this near means no wall
  double corner_memory = 2.0;        ///< s after losing the wall during which it arcs toward the wall side
  double distance_gain = 1.5;        ///< rad/s of turn per m of distance error
  double angle_gain = 1.5;           ///< rad/s of turn per rad of heading error to the wall
  double max_distance_error = 0.6;   ///< m; larger distance errors count as this
  /// s; obstacles are looked for along the heading the current turn reaches in this time
  double look_ahead_time = 0.8;
  Pose2 X_BS;                        ///< mounting pose of the laser frame in base_link
};

/// Wall following as a function of the latest scan (plus a short memory of when it last saw
/// the wall, measured with scan stamps).
class WallFollower {
 public:
  explicit WallFollower(WallFollowerConfig config = {});

  /// The velocity command (base_link: linear.x m/s, angular.z rad/s) for this scan, within
  /// the configured limits, never backwards.
  msg::Twist command(const msg::LaserScan& scan);
  /// The same for returns already placed in base_link, stamped `stamp`.
  msg::Twist command(const std::vector<ScanPoint>& points_B, SimTime stamp);

  WallFollowerState state() const { return state_; }     ///< what the last command did
  double wall_distance() const { return wall_distance_; }  ///< m to the wall side's nearest return, +inf if none
  double front_distance() const { return front_distance_; }  ///< m of free travel straight ahead, +inf if clear
  const WallFollowerConfig& config() const { return config_; }  ///< its settings
  /// Forgets the last time the wall was seen.
  void reset();

 private:
  WallFollowerConfig config_;
  WallFollowerState state_ = WallFollowerState::no_data;
  double wall_distance_ = 0, front_distance_ = 0;
  bool seen_wall_ = false;
  SimTime last_wall_seen_;
};

}  // namespace rescuesim::autonomy
