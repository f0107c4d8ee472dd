#pragma once
/// The built-in exploring controller (the seed's navigation demo, sections 4.1-4.2): it maps
/// with the laser, follows a wall by default, and when it gets stuck (no progress, slipping
/// wheels, blocked again and again, or circling ground it already knows) it plans with A* to
/// the nearest frontier, drives there and resumes wall following; when stuck in place it
/// first reverses a little if the way back is clear. A goal mode drives to a set point.
/// It talks only in messages and reads time only from their stamps and the `now` it is
/// given, so the same object runs in-process and inside a ROS node, deterministically.
///
/// Frames: odometry comes in the odom frame O. The explorer keeps its own map frame M, which
/// coincides with O at the start; every scan after the first is matched against the map
/// (ScanMatcher) from the odometry prediction, and a good match updates the correction X_MO
/// (the odom frame in the map frame), so the map does not bend with odometry's drift. Scans
/// are mapped, paths planned and followed, goals set and the robot's pose tracked in M.

#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "autonomy/astar.h"
#include "autonomy/look_coverage.h"
#include "autonomy/occupancy_grid.h"
#include "autonomy/path_follower.h"
#include "autonomy/scan_matcher.h"
#include "autonomy/scan_points.h"
#include "autonomy/slip_detector.h"
#include "autonomy/wall_follower.h"
#include "msgs/messages.h"

