#include "autonomy/explorer.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.h"

namespace rescuesim::autonomy {

namespace {

// odometry kept for placing scans: enough for several seconds at usual rates
constexpr std::size_t kOdomHistory = 256;

// does the scan have a beam within one increment of base_link bearing `b` (rad)?
bool looks_toward(const msg::LaserScan& scan, const Pose2& X_BS, double b) {
  if (scan.ranges.empty() || !(scan.angle_increment > 0)) return false;
  double offset = b - X_BS.yaw - scan.angle_min;
  offset -= 2 * M_PI * std::floor(offset / (2 * M_PI));
  const double per_turn = 2 * M_PI / scan.angle_increment;
  double beam = std::round(offset / scan.angle_increment);
  if (beam >= per_turn - 0.5) beam -= std::round(per_turn);
  return beam >= 0 && beam < static_cast<double>(scan.ranges.size());
}

ExplorerConfig with_shared_settings(ExplorerConfig c, const Pose2& X_BS) {
  c.wall.X_BS = X_BS;
  c.wall.robot_radius = c.robot_radius;
  c.planner.cost.robot_radius = c.robot_radius;
  return c;
}

}  // namespace

Explorer::Explorer(const Pose2& X_BS, ExplorerConfig config)
    : X_BS_(X_BS),
      config_(with_shared_settings(std::move(config), X_BS)),
      mapper_(config_.map),
      planner_(config_.planner),
      wall_(config_.wall),
      follower_(config_.path),
      slip_(config_.slip),
      match_slip_(config_.slip),
      matcher_(config_.matcher) {
  loc_.camera_yaw = config_.look.fixed_yaw;
  plan_.path_msg.header.frame_id = config_.frame_id;
}

void Explorer::on_joint_state(const msg::JointState& joints) {
  const ExplorerLookConfig& look = config_.look;
  if (look.yaw_joint.empty()) return;
  for (std::size_t i = 0; i < joints.name.size() && i < joints.position.size(); ++i) {
    if (joints.name[i] == look.yaw_joint && std::isfinite(joints.position[i])) {
      loc_.camera_yaw = look.fixed_yaw + look.yaw_sign * joints.position[i];
    }
  }
}

std::optional<double> Explorer::look_command(SimTime now) const {
  const ExplorerLookConfig& look = config_.look;
  if (!look.enabled || look.yaw_joint.empty() || look.sweep_amplitude == 0 || !(look.sweep_period > 0)) return std::nullopt;
  // a sine swing about ahead (camera yaw 0 in base_link): slow at its ends, where the camera
  // lingers on the sides of a corridor; the joint position giving camera yaw y is sign (y - fixed_yaw)
  const double phase = 2 * M_PI * now.seconds() / look.sweep_period;
  return look.yaw_sign * (look.sweep_amplitude * std::sin(phase) - look.fixed_yaw);
}

void Explorer::on_odometry(const msg::Odometry& odom) {
  // a stamp going backwards means the run restarted: forget the old poses
  if (!loc_.odom.empty() && odom.header.stamp < loc_.odom.back().first) loc_.odom.clear();
  loc_.odom.emplace_back(odom.header.stamp, odom.pose.to_pose2());
  if (loc_.odom.size() > kOdomHistory) loc_.odom.pop_front();
}

std::optional<Pose2> Explorer::pose_at(SimTime t) const {
  if (loc_.odom.empty()) return std::nullopt;
  if (t <= loc_.odom.front().first) return loc_.odom.front().second;
  if (t >= loc_.odom.back().first) return loc_.odom.back().second;
  // interpolate between the poses either side of t
  auto after = std::lower_bound(loc_.odom.begin(), loc_.odom.end(), t, [](const auto& e, SimTime s) { return e.first < s; });
  auto before = std::prev(after);
  const double span = (after->first - before->first).seconds();
  const double a = span > 0 ? (t - before->first).seconds() / span : 1.0;
  const Pose2& p = before->second;
  const Pose2& q = after->second;
  return Pose2{p.x + a * (q.x - p.x), p.y + a * (q.y - p.y), wrap_angle(p.yaw + a * wrap_angle(q.yaw - p.yaw))};
}

std::optional<Pose2> Explorer::pose_in_map(SimTime t) const {
  const auto X_OB = pose_at(t);
  if (!X_OB) return std::nullopt;
  return loc_.X_MO * *X_OB;
}

bool Explorer::match_scan(const Pose2& X_OB) {
  // the scan against the map so far, from odometry's prediction; a match pins down the pose
  // (or, in a corridor, all but the shift along it) and so the correction X_MO
  std::vector<Vec2> p_B;
  p_B.reserve(scan_.points_B.size());
  for (const ScanPoint& p : scan_.points_B) {
    if (!p.too_close) p_B.push_back(p.p_B);
  }
  loc_.last_match = matcher_.match(mapper_, p_B, loc_.X_MO * X_OB);
  if (loc_.last_match.verdict == MatchVerdict::rejected) {
    ++stats_.scans_unmatched;
    return false;
  }
  ++(loc_.last_match.verdict == MatchVerdict::good ? stats_.scans_matched : stats_.scans_ambiguous);
  loc_.X_MO = loc_.last_match.X_MB * X_OB.inverse();
  // odometry's motion against the matched one: wheels that spin while the scans stay put
  match_slip_.add_motion(X_OB, loc_.last_match.X_MB);
  return true;
}

void Explorer::on_scan(const msg::LaserScan& scan) {
  // the reactive controllers see every scan; the map only those with a pose
  scan_.points_B = scan_points_in_base(scan, X_BS_);
  scan_.masts_M.clear();
  scan_.stamp = scan.header.stamp;
  scan_.have = true;
  scan_.sees_behind = looks_toward(scan, X_BS_, M_PI - 0.35) && looks_toward(scan, X_BS_, M_PI) && looks_toward(scan, X_BS_, M_PI + 0.35);
  const auto X_OB = pose_at(scan.header.stamp);
  if (!X_OB) return;
  // scans that contradict odometry (slipping wheels) would smear the map, unless the map
  // itself placed them; the last pose where odometry or the map and the laser agreed is
  // remembered for reversing blind
  const bool compared = slip_.add(scan, *X_OB * X_BS_);
  const bool matched = config_.scan_matching && stats_.scans > 0 && match_scan(*X_OB);
  const bool pinned = matched && loc_.last_match.verdict == MatchVerdict::good;
  if ((slip_.slipping() || slip_.last_misfit()) && !pinned) {
    ++stats_.slipping_scans;
    return;
  }
  const Pose2 X_MB = loc_.X_MO * *X_OB;
  if (compared || pinned || !loc_.trusted_X_MB) loc_.trusted_X_MB = X_MB;
  // a wall follower steers by the laser: its map may be drawn at map_period (half a
  // millisecond short of it counts, so a 0.5 s period at 10 Hz maps every fifth scan)
  const bool map_due = config_.map_period <= 0 || mode_ != ExplorerMode::wall_following || stats_.scans == 0 ||
                       (scan.header.stamp - scan_.last_mapped).seconds() >= config_.map_period - 5e-4;
  if (!map_due) {
    if (config_.post_radius > 0) find_masts(X_MB);
    return;
  }
  scan_.last_mapped = scan.header.stamp;
  const int learned = mapper_.integrate(scan, X_MB * X_BS_);
  if (config_.post_radius > 0) find_masts(X_MB);
  if (config_.look.enabled) {
    CameraFan fan = config_.look.fan;
    fan.near = std::max(fan.near, config_.robot_radius);
    looked_.look(mapper_, X_MB.position(), X_MB.yaw + loc_.camera_yaw, fan);
    looked_.cover_disc(mapper_, X_MB.position(), config_.robot_radius);
  }
  ++stats_.scans;
  stats_.cells_learned += learned;
  progress_.novelty.emplace_back(scan.header.stamp, learned);
  while (!progress_.novelty.empty() && (scan.header.stamp - progress_.novelty.front().first).seconds() > config_.novelty_window) {
    progress_.novelty.pop_front();
  }
}

void Explorer::find_masts(const Pose2& X_MB) {
  // a return of 1-3 map cells standing alone, not the end of a wall seen edge-on: few occupied
  // cells around it beyond its own
  constexpr double kOwn = 0.08, kAround = 0.3;
  constexpr int kMaxAround = 2;
  const double res = mapper_.resolution();
  const int reach = static_cast<int>(std::ceil(kAround / res));
  for (const Vec2& p_B : thin_returns(scan_.points_B, X_BS_.position(), config_.post_width, 0.3)) {
    const Vec2 p_M = X_MB.transform(p_B);
    const auto c = mapper_.world_to_cell(p_M);
    if (!c) continue;
    int around = 0;
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        const Cell n{c->x + dx, c->y + dy};
        const double d = res * std::hypot(dx, dy);
        if (d > kOwn && d <= kAround && mapper_.contains(n) && mapper_.is_occupied(n)) ++around;
      }
    }
    if (around <= kMaxAround) scan_.masts_M.push_back(p_M);
  }
  // plans keep a narrower berth than driving: enough to pass a robot standing in a corridor
  planner_.set_keep_out(scan_.masts_M, 0.6 * config_.post_radius);
}

