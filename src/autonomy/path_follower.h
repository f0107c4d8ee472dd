#pragma once
/// Pure-pursuit tracking of a planned path of odom-frame points, with arrival and
/// "stuck" reports measured in sim time.

#include <cstddef>
#include <vector>

#include "core/pose.h"
#include "core/sim_time.h"
#include "msgs/messages.h"

namespace rescuesim::autonomy {

/// Where a PathFollower stands.
enum class PathStatus {
  idle,       ///< no path
  following,  ///< driving along the path
  reached,    ///< within goal_tolerance of the path's last point
  stuck,      ///< no progress along the path for stuck_time
};

/// Settings of a PathFollower.
struct PathFollowerConfig {
  double lookahead = 0.6;              ///< m along the path ahead of the closest point
  double max_linear = 0.4;             ///< m/s
  double max_angular = 1.2;            ///< rad/s
  double goal_tolerance = 0.25;        ///< m from the last point that counts as arrived
  double rotate_in_place_angle = 1.0;  ///< rad; a target bearing beyond this is first turned to on the spot
  double turn_gain = 2.0;              ///< rad/s per rad of bearing when turning on the spot
  double stuck_time = 5.0;             ///< s without stuck_progress before reporting stuck
  double stuck_progress = 0.2;         ///< m of progress (along the path or toward it) that resets the stuck timer
  double search_window = 2.0;          ///< m of path ahead of the last closest point searched for the next one
};

/// Pure pursuit on a polyline in the odom frame.
class PathFollower {
 public:
  explicit PathFollower(PathFollowerConfig config = {});

  /// Starts following `path_O` (m, odom frame; may be a single point) at time `now`.
  void set_path(std::vector<Vec2> path_O, SimTime now);
  /// Drops the path (status idle).
  void clear();

  /// The velocity command (base_link: linear.x m/s >= 0, angular.z rad/s) for the robot at
  /// `X_OB` (base_link in odom) at time `now`; zero once reached, stuck or idle.
  msg::Twist command(const Pose2& X_OB, SimTime now);

  PathStatus status() const { return status_; }  ///< where it stands after the last command
  const std::vector<Vec2>& path() const { return path_; }  ///< m, odom frame
  /// Index of the first path point beyond the closest point (path.size() at the end).
  std::size_t next_index() const;
  /// Path length (m) from the closest point to the end.
  double remaining_length() const;
  const PathFollowerConfig& config() const { return config_; }  ///< its settings

 private:
  Vec2 point_at(double s) const;  // the path point at arc length s (m)

  PathFollowerConfig config_;
  std::vector<Vec2> path_;
  std::vector<double> arc_;       // arc length (m) at each path point
  PathStatus status_ = PathStatus::idle;
  double progress_ = 0;           // arc length of the closest point (m), never decreasing
  double best_remaining_ = 0;     // least distance to go so far (m): along the path plus to it
  SimTime best_time_;             // when best_remaining_ last improved by stuck_progress
};

}  // namespace rescuesim::autonomy