namespace rescuesim::autonomy {

/// What the explorer is doing.
enum class ExplorerMode {
  wall_following,  ///< reactive wall following (the default)
  to_frontier,     ///< following an A* path to the nearest frontier
  to_goal,         ///< following an A* path to the goal set by set_goal
  at_goal,         ///< arrived at the goal: standing still
  backing_up,      ///< stuck: reversing a little before planning a way on
};

/// Why the explorer last decided it was stuck.
enum class StuckReason {
  none,         ///< not stuck yet
  no_progress,  ///< moved less than stuck_distance in stuck_window, or the wheels slip
  blocked,      ///< blocked_limit stop-and-turn episodes within blocked_window
  looping,      ///< a novelty_window of wall following added under novelty_min_area of new map
};

/// Where the explorer's victim camera looks (ExplorerConfig::look). With it enabled, the
/// explorer keeps a LookCoverage of the ground the camera has seen, counts free ground it has
/// not seen as worth a trip as much as a frontier, and swings the camera from side to side
/// when a joint turns it (look_command).
struct ExplorerLookConfig {
  bool enabled = false;           ///< track the camera's view and explore towards ground it has not seen
  CameraFan fan;                  ///< the camera's horizontal fan
  std::string yaw_joint;          ///< the joint (in joint_states) that turns the camera about the vertical; empty: none
  double yaw_sign = 1.0;          ///< +1 when that joint's axis points up, -1 when down
  double fixed_yaw = 0.0;         ///< rad; the camera's yaw in base_link when no joint turns it
  double sweep_amplitude = 1.05;  ///< rad the camera swings either side of ahead (0: it looks ahead)
  double sweep_period = 4.0;      ///< s for one swing there and back
  int min_cells = 40;             ///< unseen free cells (8-connected) worth a trip
};

/// Settings of an Explorer. The constructor copies robot_radius into the planner's and the
/// wall follower's settings.
struct ExplorerConfig {
  double robot_radius = 0.35;        ///< m, the robot as a disc
  std::string frame_id = "map";      ///< name of the map frame M (of the map and paths); see X_MO()
  OccupancyMapperConfig map;         ///< mapping (auto-sized around the first scan by default)
  PlannerConfig planner;             ///< A* and frontier search
  WallFollowerConfig wall;           ///< the reactive controller (its X_BS is set by the constructor)
  PathFollowerConfig path;           ///< pure pursuit
  bool frontier_trips = true;        ///< false: pure wall following, never stuck, never plans (goals still work)
  /// true: drive from one frontier to the next and follow walls only while none is reachable
  /// (re-planned every replan_period); false: follow walls and plan a frontier trip when stuck
  bool frontier_first = false;
  ExplorerLookConfig look;           ///< the victim camera (disabled by default)
  double stuck_window = 8.0;         ///< s; moving less than stuck_distance in this long is stuck
  double stuck_distance = 0.3;       ///< m
  SlipDetectorConfig slip;           ///< odometry checked against the laser and the scan matcher: slipping wheels mean stuck
  bool scan_matching = true;         ///< false: the map frame stays the odom frame (X_MO the identity)
  /// s; least sim time between two scans mapped while wall following (0: every scan). Paths
  /// (frontier trips, goals and reversing) always map every scan; a wall follower steers by
  /// the laser alone, so a map that only feeds the run's outputs may be drawn at a lower rate.
  double map_period = 0;
  /// scan-to-map matching; the likelihood field is rebuilt every 5 scans (0.5 s at 10 Hz)
  ScanMatcherConfig matcher = [] {
    ScanMatcherConfig c;
    c.field_refresh = 5;
    return c;
  }();
  int blocked_limit = 3;             ///< this many blocked episodes (stop and turn on the spot) ...
  double blocked_window = 20.0;      ///< s ... within this long is stuck
  double novelty_window = 30.0;      ///< s; wall following this long while learning ...
  double novelty_min_area = 0.5;     ///< m^2 ... less than this much new map is looping
  double replan_period = 1.0;        ///< s; least sim time between two plans
  double goal_replan_period = 2.0;   ///< s; the goal path is replanned this often on the growing map
  int max_tries = 3;                 ///< a frontier whose path got stuck this often is given up
  double safety_stop_distance = 0.1;  ///< m of free travel ahead below which a path is not driven forward
  double safety_slow_distance = 0.6;  ///< m of free travel ahead below which path driving slows
  /// m: other robots as discs of this radius around their masts; 0: none expected (a robot
  /// alone). The laser of the built-in robot passes above another robot's body and returns
  /// only from its mast, so a thin return standing alone in the scan (scan_points'
  /// thin_returns, narrower than post_width) with few occupied cells around it in the map (a
  /// wall's end seen edge-on has its wall behind it) is taken for a mast: path driving slows
  /// and stops for the disc as for the laser's returns, and plans keep clear of it.
  double post_radius = 0;
  double post_width = 0.09;  ///< m, widest return taken for a mast (the built-in robot's is 0.07 m)
  double blocked_clearance_factor = 0.8;  ///< an occupied cell within this x robot_radius of the path blocks it
  double backup_time = 2.0;          ///< s of reversing when stuck (when the way back is clear)
  double backup_speed = 0.15;        ///< m/s, reversing speed
  double backup_cooldown = 10.0;     ///< s after reversing before it may reverse again
  /// m of free travel behind needed to start reversing: seen by the laser when its fan covers
  /// the rear, else every cell the robot would sweep (plus slip.min_motion for odometry drift)
  /// must be known free on the map
  double backup_clearance = 0.3;
};

/// Counters of what the explorer did, for tests, logs and run summaries.
struct ExplorerStats {
  int scans = 0;              ///< scans integrated into the map
  long cells_learned = 0;     ///< map cells observed for the first time
  int plans = 0;              ///< planner calls
  int frontier_trips = 0;     ///< paths to a frontier started
  int frontiers_reached = 0;  ///< frontier paths driven to their end
  int stuck_no_progress = 0;  ///< stuck triggers: no progress
  int stuck_blocked = 0;      ///< stuck triggers: blocked again and again
  int stuck_looping = 0;      ///< stuck triggers: going round known ground
  int no_frontier = 0;        ///< stuck, but no reachable frontier was left
  int path_blocked = 0;       ///< replans because the map showed an obstacle on the path
  int path_stuck = 0;         ///< replans because the path follower made no progress
  int abandoned = 0;          ///< frontiers given up after max_tries
  int backups = 0;            ///< times it reversed to get unstuck
  int slipping_scans = 0;     ///< scans that contradicted odometry and were not matched to the map (not mapped)
  int scans_matched = 0;      ///< scans whose match to the map was good (X_MO updated)
  int scans_ambiguous = 0;    ///< scans matched in one direction only (a corridor; X_MO updated across it)
  int scans_unmatched = 0;    ///< scans whose match was rejected (X_MO kept)
  int look_trips = 0;         ///< trips started to ground the camera has not seen (not a frontier)
  int team_frontier_trips = 0;  ///< trips to frontiers where a teammate has looked, when nothing else was left
  long team_mapped_cells = 0;   ///< cells of this robot's map that teammates said they mapped (add_team_map), counted once each
};

/// Wall following plus A* frontier trips on a laser-built map.
class Explorer {
 public:
  /// `X_BS` is the laser's mounting pose (laser frame in base_link), used to place scans.
  explicit Explorer(const Pose2& X_BS, ExplorerConfig config = {});