msg::OccupancyGrid Explorer::map(SimTime stamp) const {
  if (mapper_.allocated()) return mapper_.to_message(config_.frame_id, stamp);
  msg::OccupancyGrid m;
  m.header = {stamp, config_.frame_id};
  m.map_load_time = stamp;
  m.resolution = static_cast<float>(mapper_.resolution());
  return m;
}

void Explorer::set_goal(const Vec2& p_M) {
  plan_.goal_M = p_M;
  enter(ExplorerMode::to_goal, std::nullopt);
}

void Explorer::clear_goal() {
  plan_.goal_M.reset();
  plan_.goal_needs_plan = false;
  enter(ExplorerMode::wall_following, std::nullopt);
}

void Explorer::enter(ExplorerMode mode, std::optional<SimTime> now) {
  const ExplorerMode from = std::exchange(mode_, mode);
  switch (mode) {
    case ExplorerMode::wall_following:
      follower_.clear();
      plan_.path_msg.poses.clear();
      plan_.tries = 0;
      if (now) {
        plan_.path_msg.header.stamp = *now;
        reset_progress(loc_.X_MO * loc_.odom.back().second, *now);
      } else {
        progress_.started = false;  // progress tracking restarts at the next command
      }
      break;
    case ExplorerMode::to_goal:
      // a goal trip begins with a plan, from wherever the robot stands
      plan_.goal_needs_plan = true;
      plan_.tries = 0;
      follower_.clear();
      plan_.path_msg.poses.clear();
      break;
    case ExplorerMode::to_frontier:
      // a frontier trip resumed after reversing keeps counting its stuck paths
      if (from != ExplorerMode::backing_up || reversing_.resume != ExplorerMode::to_frontier) plan_.tries = 0;
      break;
    case ExplorerMode::at_goal: break;
    case ExplorerMode::backing_up:
      RS_DEMAND(now.has_value(), "Explorer::enter: reversing starts at a command's sim time");
      reversing_.until = *now + SimTime::from_seconds(config_.backup_time);
      follower_.clear();
      plan_.path_msg.poses.clear();
      break;
  }
}

