#include "session/terrain_trial.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/rng.h"
#include "sim/simulation.h"
#include "viz/world_plot.h"
#include "world/terrain.h"
#include "world/world.h"

namespace rescuesim {

namespace {

constexpr double kDeg = M_PI / 180.0;

/// A point of the lane's frame (u along the direction of travel from the element's centre, v
/// across it, to the left) in the world.
Vec2 lane_point(const TerrainSpec& lane, double u, double v) {
  const double c = std::cos(lane.pose.yaw), s = std::sin(lane.pose.yaw);
  return {lane.pose.x + c * u - s * v, lane.pose.y + s * u + c * v};
}

/// The lane's element (find_terrain_lane), or an Error saying what the world has.
const TerrainSpec& find_lane(const WorldSpec& world, const std::string& lane) {
  if (const TerrainSpec* t = find_terrain_lane(world, lane)) return *t;
  std::string known;
  for (const auto& t : world.terrain) known += (known.empty() ? "" : ", ") + t.name + " (" + TerrainSpec::kind_name(t.kind) + ")";
  throw Error("no lane '" + lane + "' in world '" + world.name + "'; it has " +
              (known.empty() ? std::string("no terrain elements") : known));
}

/// Where a lap ends, in metres along the lane from its start line: the end line, `approach`
/// beyond the element, or, for stairs, which end in a landing with a drop beyond it, on the
/// landing 0.5 m short of its far edge.
double lane_goal(const TerrainSpec& lane, const TerrainTrialOptions& o) {
  if (lane.kind == TerrainSpec::Kind::stairs) return o.approach + lane.length - 0.5;
  return 2 * o.approach + lane.length;
}

/// Roll and pitch (rad) of a body frame: pitch nose up positive.
void roll_pitch(const Quat& q, double& roll, double& pitch) {
  const Vec3 x = q * Vec3::UnitX(), y = q * Vec3::UnitY();
  pitch = std::asin(std::clamp(x.z(), -1.0, 1.0));
  roll = std::asin(std::clamp(y.z(), -1.0, 1.0));
  if ((q * Vec3::UnitZ()).z() < 0) {  // upside down: past 90 degrees
    pitch = std::copysign(M_PI - std::abs(pitch), pitch == 0 ? 1.0 : pitch);
    roll = std::copysign(M_PI - std::abs(roll), roll == 0 ? 1.0 : roll);
  }
}

/// The scripted driver: along the lane's centre line at the trial's speed, heading and offset
/// corrected; flippers (when the robot has them) raised to meet an obstacle, lowered onto it once
/// the nose is up (the way the tests climb stairs), lowered ahead of the robot when it tips nose
/// down, so it comes down on them.
class LaneDriver {
 public:
  LaneDriver(const TerrainSpec& lane, const RobotSpec& robot, const TerrainTrialOptions& o) : lane_(lane), robot_(robot), o_(o) {}

  /// Forward along the lane, or (reverse) backwards along it, facing the same way: backing up,
  /// a turn moves the robot across the lane the other way, so the offset term changes sign.
  msg::Twist twist(const Pose3& X, bool reverse = false) const {
    const double across = in_lane(X).y();
    const double heading = std::remainder(X.yaw() - lane_.pose.yaw, 2 * M_PI);
    msg::Twist t;
    t.linear.x() = reverse ? -o_.speed : o_.speed;
    t.angular.z() = std::clamp(-2.0 * heading + (reverse ? 2.5 : -2.5) * across, -0.8, 0.8);
    return t;
  }

  /// Flipper targets for the pitch now (rad, nose up positive), or empty when they stay.
  std::vector<double> flippers(double pitch) {
    if (robot_.flipper_joints.empty()) return {};
    double want = mode_;
    if (pitch > 0.3) want = 0.2;         // nose up: lay them on what it climbs
    else if (pitch < -0.3) want = 0.5;   // nose down: reach for the ground ahead
    else if (std::abs(pitch) < 0.1) want = -0.6;  // level: raised, ready for the next obstacle
    if (want == mode_ && started_) return {};
    mode_ = want;
    started_ = true;
    return std::vector<double>(robot_.flipper_joints.size(), want);
  }