  /// Matches a scan against the map, starting from the odom pose interpolated to its stamp
  /// placed in the map frame by X_MO; a good match updates X_MO. The scan is then integrated
  /// into the map at the corrected pose (scans before the first odometry, and scans that
  /// contradict odometry and could not be matched, only feed the reactive controller).
  void on_scan(const msg::LaserScan& scan);
  /// Records the pose of base_link in the odom frame (header.frame_id) at the stamp.
  void on_odometry(const msg::Odometry& odom);
  /// The velocity command (base_link: linear.x m/s, angular.z rad/s) at sim time `now`;
  /// zero until both a scan and odometry have arrived.
  msg::Twist command(SimTime now);

  /// Records where the camera's yaw joint stands (ExplorerLookConfig::yaw_joint); other
  /// joints are ignored.
  void on_joint_state(const msg::JointState& joints);
  /// The position (rad) to command the camera's yaw joint to at sim time `now`: a swing of
  /// sweep_amplitude either side of ahead (the camera's yaw in base_link swings about 0); nothing when looking is disabled, no joint turns
  /// the camera or the amplitude is zero.
  std::optional<double> look_command(SimTime now) const;
  /// Where the camera has looked (map frame cells; empty while looking is disabled), and
  /// where teammates said theirs have.
  const LookCoverage& looked() const { return looked_; }
  /// Ground a teammate's camera has looked at (squares of side `cell` m centred on `centres_M`,
  /// map frame), as it said over the radio: not worth a trip of this robot's, neither as
  /// unseen ground nor as a frontier. Ignored while looking is disabled or before the first scan.
  void add_team_seen(const std::vector<Vec2>& centres_M, double cell);

  /// What a teammate's laser has mapped, as it said over the radio: squares of side `cell` m
  /// centred on the points (map frame), each free or occupied. A frontier of this robot's map
  /// whose unknown side a teammate has mapped is no longer worth a trip (the teammate has been
  /// there); such frontiers are not even a last resort. The team's word is kept beside this
  /// robot's own map, never in it: scan matching and the paths themselves use this robot's map
  /// alone, so a teammate's misplaced map cannot pull it off the walls or into one. Ignored
  /// before the first scan.
  void add_team_map(const std::vector<std::pair<Vec2, CellState>>& squares_M, double cell);
  /// True when a teammate has said cell `c` (inside the map) is free or occupied.
  bool team_mapped(Cell c) const {
    return !team_.map.empty() && team_.map[static_cast<std::size_t>(mapper_.index(c))] != CellState::unknown;
  }

  /// Drives to `p_M` (m, map frame) by A* over the map (unknown cells allowed per the
  /// planner settings), replanning as the map grows; stops there (mode at_goal).
  void set_goal(const Vec2& p_M);
  /// Drops the goal and goes back to exploring.
  void clear_goal();