void Explorer::reset_progress(const Pose2& X_MB, SimTime now) {
  progress_.anchor = X_MB;
  progress_.anchor_time = now;
  progress_.since = now;
  progress_.blocked_times.clear();
}

msg::Twist Explorer::command(SimTime now) {
  if (loc_.odom.empty() || !scan_.have) return {};
  const Pose2 X_MB = loc_.X_MO * loc_.odom.back().second;
  if (!progress_.started) {
    reset_progress(X_MB, now);
    progress_.started = true;
  }
  // progress: any move of stuck_distance from the anchor restarts the stuck clock
  if ((X_MB.position() - progress_.anchor.position()).norm() > config_.stuck_distance) {
    progress_.anchor = X_MB;
    progress_.anchor_time = now;
  }
  switch (mode_) {
    case ExplorerMode::wall_following: return wall_follow(X_MB, now);
    case ExplorerMode::to_frontier: return drive_to_frontier(X_MB, now);
    case ExplorerMode::to_goal: return drive_to_goal(X_MB, now);
    case ExplorerMode::at_goal: return {};
    case ExplorerMode::backing_up: return back_up(X_MB, now);
  }
  return {};
}

bool Explorer::wheels_slipping() const { return slip_.slipping() || match_slip_.slipping(); }

StuckReason Explorer::stuck_reason(SimTime now) const {
  if ((now - progress_.anchor_time).seconds() > config_.stuck_window || wheels_slipping()) return StuckReason::no_progress;
  if (static_cast<int>(progress_.blocked_times.size()) >= config_.blocked_limit) return StuckReason::blocked;
  // looping: a whole novelty window of wall following that taught the map almost nothing
  if ((now - progress_.since).seconds() >= config_.novelty_window) {
    int learned = 0;
    for (const auto& [stamp, cells] : progress_.novelty) {
      if ((now - stamp).seconds() <= config_.novelty_window) learned += cells;
    }
    const double cell_area = mapper_.resolution() * mapper_.resolution();
    if (learned * cell_area < config_.novelty_min_area) return StuckReason::looping;
  }
  return StuckReason::none;
}