  /// Metres along the lane from its start line.
  double along(const Pose3& X) const { return in_lane(X).x() + 0.5 * lane_.length + o_.approach; }

 private:
  /// The base's position in the lane's frame: x along the direction of travel from the
  /// element's centre, y across it.
  Vec2 in_lane(const Pose3& X) const {
    const Vec2 d = X.p.head<2>() - Vec2(lane_.pose.x, lane_.pose.y);
    const double c = std::cos(lane_.pose.yaw), s = std::sin(lane_.pose.yaw);
    return {c * d.x() + s * d.y(), -s * d.x() + c * d.y()};
  }

  const TerrainSpec& lane_;
  const RobotSpec& robot_;
  const TerrainTrialOptions& o_;
  double mode_ = -0.6;
  bool started_ = false;
};

/// A simulation with the robot on the lane's start line, up to start_offset off its centre line
/// and start_yaw turned (drawn from `rng`), run seed `seed`.
Simulation start_on_lane(const WorldSpec& base, const std::map<std::string, RobotSpec>& models, const TerrainSpec& lane,
                         const TerrainTrialOptions& o, std::uint64_t seed, Rng& rng) {
  WorldSpec spec = base;
  const double offset = rng.uniform(-o.start_offset, o.start_offset);
  const double yaw = rng.uniform(-o.start_yaw, o.start_yaw) * kDeg;
  const double back = 0.5 * lane.length + o.approach;  // the start line, behind the element's centre
  RobotPlacement r;
  r.name = "robot";
  r.model = o.robot;
  const Vec2 at = lane_point(lane, -back, offset);
  r.start = {at.x(), at.y(), lane.pose.yaw + yaw};
  spec.robots = {r};
  spec.victims.clear();
  SimOptions so;
  so.seed = seed;
  return Simulation(compile_world(spec, models), so);
}

/// What one leg of a trial (a crossing, a figure-eight) asks of the loop that drives it: the
/// twist now, the progress made (m, in the leg's own measure), and whether it is done.
struct Leg {
  std::function<msg::Twist(const Pose3&)> twist;
  std::function<double(const Pose3&)> progress;
  std::function<bool(const Pose3&)> done;
};

/// Drives one leg from where the robot is, watching for falls (pitch or roll beyond the
/// limits), being stuck (no 5 cm of progress in stuck_time) and time-outs, with the flippers
/// worked by `driver`. `floor_z` is the base's height when standing on the floor.
TerrainLap drive_leg(Simulation& sim, LaneDriver& driver, const TerrainTrialOptions& o, int lap, bool reverse, double floor_z,
                     const Leg& leg) {
  const RobotSpec& robot = sim.world().robots[0].spec;
  const double t0 = sim.time().seconds();
  TerrainLap out;
  out.lap = lap;
  out.reverse = reverse;
  double best = 0, best_at = 0;
  const long steps = std::lround(o.time_limit / sim.dt());
  for (long i = 0;; ++i) {
    const Pose3& X = sim.state().robots[0].base.X_WB;
    const double t = sim.time().seconds() - t0;
    double roll = 0, pitch = 0;
    roll_pitch(X.q, roll, pitch);
    out.max_pitch = std::max(out.max_pitch, std::abs(pitch) / kDeg);
    out.max_roll = std::max(out.max_roll, std::abs(roll) / kDeg);
    out.max_height = std::max(out.max_height, X.p.z() - floor_z);
    if (i % std::max<long>(1, std::lround(0.1 / sim.dt())) == 0) out.path.push_back(X.p.head<2>());
    const double gone = leg.progress(X);
    if (gone > best + 0.05) best = gone, best_at = t;
    out.progress = std::max(out.progress, gone);
    out.time = t;
    if (leg.done(X)) {
      out.outcome = "completed";
      break;
    }
    if (std::abs(pitch) > o.fall_pitch * kDeg || std::abs(roll) > o.fall_roll * kDeg) {
      out.outcome = "fell";
      break;
    }
    if (t - best_at > o.stuck_time) {
      out.outcome = "stuck";
      break;
    }
    if (i >= steps || sim.in_trouble()) {
      out.outcome = "timeout";
      break;
    }
    sim.command_velocity(RobotIndex(0), leg.twist(X));
    if (const std::vector<double> f = driver.flippers(pitch); !f.empty()) {
      msg::JointState js;
      js.name = robot.flipper_joints;
      js.position = f;
      sim.command_joints(RobotIndex(0), js);
    }
    sim.step();
  }
  out.path.push_back(sim.state().robots[0].base.X_WB.p.head<2>());
  return out;
}

/// One crossing of the lane from where the robot is: forward to the end line, or (reverse)
/// backwards to the start line. Progress is measured in the direction of travel from where the
/// crossing began (forward: from the start line); time from the crossing's start.
TerrainLap drive_lap(Simulation& sim, LaneDriver& driver, const TerrainSpec& lane, const TerrainTrialOptions& o, int lap, bool reverse,
                     double floor_z) {
  const double goal = lane_goal(lane, o);
  const double from = driver.along(sim.state().robots[0].base.X_WB);
  Leg leg;
  leg.twist = [&](const Pose3& X) { return driver.twist(X, reverse); };
  leg.progress = [&](const Pose3& X) { return reverse ? from - driver.along(X) : driver.along(X); };
  leg.done = [&](const Pose3& X) { return reverse ? driver.along(X) <= 0 : driver.along(X) >= goal; };
  return drive_leg(sim, driver, o, lap, reverse, floor_z, leg);
}

/// The figure-eight on an element (docs/terrain.md, "Figure-eights"): two pylons on its centre
/// line, a quarter of its length in from each end, and a loop of radius r around each, clockwise
/// around the far pylon and anticlockwise around the near one, the two joined by diagonals that
/// cross at the element's centre. r is half the element's width less 0.7 m (room for a robot
/// with its flippers raised, 1.2 m long, to turn onto the loop without its nose in the wall), at
/// least 0.3 m and at most a quarter of the length: 0.5 m on the test methods' 2.4 m wide
/// figure-8 apparatus; in a 1.2 m lane the loops are tighter than a robot can follow. Points are
/// in the lane's frame (x along the lane from the element's centre, y to the left).
struct EightGeometry {
  double a = 0, r = 0;          ///< pylons at x = -a and +a; loop radius
  std::vector<Vec2> eight;      ///< one figure-eight from the centre back to it