  /// Points (m, map frame) where teammates are or are going: frontier trips skip frontiers
  /// within the planner's claimed_radius of them, unless no other frontier is left. Replaces
  /// the previous set; empty for a robot alone.
  void set_claims(std::vector<Vec2> claims_M) { team_.claims_M = std::move(claims_M); }
  /// Other robots' masts in the last scan (map frame; ExplorerConfig::post_radius).
  const std::vector<Vec2>& masts() const { return scan_.masts_M; }
  /// The end of the frontier trip under way (map frame), if one is.
  std::optional<Vec2> frontier_target() const {
    return mode_ == ExplorerMode::to_frontier ? std::optional<Vec2>(plan_.target_M) : std::nullopt;
  }

  /// The path being followed (map frame), empty when wall following.
  const msg::Path& current_path() const { return plan_.path_msg; }
  /// The map so far (map frame, named frame_id; `stamp`); an empty grid before the first scan.
  msg::OccupancyGrid map(SimTime stamp) const;
  /// The map itself (map frame), for planners and plots in-process.
  const OccupancyMapper& mapper() const { return mapper_; }

  /// The odom frame in the map frame: the correction scan matching has found so far (the
  /// identity until the first good match, and always without scan matching).
  const Pose2& X_MO() const { return loc_.X_MO; }
  /// The pose of base_link in the map frame at `t` (odometry at t, corrected by the current
  /// X_MO); nothing before the first odometry.
  std::optional<Pose2> pose_in_map(SimTime t) const;
  /// The last scan match (verdict rejected before the first).
  const ScanMatch& last_match() const { return loc_.last_match; }

  /// What it is doing now.
  ExplorerMode mode() const { return mode_; }
  /// Why it last decided it was stuck (none before the first time).
  StuckReason last_stuck_reason() const { return progress_.last_stuck; }
  /// True after a stuck trigger found no reachable frontier (cleared when one is found).
  bool exploration_complete() const { return plan_.complete; }
  /// Counters of what it did.
  const ExplorerStats& stats() const { return stats_; }
  /// Its settings, with robot_radius and X_BS copied into the parts.
  const ExplorerConfig& config() const { return config_; }

 private:
  /// Where the robot is: odometry, the map frame's correction, the last pose the laser agreed
  /// with, and where its camera looks. Written by on_odometry, on_scan and on_joint_state.
  struct Localisation {
    std::deque<std::pair<SimTime, Pose2>> odom;  // recent poses of base_link in odom
    Pose2 X_MO;                                  // the odom frame in the map frame
    ScanMatch last_match;
    std::optional<Pose2> trusted_X_MB;  // pose of the last scan that fitted odometry or the map
    double camera_yaw = 0;              // the camera's yaw in base_link (rad)
  };
  /// The latest scan as the reactive parts read it (wall follower, path safety, reversing,
  /// masts), and when the map last took one.
  struct LatestScan {
    std::vector<ScanPoint> points_B;  // in base_link
    SimTime stamp;
    bool have = false;          // a scan has arrived
    bool sees_behind = false;   // the laser's fan covers the robot's rear
    std::vector<Vec2> masts_M;  // other robots' masts in it (post_radius)
    SimTime last_mapped;        // stamp of the last scan integrated into the map
  };
  /// Whether the robot is getting anywhere: what stuck_reason reads.
  struct Progress {
    bool started = false;  // tracking runs (else it restarts at the next command)
    Pose2 anchor;          // where the robot was when it last made progress
    SimTime anchor_time;
    SimTime since;                      // when tracking last restarted (looping is judged from here)
    std::deque<SimTime> blocked_times;  // starts of blocked episodes
    WallFollowerState last_wall_state = WallFollowerState::no_data;
    std::deque<std::pair<SimTime, int>> novelty;  // cells learned per scan, by stamp
    StuckReason last_stuck = StuckReason::none;
  };
  /// The trip under way (to a frontier or the goal), its path, and the planner's schedule.
  struct Plan {
    std::optional<Vec2> goal_M;  // map frame, as everything below
    bool goal_needs_plan = false;
    Vec2 target_M = Vec2::Zero();  // end of the current path
    int tries = 0;                 // stuck paths to this frontier so far
    std::vector<Vec2> excluded_M;  // frontiers given up
    bool planned = false;          // last_plan is set
    SimTime last_plan;
    SimTime last_check;                 // last look for obstacles on the path
    bool team_frontier_target = false;  // the last plan had to take a frontier a teammate looked at
    bool complete = false;              // the last search found no reachable frontier
    msg::Path path_msg;
  };
  /// Reversing out of a stuck spot.
  struct Reversing {
    std::optional<SimTime> until;                        // end of the last reversing (none before the first)
    ExplorerMode resume = ExplorerMode::wall_following;  // what it was for
  };
  /// What teammates said over the radio (set_claims, add_team_map, add_team_seen).
  struct TeamKnowledge {
    std::vector<Vec2> claims_M;  // where teammates are and are going
    std::vector<CellState> map;  // per map cell: what teammates mapped; empty before the first
    bool seen = false;           // a teammate's squares marked some cell of `looked_`
  };