bool Explorer::may_plan(SimTime now) const { return !plan_.planned || (now - plan_.last_plan).seconds() >= config_.replan_period; }

std::vector<Vec2> Explorer::plan_frontier(const Pose2& X_MB, SimTime now) {
  plan_.planned = true;
  plan_.last_plan = now;
  ++stats_.plans;
  // the targets: frontiers, and with the camera's view tracked, free ground it has not seen.
  // Frontiers where a teammate has looked are left to it while there is anything else; when
  // there is nothing else they are this robot's too, unless the teammate has mapped what lies
  // beyond them: a robot that thinks it is done idles.
  // A frontier a teammate's laser has mapped beyond (its map, shared over the radio) is no
  // target at all.
  bool team_frontiers = false;
  const auto is_target = [this, &team_frontiers](Cell c) {
    return (open_frontier(c) && (team_frontiers || !looked_.looked_by_team(c))) || unseen(c);
  };
  const auto min_cells = [this](Cell c) {
    return is_frontier(mapper_, c) ? config_.planner.min_frontier_cells : config_.look.min_cells;
  };
  const auto plan = [&](const std::vector<Vec2>& claims) {
    return config_.look.enabled || !team_.map.empty()
               ? planner_.plan_to_nearest_target(mapper_, X_MB.position(), is_target, min_cells, plan_.excluded_M, claims)
               : planner_.plan_to_nearest_frontier(mapper_, X_MB.position(), plan_.excluded_M, claims);
  };
  // targets teammates have not claimed first; any target when they claimed them all
  std::vector<Vec2> path;
  if (!team_.claims_M.empty()) path = plan(team_.claims_M);
  if (path.empty()) path = plan({});
  // (a third search only when a teammate's squares could have hidden anything: alone, it would
  // repeat the second)
  if (path.empty() && team_.seen) {
    team_frontiers = true;
    path = plan({});
    if (!path.empty()) ++stats_.team_frontier_trips;
  }
  plan_.team_frontier_target = team_frontiers;
  if (!path.empty()) {
    const auto end = mapper_.world_to_cell(path.back());
    if (end && !is_frontier(mapper_, *end)) ++stats_.look_trips;
  }
  return path;
}

bool Explorer::unseen(Cell c) const { return config_.look.enabled && mapper_.is_free(c) && !looked_.looked(c); }

bool Explorer::open_frontier(Cell c) const {
  if (!is_frontier(mapper_, c)) return false;
  if (team_.map.empty()) return true;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const Cell n{c.x + dx, c.y + dy};
      if (mapper_.contains(n) && mapper_.is_unknown(n) && !team_mapped(n)) return true;
    }
  }
  return false;
}