  explicit EightGeometry(const TerrainSpec& lane) {
    a = 0.25 * lane.length;
    r = std::clamp(0.5 * lane.width - 0.7, 0.3, a);
    const auto loop = [&](double cx, double from_deg, double to_deg) {
      for (int k = 0; k <= 36; ++k) {  // every 5 degrees
        const double t = (from_deg + (to_deg - from_deg) * k / 36.0) * kDeg;
        eight.push_back({cx + r * std::cos(t), r * std::sin(t)});
      }
    };
    loop(+a, 90, -90);   // around the far pylon, clockwise: left side, far end, right side
    eight.push_back({0, 0});
    loop(-a, 90, 270);   // around the near pylon, anticlockwise: left side, near end, right side
    eight.push_back({0, 0});
  }

  /// The figure-eight's path length from the centre back to it (m): four diagonals from the
  /// centre to the loops' sides and two half circles.
  double length() const { return 2 * (2 * std::hypot(a, r) + M_PI * r); }
};

/// Follows a path (the polyline through `corners`, in the world, from where the robot stands)
/// by pure pursuit: it steers along the arc to the point kLookahead further along the path than
/// its nearest point, at the trial's speed slowed by the cosine of the heading error and to what
/// its turn rate allows on that arc (|omega| <= kMaxTurn: 0.4 m/s on a 0.5 m loop), and turns in
/// place when that point lies more than 90 degrees off. The nearest point is looked for only a
/// short way ahead of the last one (kSearch), so that where the path crosses itself (a
/// figure-eight's centre) the robot keeps to the leg it is on. When it has made no 5 cm of
/// progress for 3 s (a track against a post), it backs up for 1.5 s, straight, and tries again,
/// as an operator would. Progress is the path length up to the nearest point; the path is done
/// when that is its end and the robot stands within 0.15 m of it (0.1 m more after each
/// back-off, up to 0.35 m).
class PathFollower {
 public:
  PathFollower(const std::vector<Vec2>& corners, Vec2 from, double speed, double dt) : speed_(speed), dt_(dt) {
    path_.push_back(from);
    arc_.push_back(0);
    for (const Vec2& c : corners) {
      const Vec2 a = path_.back();
      const double l = (c - a).norm();
      const int n = std::max(1, static_cast<int>(std::ceil(l / kSpacing)));
      for (int k = 1; k <= n; ++k) {
        path_.push_back(a + (c - a) * (static_cast<double>(k) / n));
        arc_.push_back(arc_.back() + l / n);
      }
    }
  }