  /// The one place the mode changes, with what entering each mode takes: wall following drops
  /// the path and restarts progress tracking (at `now`, or at the next command when called
  /// between commands); a goal trip drops the path and asks for a plan; a frontier trip
  /// counts its tries afresh unless it resumes after reversing; reversing drops the path and
  /// sets its end. `now` is nothing only between commands (set_goal, clear_goal).
  void enter(ExplorerMode mode, std::optional<SimTime> now);
  std::optional<Pose2> pose_at(SimTime t) const;  // odometry (base_link in odom) at t
  bool match_scan(const Pose2& X_OB);
  msg::Twist wall_follow(const Pose2& X_MB, SimTime now);
  msg::Twist drive_to_frontier(const Pose2& X_MB, SimTime now);
  msg::Twist drive_to_goal(const Pose2& X_MB, SimTime now);
  msg::Twist follow_path(const Pose2& X_MB, SimTime now);
  msg::Twist back_up(const Pose2& X_MB, SimTime now);
  bool start_backup(ExplorerMode resume, SimTime now);
  bool rear_clear(double distance) const;
  bool wheels_slipping() const;
  StuckReason stuck_reason(SimTime now) const;
  bool may_plan(SimTime now) const;
  bool due_for_check(SimTime now);
  bool path_ahead_blocked(const Pose2& X_MB) const;
  std::vector<Vec2> plan_frontier(const Pose2& X_MB, SimTime now);
  bool still_frontier(const Vec2& p_M) const;
  /// Other robots' masts in the scan just mapped (LatestScan::masts_M, ExplorerConfig::post_radius).
  void find_masts(const Pose2& X_MB);
  bool unseen(Cell c) const;
  /// A frontier whose unknown side some teammate has not mapped either (any frontier without
  /// a teammate's map).
  bool open_frontier(Cell c) const;
  /// Follows `path` (a trip in the current mode): its end, its message, fresh slip evidence.
  void start_path(std::vector<Vec2> path, SimTime now);
  void reset_progress(const Pose2& X_MB, SimTime now);

  // the parts, made from the settings
  Pose2 X_BS_;
  ExplorerConfig config_;
  OccupancyMapper mapper_;
  AStarPlanner planner_;
  WallFollower wall_;
  PathFollower follower_;
  SlipDetector slip_;        // odometry against the laser, scan to scan
  SlipDetector match_slip_;  // odometry against scan matching
  ScanMatcher matcher_;
  LookCoverage looked_;  // where this robot's camera and (add_team_seen) its teammates' have looked

  // the state, by who reads it
  ExplorerMode mode_ = ExplorerMode::wall_following;  // changed only by enter()
  Localisation loc_;
  LatestScan scan_;
  Progress progress_;
  Plan plan_;
  Reversing reversing_;
  TeamKnowledge team_;
  ExplorerStats stats_;
};

}  // namespace rescuesim::autonomy