void Explorer::add_team_map(const std::vector<std::pair<Vec2, CellState>>& squares_M, double cell) {
  if (!mapper_.allocated() || !(cell > 0)) return;
  const std::size_t cells = static_cast<std::size_t>(mapper_.width()) * static_cast<std::size_t>(mapper_.height());
  if (team_.map.size() != cells) team_.map.assign(cells, CellState::unknown);
  const double half = cell / 2, res = mapper_.resolution();
  for (const auto& [p, state] : squares_M) {
    if (state == CellState::unknown) continue;
    // the cells whose centres lie in the square (its sides along the map's axes: the squares
    // are the world's, and a start turned by other than a quarter turn only shifts them a little)
    const Vec2 lo = (p - Vec2(half, half) - mapper_.origin()) / res, hi = (p + Vec2(half, half) - mapper_.origin()) / res;
    if (!lo.allFinite() || !hi.allFinite() || hi.x() < 0 || hi.y() < 0 || lo.x() >= mapper_.width() || lo.y() >= mapper_.height()) continue;
    const int x0 = static_cast<int>(std::max(0.0, std::ceil(lo.x() - 0.5))), y0 = static_cast<int>(std::max(0.0, std::ceil(lo.y() - 0.5)));
    const int x1 = static_cast<int>(std::min<double>(mapper_.width() - 1, std::floor(hi.x() - 0.5)));
    const int y1 = static_cast<int>(std::min<double>(mapper_.height() - 1, std::floor(hi.y() - 0.5)));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        CellState& t = team_.map[static_cast<std::size_t>(mapper_.index({x, y}))];
        if (t == CellState::unknown) ++stats_.team_mapped_cells;
        // a wall one teammate saw stays a wall when another saw free ground there
        if (t != CellState::occupied) t = state;
      }
    }
  }
}

void Explorer::add_team_seen(const std::vector<Vec2>& centres_M, double cell) {
  if (!config_.look.enabled || !mapper_.allocated() || !(cell > 0)) return;
  for (const Vec2& p : centres_M) team_.seen = looked_.mark_team_square(mapper_, p, cell / 2) > 0 || team_.seen;
}

bool Explorer::still_frontier(const Vec2& p_M) const {
  const auto c = mapper_.world_to_cell(p_M);
  if (!c) return false;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      const Cell n{c->x + dx, c->y + dy};
      if (!mapper_.contains(n)) continue;
      if ((open_frontier(n) && (plan_.team_frontier_target || !looked_.looked_by_team(n))) || unseen(n)) return true;
    }
  }
  return false;
}

void Explorer::start_path(std::vector<Vec2> path, SimTime now) {
  plan_.target_M = path.back();
  // a new path is judged on fresh evidence: a slip verdict only changes while odometry claims
  // motion, so one kept from before would hold a robot that stopped for it still for good
  slip_.reset();
  match_slip_.reset();
  // the path message: each pose faces the next point
  plan_.path_msg.header = {now, config_.frame_id};
  plan_.path_msg.poses.clear();
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Vec2 d = i + 1 < path.size() ? Vec2(path[i + 1] - path[i]) : (i > 0 ? Vec2(path[i] - path[i - 1]) : Vec2(1, 0));
    msg::PoseStamped p;
    p.header = plan_.path_msg.header;
    p.pose = Pose3::from_pose2({path[i].x(), path[i].y(), std::atan2(d.y(), d.x())});
    plan_.path_msg.poses.push_back(p);
  }
  follower_.set_path(std::move(path), now);
}

msg::Twist Explorer::wall_follow(const Pose2& X_MB, SimTime now) {
  const msg::Twist twist = wall_.command(scan_.points_B, scan_.stamp);
  // count blocked episodes (their starts) within the window
  if (wall_.state() == WallFollowerState::blocked && progress_.last_wall_state != WallFollowerState::blocked) {
    progress_.blocked_times.push_back(now);
  }
  progress_.last_wall_state = wall_.state();
  while (!progress_.blocked_times.empty() && (now - progress_.blocked_times.front()).seconds() > config_.blocked_window) {
    progress_.blocked_times.pop_front();
  }

  // stuck: plan a trip to new terrain (at most once per replan period)
  // frontier first: look for a trip whenever the planner may run
  const StuckReason reason = config_.frontier_trips ? stuck_reason(now) : StuckReason::none;
  const bool eager = config_.frontier_trips && config_.frontier_first;
  if ((reason == StuckReason::none && !eager) || !may_plan(now)) return twist;
  if (reason != StuckReason::none) {
    progress_.last_stuck = reason;
    if (reason == StuckReason::no_progress) ++stats_.stuck_no_progress;
    if (reason == StuckReason::blocked) ++stats_.stuck_blocked;
    if (reason == StuckReason::looping) ++stats_.stuck_looping;
    if (reason == StuckReason::no_progress && start_backup(ExplorerMode::wall_following, now)) return back_up(X_MB, now);
  }
  std::vector<Vec2> path = plan_frontier(X_MB, now);
  // an eager look that found nothing leaves the stuck clocks of wall following running
  if (reason != StuckReason::none || !path.empty()) reset_progress(X_MB, now);
  if (path.empty()) {
    if (reason != StuckReason::none) ++stats_.no_frontier;
    plan_.complete = true;
    return twist;
  }
  plan_.complete = false;
  ++stats_.frontier_trips;
  enter(ExplorerMode::to_frontier, now);
  start_path(std::move(path), now);
  return follow_path(X_MB, now);
}