  /// The twist for the next step (called once per step).
  msg::Twist twist(const Pose3& X) {
    advance(X);
    msg::Twist t;
    if (finished(X)) return t;
    now_ += dt_;
    if (arc_[near_] > best_ + 0.05) best_ = arc_[near_], best_at_ = now_;
    if (now_ >= backing_until_ && now_ - best_at_ > kRetryAfter) backing_until_ = now_ + kBackUp, best_at_ = now_ + kBackUp, ++retries_;
    if (now_ < backing_until_) {
      t.linear.x() = -speed_;
      return t;
    }
    std::size_t aim = near_;
    while (aim + 1 < path_.size() && arc_[aim] < arc_[near_] + kLookahead) ++aim;
    const Vec2 d = path_[aim] - X.p.head<2>();
    const double e = std::remainder(std::atan2(d.y(), d.x()) - X.yaw(), 2 * M_PI);
    if (std::abs(e) > M_PI / 2) {
      t.angular.z() = std::copysign(kMaxTurn, e);
      return t;
    }
    const double curvature = 2 * std::sin(e) / std::max(d.norm(), 0.05);
    double v = speed_ * std::cos(e);
    if (std::abs(v * curvature) > kMaxTurn) v = kMaxTurn / std::abs(curvature);
    t.linear.x() = v;
    t.angular.z() = v * curvature;
    return t;
  }
  double progress(const Pose3& X) {
    advance(X);
    return arc_[near_];
  }
  bool done(const Pose3& X) {
    advance(X);
    return finished(X);
  }

 private:
  static constexpr double kSpacing = 0.05, kLookahead = 0.35, kSearch = 0.6;  // m
  static constexpr double kMaxTurn = 0.8;                                       // rad/s
  static constexpr double kRetryAfter = 3.0, kBackUp = 1.5;                     // s
  static constexpr double kReach = 0.15, kReachPerRetry = 0.1, kReachMax = 0.35;  // m