msg::Twist Explorer::drive_to_frontier(const Pose2& X_MB, SimTime now) {
  // arrived: new terrain is in view, back to wall following; a frontier that is still one
  // after arriving cannot be resolved from here and is not visited again
  if (follower_.status() == PathStatus::reached) {
    ++stats_.frontiers_reached;
    if (still_frontier(plan_.target_M)) plan_.excluded_M.push_back(plan_.target_M);
    enter(ExplorerMode::wall_following, now);
    return wall_follow(X_MB, now);
  }
  // replan (at most once per replan period) when stuck on the path, when the target was
  // explored on the way, or when the map shows an obstacle on what is left of the path;
  // a frontier whose paths got stuck max_tries times is given up
  const bool stuck = follower_.status() == PathStatus::stuck || wheels_slipping();
  if (!may_plan(now)) return stuck ? msg::Twist{} : follow_path(X_MB, now);
  if (stuck) {
    ++stats_.path_stuck;
    if (++plan_.tries >= config_.max_tries) {
      ++stats_.abandoned;
      plan_.excluded_M.push_back(plan_.target_M);
      enter(ExplorerMode::wall_following, now);
      return wall_follow(X_MB, now);
    }
    if (start_backup(ExplorerMode::to_frontier, now)) return back_up(X_MB, now);
  } else if (still_frontier(plan_.target_M)) {
    if (!due_for_check(now) || !path_ahead_blocked(X_MB)) return follow_path(X_MB, now);
    ++stats_.path_blocked;
  }
  std::vector<Vec2> path = plan_frontier(X_MB, now);
  if (path.empty()) {
    enter(ExplorerMode::wall_following, now);
    return wall_follow(X_MB, now);
  }
  start_path(std::move(path), now);
  return follow_path(X_MB, now);
}

msg::Twist Explorer::drive_to_goal(const Pose2& X_MB, SimTime now) {
  if (follower_.status() == PathStatus::reached) {
    enter(ExplorerMode::at_goal, now);
    return {};
  }
  // plan on request; replan (at most once per replan period) when there is no path, when
  // stuck, when the map shows an obstacle on the path, and every goal_replan_period as the
  // map grows
  const bool stuck = follower_.status() == PathStatus::stuck || wheels_slipping();
  const bool no_path = follower_.status() == PathStatus::idle;
  if (!plan_.goal_needs_plan) {
    if (!may_plan(now)) return stuck ? msg::Twist{} : follow_path(X_MB, now);
    if (stuck) {
      ++stats_.path_stuck;
      if (start_backup(ExplorerMode::to_goal, now)) return back_up(X_MB, now);
    } else if (!no_path && (now - plan_.last_plan).seconds() < config_.goal_replan_period) {
      if (!due_for_check(now) || !path_ahead_blocked(X_MB)) return follow_path(X_MB, now);
      ++stats_.path_blocked;
    }
  }
  plan_.goal_needs_plan = false;
  plan_.planned = true;
  plan_.last_plan = now;
  ++stats_.plans;
  std::vector<Vec2> path = planner_.plan(mapper_, X_MB.position(), *plan_.goal_M);
  if (path.empty()) {
    // unreachable on the map so far: stand still and try again later
    follower_.clear();
    plan_.path_msg.poses.clear();
    return {};
  }
  path.back() = *plan_.goal_M;  // end on the goal itself rather than its cell's centre
  start_path(std::move(path), now);
  return follow_path(X_MB, now);
}

bool Explorer::due_for_check(SimTime now) {
  if ((now - plan_.last_check).seconds() < config_.replan_period) return false;
  plan_.last_check = now;
  return true;
}

bool Explorer::path_ahead_blocked(const Pose2& X_MB) const {
  return path_blocked(mapper_, follower_.path(), follower_.next_index(), X_MB.position(),
                      config_.blocked_clearance_factor * config_.robot_radius);
}