  void advance(const Pose3& X) {
    const Vec2 p = X.p.head<2>();
    std::size_t best = near_;
    for (std::size_t k = near_; k < path_.size() && arc_[k] <= arc_[near_] + kSearch; ++k) {
      if ((path_[k] - p).squaredNorm() < (path_[best] - p).squaredNorm()) best = k;
    }
    near_ = best;
  }
  bool finished(const Pose3& X) const {
    return near_ + 1 == path_.size() && (path_.back() - X.p.head<2>()).norm() < std::min(kReach + kReachPerRetry * retries_, kReachMax);
  }
  std::vector<Vec2> path_;
  std::vector<double> arc_;  ///< path length up to each point (m)
  double speed_, dt_;
  std::size_t near_ = 0;
  double now_ = 0, best_ = 0, best_at_ = 0, backing_until_ = -1;
  int retries_ = 0;  ///< back-offs so far
};

/// Follows lane-frame points as one leg.
TerrainLap drive_points(Simulation& sim, LaneDriver& driver, const TerrainSpec& lane, const TerrainTrialOptions& o, int lap, double floor_z,
                        const std::vector<Vec2>& in_lane) {
  std::vector<Vec2> world;
  for (const Vec2& p : in_lane) world.push_back(lane_point(lane, p.x(), p.y()));
  PathFollower follow(world, sim.state().robots[0].base.X_WB.p.head<2>(), o.speed, sim.dt());
  Leg leg;
  leg.twist = [&](const Pose3& X) { return follow.twist(X); };
  leg.progress = [&](const Pose3& X) { return follow.progress(X); };
  leg.done = [&](const Pose3& X) { return follow.done(X); };
  return drive_leg(sim, driver, o, lap, false, floor_z, leg);
}

/// Mixes the final State of one of a trial's simulations into the trial's hash (in the order
/// they run).
void mix_state(std::uint64_t& hash, const Simulation& sim) { hash = (hash ^ state_hash(sim.state())) * 0x100000001b3ULL; }

/// One lap of the `laps` pattern: a fresh simulation, from the start line to the end line.
TerrainLap run_lap(const WorldSpec& base, const std::map<std::string, RobotSpec>& models, const TerrainSpec& lane,
                   const TerrainTrialOptions& o, int lap, Rng& rng, TerrainTrialResult& result) {
  Simulation sim = start_on_lane(base, models, lane, o, o.seed + static_cast<std::uint64_t>(lap), rng);
  LaneDriver driver(lane, sim.world().robots[0].spec, o);
  TerrainLap out = drive_lap(sim, driver, lane, o, lap, false, sim.state().robots[0].base.X_WB.p.z());
  result.sim_time += sim.time().seconds();
  mix_state(result.state_hash, sim);
  return out;
}

}  // namespace

TerrainTrialResult run_terrain_trial(const WorldSpec& world, const std::map<std::string, RobotSpec>& models,
                                     const TerrainTrialOptions& options, const std::function<void(const TerrainLap&)>& progress) {
  if (!models.count(options.robot)) {
    std::string known;
    for (const auto& [name, m] : models) known += (known.empty() ? "" : ", ") + name;
    throw Error("unknown robot '" + options.robot + "' (known: " + known + ")");
  }
  if (options.laps < 1) throw Error("laps " + std::to_string(options.laps) + " is not positive");
  if (!(options.speed > 0) || !(options.time_limit > 0) || !(options.stuck_time > 0)) {
    throw Error("speed, time limit and stuck time must be positive");
  }
  TerrainTrialResult result;
  result.element = find_lane(world, options.lane);
  check_terrain_pattern(result.element, options.pattern);
  result.robot = options.robot;
  result.options = options;
  Rng rng(options.seed, "terrain_trial");
  result.state_hash = 0xcbf29ce484222325ULL;
  double total = 0;
  const auto count = [&](TerrainLap l) {
    if (l.outcome == "completed") ++result.repetitions, total += l.time;
    if (l.outcome == "fell") ++result.falls;
    if (l.outcome == "stuck") ++result.stuck;
    if (l.outcome == "timeout") ++result.timeouts;
    if (progress) progress(l);
    result.laps.push_back(std::move(l));
  };
  if (options.pattern == TerrainPattern::laps) {
    for (int lap = 1; lap <= options.laps; ++lap) count(run_lap(world, models, result.element, options, lap, rng, result));
  } else if (options.pattern == TerrainPattern::figure_eight) {
    // in from the start line to the element's centre (not a repetition; a failure there is lap
    // 1's), then figure-eights without a reset until the repetitions asked for or the first that fails
    const TerrainSpec& lane = result.element;
    const EightGeometry g(lane);
    for (double x : {-g.a, g.a}) result.pylons.push_back(lane_point(lane, x, 0));
    result.loop_radius = g.r;
    result.eight_length = g.length();
    Simulation sim = start_on_lane(world, models, lane, options, options.seed + 1, rng);
    LaneDriver driver(lane, sim.world().robots[0].spec, options);
    const double floor_z = sim.state().robots[0].base.X_WB.p.z();
    // the entry is driven as a lap is, along the centre line to the element's centre
    Leg in;
    in.twist = [&](const Pose3& X) { return driver.twist(X); };
    in.progress = [&](const Pose3& X) { return driver.along(X); };
    in.done = [&](const Pose3& X) { return driver.along(X) >= options.approach + 0.5 * lane.length; };
    TerrainLap entry = drive_leg(sim, driver, options, 1, false, floor_z, in);
    if (entry.outcome != "completed") {
      count(std::move(entry));
    } else {
      for (int lap = 1; lap <= options.laps; ++lap) {
        TerrainLap l = drive_points(sim, driver, lane, options, lap, floor_z, g.eight);
        if (lap == 1) l.path.insert(l.path.begin(), entry.path.begin(), entry.path.end());
        count(std::move(l));
        if (result.laps.back().outcome != "completed") break;
      }
    }
    result.sim_time = sim.time().seconds();
    mix_state(result.state_hash, sim);
  } else {
    // back and forth without a reset: odd crossings forward to the end line, even ones backwards
    // to the start line, until the repetitions asked for or the first that fails
    Simulation sim = start_on_lane(world, models, result.element, options, options.seed + 1, rng);
    LaneDriver driver(result.element, sim.world().robots[0].spec, options);
    const double floor_z = sim.state().robots[0].base.X_WB.p.z();
    for (int lap = 1; lap <= options.laps; ++lap) {
      count(drive_lap(sim, driver, result.element, options, lap, lap % 2 == 0, floor_z));
      if (result.laps.back().outcome != "completed") break;
    }
    result.sim_time = sim.time().seconds();
    mix_state(result.state_hash, sim);
  }
  result.mean_time = result.repetitions > 0 ? total / result.repetitions : 0.0;
  return result;
}

namespace {

/// Each pattern's name in files and options, and what its repetitions are called.
struct PatternNames {
  TerrainPattern pattern;
  const char* name;
  const char* reps;
};
constexpr PatternNames kPatterns[] = {{TerrainPattern::laps, "laps", "laps"},
                                      {TerrainPattern::back_and_forth, "back-and-forth", "crossings back and forth"},
                                      {TerrainPattern::figure_eight, "figure-eight", "figure-eights"}};

const PatternNames& names_of(TerrainPattern p) {
  for (const auto& n : kPatterns) {
    if (n.pattern == p) return n;
  }
  return kPatterns[0];
}

}  // namespace

const char* terrain_pattern_name(TerrainPattern p) { return names_of(p).name; }

const char* terrain_pattern_reps(TerrainPattern p) { return names_of(p).reps; }

const TerrainSpec* find_terrain_lane(const WorldSpec& world, const std::string& lane) {
  for (const auto& t : world.terrain) {
    if (t.name == lane) return &t;
  }
  for (const auto& t : world.terrain) {
    if (lane == TerrainSpec::kind_name(t.kind)) return &t;
  }
  return nullptr;
}

void check_terrain_pattern(const TerrainSpec& lane, TerrainPattern p) {
  if (p == TerrainPattern::figure_eight && !is_figure_eight_kind(lane.kind)) {
    throw Error(std::string("figure-eights are driven on stepfields and crossing ramps (the test methods' figure-8 terrains); lane '") +
                lane.name + "' is " + TerrainSpec::kind_name(lane.kind) + ": use --pattern laps or back-and-forth");
  }
}

TerrainPattern parse_terrain_pattern(const std::string& name) {
  for (const auto& n : kPatterns) {
    if (name == n.name) return n.pattern;
  }
  throw Error("unknown pattern '" + name + "'; expected laps, back-and-forth or figure-eight");
}

std::string terrain_trial_json(const TerrainTrialResult& r) {
  nlohmann::ordered_json j;
  j["lane"] = r.element.name;
  j["kind"] = TerrainSpec::kind_name(r.element.kind);
  j["robot"] = r.robot;
  j["pattern"] = terrain_pattern_name(r.options.pattern);
  j["seed"] = r.options.seed;
  j["laps"] = r.laps.size();
  j["repetitions"] = r.repetitions;
  j["falls"] = r.falls;
  j["stuck"] = r.stuck;
  j["timeouts"] = r.timeouts;
  j["mean_time_s"] = r.mean_time;
  j["lane_length_m"] = lane_goal(r.element, r.options);
  j["speed_m_s"] = r.options.speed;
  j["sim_time_s"] = r.sim_time;
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(r.state_hash));
  j["state_hash"] = hash;
  if (r.options.pattern == TerrainPattern::figure_eight) {
    j["loop_radius_m"] = r.loop_radius;
    j["figure_eight_length_m"] = r.eight_length;
    j["pylons"] = nlohmann::ordered_json::array();
    for (const Vec2& p : r.pylons) j["pylons"].push_back({p.x(), p.y()});
  }
  nlohmann::ordered_json laps = nlohmann::ordered_json::array();
  for (const auto& l : r.laps) {
    laps.push_back({{"lap", l.lap},
                    {"direction", r.options.pattern == TerrainPattern::figure_eight ? "figure-eight" : l.reverse ? "back" : "forward"},
                    {"outcome", l.outcome},
                    {"time_s", l.time},
                    {"progress_m", l.progress},
                    {"max_pitch_deg", l.max_pitch},
                    {"max_roll_deg", l.max_roll},
                    {"max_height_m", l.max_height}});
  }
  j["laps_detail"] = laps;
  return j.dump(2) + "\n";
}