bool Explorer::rear_clear(double distance) const {
  // the laser, when it looks behind
  if (scan_.sees_behind) return free_distance_along(scan_.points_B, M_PI, config_.robot_radius) >= distance;
  // else the map: every cell the robot would sweep reversing must be known free, seen from
  // the last pose odometry and laser agreed on, with room for the drift since then
  if (!mapper_.allocated() || !loc_.trusted_X_MB) return false;
  const Pose2& X_MB = *loc_.trusted_X_MB;
  distance += config_.slip.min_motion;
  const double reach = config_.robot_radius + mapper_.resolution();
  for (double back = 0; back <= distance + 1e-9; back += mapper_.resolution()) {
    for (double side = -reach; side <= reach + 1e-9; side += mapper_.resolution()) {
      for (double ahead = -reach; ahead <= reach + 1e-9; ahead += mapper_.resolution()) {
        if (std::hypot(side, ahead) > reach) continue;
        const auto c = mapper_.world_to_cell(X_MB.transform(Vec2(ahead - back, side)));
        if (!c || !mapper_.is_free(*c)) return false;
      }
    }
  }
  return true;
}

bool Explorer::start_backup(ExplorerMode resume, SimTime now) {
  // only when the way back is clear (seen by the laser, or known free on the map)
  if (reversing_.until && (now - *reversing_.until).seconds() < config_.backup_cooldown) return false;
  if (!rear_clear(std::max(config_.backup_clearance, config_.backup_speed * config_.backup_time))) return false;
  ++stats_.backups;
  reversing_.resume = resume;
  enter(ExplorerMode::backing_up, now);
  return true;
}

msg::Twist Explorer::back_up(const Pose2& X_MB, SimTime now) {
  // reverse for a moment (stopping short of anything the laser sees behind), then find a way
  // on: the goal again, or the nearest frontier (wall following when there is none)
  if (now < *reversing_.until && (!scan_.sees_behind || free_distance_along(scan_.points_B, M_PI, config_.robot_radius) > 0.1)) {
    msg::Twist twist;
    twist.linear.x() = -config_.backup_speed;
    return twist;
  }
  reset_progress(X_MB, now);
  slip_.reset();  // fresh evidence before calling it slipping again
  match_slip_.reset();
  reversing_.until = now;
  if (reversing_.resume == ExplorerMode::to_goal) {
    enter(ExplorerMode::to_goal, now);
    return drive_to_goal(X_MB, now);
  }
  std::vector<Vec2> path = plan_frontier(X_MB, now);
  plan_.complete = path.empty();
  if (path.empty()) {
    ++stats_.no_frontier;
    enter(ExplorerMode::wall_following, now);
    return wall_.command(scan_.points_B, scan_.stamp);
  }
  ++stats_.frontier_trips;
  enter(ExplorerMode::to_frontier, now);
  start_path(std::move(path), now);
  return follow_path(X_MB, now);
}

msg::Twist Explorer::follow_path(const Pose2& X_MB, SimTime now) {
  msg::Twist twist = follower_.command(X_MB, now);
  // the laser overrules the map: slow, then stop forward motion, when something is close
  // ahead; another robot counts as the outline of the disc around its mast
  double ahead = free_distance_ahead(scan_.points_B, config_.robot_radius);
  if (!scan_.masts_M.empty()) {
    constexpr int kOutline = 16;
    std::vector<ScanPoint> outline;
    const Pose2 X_BM = X_MB.inverse();
    for (const Vec2& c_M : scan_.masts_M) {
      for (int k = 0; k < kOutline; ++k) {
        const double a = 2 * M_PI * k / kOutline;
        ScanPoint p;
        p.p_B = X_BM.transform(c_M + config_.post_radius * Vec2(std::cos(a), std::sin(a)));
        outline.push_back(p);
      }
    }
    ahead = std::min(ahead, free_distance_ahead(outline, config_.robot_radius));
  }
  const double span = std::max(config_.safety_slow_distance - config_.safety_stop_distance, 1e-6);
  const double scale = std::clamp((ahead - config_.safety_stop_distance) / span, 0.0, 1.0);
  twist.linear.x() = std::min(twist.linear.x(), scale * config_.path.max_linear);
  return twist;
}

}  // namespace rescuesim::autonomy