Canvas terrain_trial_figure(const WorldSpec& world, const TerrainTrialResult& r) {
  WorldPlotOptions po;
  po.px_per_m = 100;
  po.title = r.robot + " on " + TerrainSpec::kind_name(r.element.kind) + ": " + std::to_string(r.repetitions) + "/" +
             std::to_string(r.laps.size()) + " reps, " + std::to_string(r.falls) + " falls, " + std::to_string(r.stuck) + " stuck";
  // the lane and its start and end lines only
  WorldSpec shown = world;
  const double half = 0.5 * r.element.length + r.options.approach + 0.6, across = 0.5 * r.element.width + 1.6;  // wide enough for the title
  Vec2 lo(1e9, 1e9), hi(-1e9, -1e9);
  for (double u : {-half, half}) {
    for (double v : {-across, across}) {
      const Vec2 p = lane_point(r.element, u, v);
      lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    }
  }
  shown.floor_min = lo.cwiseMax(world.floor_min);
  shown.floor_max = hi.cwiseMin(world.floor_max);
  shown.robots.clear();
  const PlotFrame frame = plot_frame_for(shown, po);
  Canvas canvas = plot_world(shown, po);
  const double start_u = -(0.5 * r.element.length + r.options.approach);
  const double line = 0.5 * r.element.width;
  for (double u : {start_u, start_u + lane_goal(r.element, r.options)}) {
    canvas.line(frame.to_px(lane_point(r.element, u, line)), frame.to_px(lane_point(r.element, u, -line)), {40, 40, 200}, 2.0);
  }
  for (const Vec2& p : r.pylons) {  // figure-eight: the pylons and the loops' radius around them
    canvas.circle(frame.to_px(p), r.loop_radius * frame.px_per_m, {40, 40, 200}, 1.0);
    canvas.fill_circle(frame.to_px(p), 4, {40, 40, 200});
  }
  for (const auto& l : r.laps) {
    const Rgb8 colour = l.outcome == "completed" ? Rgb8{30, 160, 60} : l.outcome == "fell" ? Rgb8{210, 40, 40} : Rgb8{235, 140, 20};
    std::vector<Vec2> px;
    for (const auto& p : l.path) px.push_back(frame.to_px(p));
    canvas.polyline(px, colour, 2.0, false, 0.8);
    if (!px.empty() && l.outcome != "completed") canvas.fill_circle(px.back(), 5, colour);
  }
  return canvas;
}

}  // namespace rescuesim
