#include "session/session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/log.h"
#include "core/memory.h"
#include "core/parallel.h"
#include "mission/datagram_json.h"
#include "sensors/camera/render_camera_service.h"
#include "session/explorer_settings.h"
#include "session/session_controllers.h"
#include "world/robot_lumping.h"

namespace rescuesim {

namespace {
constexpr double kCoverageCell = 0.5;    // m
constexpr double kCoverageRadius = 1.0;  // m around the path counts as covered
constexpr double kWallFollowerMapPeriod = 0.5;  // s between scans a wall follower outside a mission maps
}  // namespace

Session::Session(const Scenario& scenario, const ModelMap& models, SessionOptions options)
    : scenario_(scenario), options_(std::move(options)) {
  if (!(options_.trajectory_rate > 0)) throw Error("SessionOptions::trajectory_rate must be > 0 Hz");
  record_interval_ = SimTime::from_seconds(1.0 / options_.trajectory_rate);
  spec_ = build_world(scenario_, &diagnostics_);
  Diagnostics problems = validate(spec_);
  diagnostics_.append(problems);
  if (diagnostics_.has_errors()) diagnostics_.throw_if_errors();
  for (const auto& c : scenario_.robots) diagnostics_.append(c.diagnostics);
  World world = compile_scenario(scenario_, spec_, models);
  bool any_camera = false;
  for (auto& robot : world.robots) {
    for (auto& sensor : robot.spec.sensors) {
      const bool camera = sensor.is_camera();
      if (camera && !options_.cameras) sensor.enabled = false;
      any_camera = any_camera || (camera && sensor.enabled);
    }
  }
  SimOptions so = options_.sim;
  so.seed = scenario_.seed;
  so.physics.dt = scenario_.physics_dt;
  so.physics.solver_iterations = scenario_.solver_iterations;
  so.physics.groups = scenario_.physics_groups;
  sim_ = std::make_unique<Simulation>(std::move(world), so);
  if (any_camera) {
    CameraServiceOptions& co = camera_options_;
    co.quality = scenario_.render_quality == "high" ? Quality::high : scenario_.render_quality == "medium" ? Quality::medium : Quality::low;
    co.latency = scenario_.render_latency;
    try {
      cameras_ = std::make_unique<RenderCameraService>(sim_->world(), co);
    } catch (const Error& e) {
      throw Error({scenario_.source_file, 0, "camera sensors"},
                  std::string(e.what()) + "\n(the cameras need OpenGL 4.5 through EGL; run without them with --no-cameras)");
    }
    sim_->set_camera_service(cameras_.get());
    sim_->set_world_changed([this] { rebuild_cameras(); });
  }
  // victim detection, picked once: in the thermal images when cameras render and a robot has
  // a thermal camera, else by line of sight (the Simulation's default)
  if (cameras_ && !world_has_no_thermal()) {
    std::vector<bool> rendered(sim_->world().robots.size());
    for (std::size_t r = 0; r < rendered.size(); ++r) rendered[r] = cameras_->detects_victims(static_cast<int>(r));
    sim_->set_victim_detector(std::make_unique<ThermalImageDetector>(rendered));
  }
  last_scans_.resize(sim_->world().robots.size());
  if (scenario_.mission) {
    try {
      mission_ = std::make_unique<Mission>(*scenario_.mission, *sim_);
      mission_->enable_map_scoring(spec_);
    } catch (const Error& e) {
      throw Error({scenario_.source_file, 0, "mission"}, e.what());
    }
  }

  // controllers listen to the laser and odometry topics and answer with cmd_vel
  controllers_ = std::make_unique<Controllers>();
  controllers_->inbox.resize(sim_->world().robots.size());  // never resized again: subscribers point into it
  const auto configs = robot_configs(scenario_, spec_, models);
  for (std::size_t r = 0; r < sim_->world().robots.size(); ++r) {
    const RobotInstance& robot = sim_->world().robots[r];
    controllers_->X_WO.push_back(robot.X_W_start.to_pose2());
    controllers_->explorers.emplace_back();
    controllers_->queued.emplace_back();
    controllers_->queued_look.emplace_back();
    controllers_->pans.emplace_back();
    const SensorSpec* laser = nullptr;
    const SensorSpec* odom = nullptr;
    const SensorSpec* joints = nullptr;
    for (const auto& s : robot.spec.sensors) {
      if (s.enabled && s.type == SensorSpec::Type::lidar && s.lidar.layers == 1 && !laser) laser = &s;
      if (s.enabled && s.type == SensorSpec::Type::odometry && !odom) odom = &s;
      if (s.enabled && s.type == SensorSpec::Type::joint_states && !joints) joints = &s;
    }
    const int ri = static_cast<int>(r);
    if (laser) {
      sim_->bus().subscribe(sim_->topic_name(ri, laser->topic), [this, r](const Topic&, const msg::Message& m) {
        last_scans_[r] = std::get<msg::LaserScan>(m);
      });
    }
    const bool wants = options_.controllers && r < configs.size() && configs[r].controller != "none";
    if (!wants) continue;
    const SourceRef where{scenario_.source_file, 0, "robots[" + std::to_string(r) + "].controller"};
    if (!laser || !odom) throw Error(where, "the " + configs[r].controller + " needs an enabled planar laser and odometry (a drive)");
    // the laser must sit on the root link, or on links fixed to it (the root's rigid body)
    const int laser_link = robot.spec.link_index(laser->link);
    const LumpedRobot lumped = lump_fixed_joints(robot.spec);
    if (lumped.body_of_link[static_cast<std::size_t>(laser_link)] != 0) {
      throw Error(where, "the " + configs[r].controller + " needs its laser fixed to the robot's body; link '" + laser->link +
                             "' moves on a joint");
    }
    const Pose3 X_BS = laser_link == 0 ? laser->X_LS : lumped.X_BL[static_cast<std::size_t>(laser_link)] * laser->X_LS;
    autonomy::ExplorerConfig ec = builtin_explorer_config(configs[r].controller, robot.spec);
    // other robots about: give their masts (all the laser sees of them) a berth as wide as a
    // rescue robot's reach from its mast (0.48 m to the front bumper)
    if (sim_->world().robots.size() > 1) ec.post_radius = 0.5;
    // scan matching keeps the map true for plans and reports; a robot that does neither (a
    // wall follower outside a mission) steers by the laser alone: it skips matching (a fifth
    // of the work of 100 such robots) and maps at 2 Hz, not at its laser's 10 Hz (mapping
    // every scan was a quarter of it; docs/performance.md)
    if (!ec.frontier_trips && !mission_) {
      ec.scan_matching = false;
      ec.map_period = kWallFollowerMapPeriod;
    }
    // the map covers the whole floor (and a margin) wherever the robot starts: the square the
    // mapper allocates around the start by default (auto_size, 40 m) would leave the far side
    // of a larger world unmapped, and a robot in a corner of a 30 m maze could map only half
    // of it. Worlds that square covers keep it.
    if (const Box2& floor = sim_->world().floor; !floor.empty()) {
      const Pose2 X_OW = controllers_->X_WO[r].inverse();
      constexpr double kMargin = 2.0;  // m
      Box2 box_O;
      for (const Vec2& corner : {floor.min, floor.max, Vec2(floor.min.x(), floor.max.y()), Vec2(floor.max.x(), floor.min.y())}) {
        box_O.extend(X_OW.transform(corner));
      }
      box_O.min -= Vec2(kMargin, kMargin);
      box_O.max += Vec2(kMargin, kMargin);
      // the default square is centred on the laser at the start, near the odom frame's origin
      const double reach = ec.map.auto_size / 2 - 1.0;
      if (box_O.min.minCoeff() < -reach || box_O.max.maxCoeff() > reach) {
        ec.map.size = box_O.max - box_O.min;
        ec.map.origin_O = box_O.min;
      }
    }
    controllers_->explorers.back() = std::make_unique<autonomy::Explorer>(X_BS.to_pose2(), ec);
    // what the explorer hears waits in its inbox until the step is over (Session::run_controllers)
    std::vector<msg::Message>* inbox = &controllers_->inbox[r];
    const auto hear = [inbox](const Topic&, const msg::Message& m) { inbox->push_back(m); };
    sim_->bus().subscribe(sim_->topic_name(ri, odom->topic), hear);
    // the victim camera's pan: where it stands, and the swing the explorer asks for (a head
    // joint is commanded with the whole head, the others held at their starting positions)
    if (!ec.look.yaw_joint.empty()) {
      Controllers::Pan& pan = controllers_->pans[r];
      pan.joint.name = {ec.look.yaw_joint};
      pan.joint.position = {0.0};
      const auto& hj = robot.spec.head_joints;
      for (std::size_t k = 0; k < hj.size(); ++k) {
        pan.head.push_back(robot.spec.joints[static_cast<std::size_t>(robot.spec.joint_index(hj[k]))].initial);
        if (hj[k] == ec.look.yaw_joint) pan.in_head = static_cast<int>(k);
      }
      if (joints) sim_->bus().subscribe(sim_->topic_name(ri, joints->topic), hear);
    }
    sim_->bus().subscribe(sim_->topic_name(ri, laser->topic), hear);
  }

  const std::size_t robots = sim_->world().robots.size();
  controllers_->pending.assign(robots, {});
  controllers_->known.assign(robots, std::vector<bool>(sim_->world().victims.size(), false));
  controllers_->found_W.assign(robots, {});
  controllers_->next_report.assign(robots, SimTime{});
  controllers_->lost_contact.assign(robots, SimTime{-1});
  controllers_->returning.assign(robots, 0);
  controllers_->heard.assign(robots, std::vector<std::optional<TeamClaim>>(robots));
  controllers_->next_share.assign(robots, SimTime{});
  controllers_->next_seen.assign(robots, SimTime{});
  controllers_->next_map.assign(robots, SimTime{});
  controllers_->base_maps.assign(robots, std::nullopt);

  // the coverage grid: cells of free floor
  grid_box_ = Box2{spec_.floor_min, spec_.floor_max};
  grid_w_ = std::max(1, static_cast<int>(std::ceil(grid_box_.size().x() / kCoverageCell)));
  grid_h_ = std::max(1, static_cast<int>(std::ceil(grid_box_.size().y() / kCoverageCell)));
  free_cells_.assign(static_cast<std::size_t>(grid_w_ * grid_h_), 1);
  visited_cells_.assign(free_cells_.size(), 0);
  for (int y = 0; y < grid_h_; ++y) {
    for (int x = 0; x < grid_w_; ++x) {
      const Vec2 c = grid_box_.min + Vec2((x + 0.5) * kCoverageCell, (y + 0.5) * kCoverageCell);
      bool solid = false;
      for (const auto& w : spec_.walls) solid = solid || contains(WorldSpec::wall_outline(w), c, 0);
      for (const auto& b : spec_.blocks) solid = solid || contains(b.outline, c, 0);
      free_cells_[static_cast<std::size_t>(y * grid_w_ + x)] = solid ? 0 : 1;
    }
  }
  record();
  if (options_.control) {
    control_ = std::make_unique<RunControl>(*this, options_.control_options);
    sim_->set_control(control_.get());
  }
}

Session::~Session() {
  // the simulation holds a pointer to the camera service: detach it before either goes
  if (sim_) sim_->set_camera_service(nullptr);
  if (sim_) sim_->set_control(nullptr);
}

bool Session::world_has_no_thermal() const {
  // the scenario's robots (the camera service renders no spawned robot's cameras)
  for (std::size_t r = 0; r < sim_->base_robots(); ++r) {
    if (cameras_->detects_victims(static_cast<int>(r))) return false;
  }
  return true;
}

void Session::rebuild_cameras() {
  // robots spawned or deleted: the renderer draws the world it was made with, so it is made
  // again (its frames in flight were published already, its last frames start afresh)
  const bool thermal = sim_->victim_detector().name() == "thermal images";
  sim_->set_camera_service(nullptr);
  cameras_.reset();
  cameras_ = std::make_unique<RenderCameraService>(sim_->world(), camera_options_);
  sim_->set_camera_service(cameras_.get());
  if (thermal) {
    std::vector<bool> rendered(sim_->world().robots.size());
    for (std::size_t r = 0; r < rendered.size(); ++r) rendered[r] = cameras_->detects_victims(static_cast<int>(r));
    sim_->set_victim_detector(std::make_unique<ThermalImageDetector>(rendered));
  }
}

std::string Session::render_device() const { return cameras_ ? cameras_->device() : std::string(); }

bool Session::thin_trajectory() {
  // samples come in groups of one per robot at each sample time: keep groups 0, 2, 4, ...
  const std::size_t group = sim_->base_robots();
  const std::size_t groups = trajectory_.size() / group;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < trajectory_.size(); i += 2 * group) {
    for (std::size_t k = 0; k < group && i + k < trajectory_.size(); ++k) trajectory_[kept++] = trajectory_[i + k];
  }
  trajectory_.resize(kept);
  record_interval_ = record_interval_ + record_interval_;
  // the sample due now is group number `groups`: on the new grid when that is even
  return groups % 2 == 0;
}

void Session::record() {
  const State& s = sim_->state();
  if (s.time < next_record_) return;
  // the scenario's robots only: robots spawned while running come and go, and the trajectory
  // is kept in groups of one sample per robot
  const std::size_t robots = std::min(s.robots.size(), sim_->base_robots());
  if (robots > 0 && trajectory_.size() + robots > options_.trajectory_max_points) {
    const SimTime before = record_interval_;
    if (!thin_trajectory()) {
      next_record_ = s.time + before;  // the sample due now falls between the kept ones
      return;
    }
  }
  next_record_ = s.time + record_interval_;
  for (std::size_t r = 0; r < robots; ++r) {
    const RobotState& rs = s.robots[r];
    const Pose2 truth = rs.base.X_WB.to_pose2();
    const Vec3 v_B = rs.base.X_WB.q.conjugate() * rs.base.v_WB;
    trajectory_.push_back({s.time.seconds(), static_cast<int>(r), truth, rs.odom, v_B.x(), rs.base.w_WB.z()});
    // mark the free cells within reach of the robot as covered
    const int reach = static_cast<int>(std::ceil(kCoverageRadius / kCoverageCell));
    const int cx = static_cast<int>(std::floor((truth.x - grid_box_.min.x()) / kCoverageCell));
    const int cy = static_cast<int>(std::floor((truth.y - grid_box_.min.y()) / kCoverageCell));
    for (int y = cy - reach; y <= cy + reach; ++y) {
      for (int x = cx - reach; x <= cx + reach; ++x) {
        if (x < 0 || y < 0 || x >= grid_w_ || y >= grid_h_) continue;
        const Vec2 c = grid_box_.min + Vec2((x + 0.5) * kCoverageCell, (y + 0.5) * kCoverageCell);
        if ((c - truth.position()).norm() <= kCoverageRadius) visited_cells_[static_cast<std::size_t>(y * grid_w_ + x)] = 1;
      }
    }
  }
}

double Session::coverage() const {
  int free = 0, seen = 0;
  for (std::size_t i = 0; i < free_cells_.size(); ++i) {
    free += free_cells_[i];
    seen += free_cells_[i] & visited_cells_[i];
  }
  return free > 0 ? static_cast<double>(seen) / free : 0.0;
}

namespace {
// The built-in team's radio rules (docs/missions.md, "The built-in team")
constexpr double kReturnAfter = 10.0;     // s out of contact with reports to make before heading back
constexpr double kRelayMargin = 3.0;      // dB: drop a relay when the route's weakest link is this close to the threshold
constexpr double kRelaySpacing = 3.0;     // m: ... and no base or relay is nearer than this
constexpr double kShareEvery = 2.0;       // s between a built-in robot's team datagrams
constexpr double kClaimAge = 10.0;        // s a teammate's word counts for
constexpr double kSeenEvery = 6.0;        // s between a built-in robot's "where my camera looked" datagrams
constexpr double kSeenCell = 0.5;         // m, the squares that datagram is counted in (world frame)
constexpr int kSeenMinCells = 25;         // a square counts as seen when the camera looked at this many of its map cells
constexpr double kMapEvery = 6.0;         // s between a built-in robot's "what my laser mapped" datagrams
constexpr double kMapCell = 0.1;          // m, the squares that datagram is drawn in (world frame)
constexpr double kBaseMapEvery = 10.0;    // s between the base's submissions of the team's map

/// The squares (kSeenCell, world frame) where an explorer's own camera has looked, as a
/// "seen" datagram (mission/datagram_json); nothing when it has looked nowhere yet.
std::optional<std::vector<std::uint8_t>> seen_datagram(const autonomy::Explorer& ex, const Pose2& X_WM) {
  const autonomy::OccupancyMapper& map = ex.mapper();
  const auto box = map.observed_box();
  if (!box) return std::nullopt;
  std::map<std::pair<int, int>, int> counts;
  for (int y = box->first.y; y <= box->second.y; ++y) {
    for (int x = box->first.x; x <= box->second.x; ++x) {
      if (!ex.looked().looked_self({x, y})) continue;
      const Vec2 q = X_WM.transform(map.cell_to_world({x, y})) / kSeenCell;
      if (!(q.cwiseAbs().maxCoeff() < kMaxSeenSide)) continue;  // a map run far away says nothing
      ++counts[{static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y()))}];
    }
  }
  SeenSquares seen;
  seen.cell = kSeenCell;
  for (const auto& [ij, n] : counts) {
    if (n >= kSeenMinCells) seen.squares.push_back(ij);
  }
  if (seen.squares.empty()) return std::nullopt;
  return rescuesim::seen_datagram(seen);
}

/// What an explorer's laser has mapped, in kMapCell squares of the world, as a "map" datagram
/// (mission/datagram_json): a square holding an occupied cell is occupied, else one holding a
/// free cell is free. Nothing before its first scan. Map cells are half a square, so every
/// square the map covers holds a cell's centre, whatever the start's heading.
std::optional<std::vector<std::uint8_t>> map_datagram(const autonomy::Explorer& ex, const Pose2& X_WM) {
  const autonomy::OccupancyMapper& map = ex.mapper();
  const auto box = map.observed_box();
  if (!box) return std::nullopt;
  // the squares of the observed box's corners in the world
  Box2 world;
  const double r = map.resolution() / 2;
  using autonomy::Cell;
  for (const Cell& c : {box->first, box->second, Cell{box->first.x, box->second.y}, Cell{box->second.x, box->first.y}}) {
    for (const Vec2& d : {Vec2(-r, -r), Vec2(r, r), Vec2(-r, r), Vec2(r, -r)}) world.extend(X_WM.transform(map.cell_to_world(c) + d));
  }
  const Vec2 lo = (world.min / kMapCell).array().floor(), hi = (world.max / kMapCell).array().floor();
  if (!(lo.cwiseAbs().maxCoeff() <= kMaxSeenSide && hi.cwiseAbs().maxCoeff() <= kMaxSeenSide)) return std::nullopt;  // a map run far away says nothing
  MapSquares out;
  out.cell = kMapCell;
  out.origin = {static_cast<int>(lo.x()), static_cast<int>(lo.y())};
  out.width = static_cast<int>(hi.x() - lo.x()) + 1;
  out.height = static_cast<int>(hi.y() - lo.y()) + 1;
  if (static_cast<long>(out.width) * out.height > kMaxMapSquares) return std::nullopt;
  out.states.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height), MapSquares::unknown);
  for (int y = box->first.y; y <= box->second.y; ++y) {
    for (int x = box->first.x; x <= box->second.x; ++x) {
      const autonomy::CellState st = map.state({x, y});
      if (st == autonomy::CellState::unknown) continue;
      const Vec2 q = X_WM.transform(map.cell_to_world({x, y})) / kMapCell;
      const int i = std::clamp(static_cast<int>(std::floor(q.x())) - out.origin.first, 0, out.width - 1);
      const int j = std::clamp(static_cast<int>(std::floor(q.y())) - out.origin.second, 0, out.height - 1);
      std::uint8_t& v = out.states[static_cast<std::size_t>(j) * static_cast<std::size_t>(out.width) + static_cast<std::size_t>(i)];
      v = std::max<std::uint8_t>(v, st == autonomy::CellState::occupied ? MapSquares::occupied : MapSquares::free);
    }
  }
  return rescuesim::map_datagram(out);
}
}  // namespace

void Session::mission_step() {
  mission_->after_step();
  const State& s = sim_->state();
  Controllers& c = *controllers_;
  const SimTime gap = SimTime::from_seconds(1.0 / mission_->spec().rules.report_rate_hz);
  const RadioNetwork& net = mission_->network();
  // the relay rule reads only the links, so it runs once per link update, not every step
  const bool links_new = net.update_count() != c.relay_check;
  c.relay_check = net.update_count();
  for (std::size_t r = 0; r < c.explorers.size(); ++r) {
    autonomy::Explorer* ex = c.explorers[r].get();
    if (!ex) continue;  // robots driven from outside report for themselves
    const int ri = static_cast<int>(r);
    const RobotState& rs = s.robots[r];
    for (std::size_t v = 0; v < s.victims.size(); ++v) {
      if (c.known[r][v] || !s.victims[v].seen_by_robot(r)) continue;
      // where the robot believes the victim is: its offset from the robot (the victim sensor),
      // placed at the robot's own pose estimate: odometry corrected by the explorer's scan
      // matching (X_MO), in its map frame, which starts on the odom frame at the start pose
      const Vec3 centre = sim_->world().victims[v].centre;
      const Vec2 p_B = rs.base.X_WB.to_pose2().inverse().transform(centre.head<2>());
      const Vec2 p_W = (c.X_WO[r] * ex->X_MO() * rs.odom).transform(p_B);
      c.known[r][v] = true;
      // a victim a teammate said it found (within the rules' radius of where this robot
      // believes it lies) is the teammate's to report; a report of it would be a duplicate
      bool teammates = false;
      for (const auto& h : c.heard[r]) {
        if (!h) continue;
        for (const Vec2& q : h->victims) teammates = teammates || (q - p_W).norm() <= mission_->spec().rules.report_radius_m;
      }
      if (teammates) continue;
      c.found_W[r].push_back(p_W);
      c.pending[r].push_back({static_cast<int>(v), Vec3(p_W.x(), p_W.y(), centre.z()), victim_picture(ri)});
    }
    const bool contact = mission_->in_contact(ri);
    if (contact) {
      c.lost_contact[r] = SimTime{-1};
    } else if (c.lost_contact[r].ns < 0) {
      c.lost_contact[r] = s.time;
    }
    if (!c.pending[r].empty() && contact && s.time >= c.next_report[r]) {
      PendingReport& next = c.pending[r].front();
      if (next.picture) {
        mission_->report(ri, next.p_W, std::move(*next.picture));
      } else {
        mission_->report(ri, next.p_W);
      }
      c.pending[r].erase(c.pending[r].begin());
      c.next_report[r] = s.time + gap;
    }
    // out of contact for a while with reports to make: back towards the (first) base, in the
    // explorer's map frame (placed at the start pose like the odom frame), until contact is back and the reports are made
    if (!c.returning[r] && !c.pending[r].empty() && !contact && (s.time - c.lost_contact[r]).seconds() >= kReturnAfter) {
      const Vec3 base = net.node(mission_->base_nodes().front()).p_W;
      ex->set_goal(c.X_WO[r].inverse().transform(base.head<2>()));
      c.returning[r] = 1;
    } else if (c.returning[r] && contact && c.pending[r].empty()) {
      ex->clear_goal();
      c.returning[r] = 0;
    }
    // a relay where the link to the base grows weak, unless one is close by
    if (links_new && contact && net.relays_left(mission_->robot_node(ri)) > 0 && net.model().kind != RadioModelKind::ideal) {
      const int me = mission_->robot_node(ri);
      // the margin of the route to a base: its weakest link's, the best over the bases
      double margin = -std::numeric_limits<double>::infinity();
      for (int b : mission_->base_nodes()) {
        const std::vector<int> path = net.route(me, b);
        if (path.size() < 2) continue;
        double bottleneck = std::numeric_limits<double>::infinity();
        for (std::size_t k = 1; k < path.size(); ++k) bottleneck = std::min(bottleneck, net.link(path[k - 1], path[k]).margin_db);
        margin = std::max(margin, bottleneck);
      }
      bool near = false;
      for (int n = 0; n < net.node_count(); ++n) {
        if (net.node(n).kind == RadioNodeKind::robot) continue;
        near = near || (net.node(n).p_W - net.node(me).p_W).head<2>().norm() < kRelaySpacing;
      }
      if (margin < kRelayMargin && !near) mission_->drop_relay(ri);
    }
  }

  // the built-in team's radio talk (Controllers::heard)
  const std::size_t n = c.explorers.size();
  // what each built-in robot heard since the last step
  for (std::size_t r = 0; r < n; ++r) {
    if (!c.explorers[r]) continue;
    for (const Datagram& d : mission_->take_inbox(static_cast<int>(r))) {
      for (std::size_t k = 0; k < n; ++k) {
        if (k == r || mission_->robot_node(static_cast<int>(k)) != d.from) continue;
        if (auto said = read_team_datagram(d.bytes)) c.heard[r][k] = TeamClaim{said->at, said->going, d.sent, std::move(said->victims)};
        if (const auto seen = read_seen_datagram(d.bytes)) {
          // the centres of the squares the teammate's camera looked at, in this robot's map frame
          const Pose2 X_MW = c.X_WO[r].inverse();
          std::vector<Vec2> centres_M;
          centres_M.reserve(seen->squares.size());
          for (const auto& [i, j] : seen->squares) centres_M.push_back(X_MW.transform(Vec2(i + 0.5, j + 0.5) * seen->cell));
          c.explorers[r]->add_team_seen(centres_M, seen->cell);
        }
        if (const auto map = read_map_datagram(d.bytes)) {
          // the squares the teammate mapped, centred in this robot's map frame
          const Pose2 X_MW = c.X_WO[r].inverse();
          std::vector<std::pair<Vec2, autonomy::CellState>> squares_M;
          for (int j = 0; j < map->height; ++j) {
            for (int i = 0; i < map->width; ++i) {
              const std::uint8_t v = map->states[static_cast<std::size_t>(j) * static_cast<std::size_t>(map->width) + static_cast<std::size_t>(i)];
              if (v == MapSquares::unknown) continue;
              const Vec2 centre_W = Vec2(map->origin.first + i + 0.5, map->origin.second + j + 0.5) * map->cell;
              squares_M.emplace_back(X_MW.transform(centre_W), v == MapSquares::occupied ? autonomy::CellState::occupied : autonomy::CellState::free);
            }
          }
          c.explorers[r]->add_team_map(squares_M, map->cell);
        }
      }
    }
  }
  for (std::size_t r = 0; r < n; ++r) {
    autonomy::Explorer* ex = c.explorers[r].get();
    if (!ex) continue;
    const int ri = static_cast<int>(r);
    // tell the teammates where it is and where it goes (its map frame placed at its start)
    if (s.time >= c.next_share[r]) {
      c.next_share[r] = s.time + SimTime::from_seconds(kShareEvery);
      const std::optional<Pose2> X_MB = ex->pose_in_map(s.time);
      if (X_MB) {
        const Vec2 at_W = c.X_WO[r].transform(X_MB->position());
        const std::optional<Vec2> going = ex->frontier_target();
        const std::optional<Vec2> going_W = going ? std::optional<Vec2>(c.X_WO[r].transform(*going)) : std::nullopt;
        const auto& found = c.found_W[r];  // (a world of more victims than a datagram names tells the first ones)
        const auto bytes = team_datagram({at_W, going_W, {found.begin(), found.begin() + static_cast<std::ptrdiff_t>(std::min(found.size(), kMaxTeamVictims))}});
        for (std::size_t k = 0; k < n; ++k) {
          if (k != r && c.explorers[k]) mission_->send(ri, sim_->world().robots[k].name, bytes);
        }
      }
    }
    // and where its camera has looked, less often
    if (s.time >= c.next_seen[r]) {
      // (nothing to say before its first look: it tries again at the next step)
      if (const auto bytes = seen_datagram(*ex, c.X_WO[r])) {
        c.next_seen[r] = s.time + SimTime::from_seconds(kSeenEvery);
        for (std::size_t k = 0; k < n; ++k) {
          if (k != r && c.explorers[k]) mission_->send(ri, sim_->world().robots[k].name, *bytes);
        }
      }
    }
    // and what its laser has mapped, as often, to the base too
    if (s.time >= c.next_map[r]) {
      if (const auto bytes = map_datagram(*ex, c.X_WO[r])) {
        c.next_map[r] = s.time + SimTime::from_seconds(kMapEvery);
        for (std::size_t k = 0; k < n; ++k) {
          if (k != r && c.explorers[k]) mission_->send(ri, sim_->world().robots[k].name, *bytes);
        }
        mission_->send(ri, "base", *bytes);
      }
    }
    // what it heard lately becomes its claims, in its own map frame
    std::vector<Vec2> claims_M;
    const Pose2 X_MW = c.X_WO[r].inverse();
    for (std::size_t k = 0; k < n; ++k) {
      const auto& h = c.heard[r][k];
      if (!h || (s.time - h->stamp).seconds() > kClaimAge) continue;
      claims_M.push_back(X_MW.transform(h->at));
      if (h->going) claims_M.push_back(X_MW.transform(*h->going));
    }
    ex->set_claims(std::move(claims_M));
  }
  // the base reads only what the built-in robots send it (a team driven from outside submits
  // its own map on /rescue/map)
  if (std::any_of(c.explorers.begin(), c.explorers.end(), [](const auto& e) { return e != nullptr; })) base_map_step();
}

namespace {
/// The team's map from the robots' newest maps (kMapCell squares of the world, every map of that
/// cell): occupied where any says occupied, else free where any says free, else unknown; as a
/// nav_msgs/OccupancyGrid in the map frame (the world's). Nothing when there is no map yet.
std::optional<msg::OccupancyGrid> team_map(const std::vector<std::optional<MapSquares>>& maps, SimTime stamp) {
  int i0 = std::numeric_limits<int>::max(), j0 = i0, i1 = std::numeric_limits<int>::min(), j1 = i1;
  for (const auto& m : maps) {
    if (!m || m->cell != kMapCell) continue;
    i0 = std::min(i0, m->origin.first), j0 = std::min(j0, m->origin.second);
    i1 = std::max(i1, m->origin.first + m->width - 1), j1 = std::max(j1, m->origin.second + m->height - 1);
  }
  if (i0 > i1) return std::nullopt;
  const long w = static_cast<long>(i1) - i0 + 1, h = static_cast<long>(j1) - j0 + 1;
  if (w * h > 4 * kMaxMapSquares) return std::nullopt;  // (each map is within kMaxSeenSide; together they stay sane)
  std::vector<std::uint8_t> states(static_cast<std::size_t>(w * h), MapSquares::unknown);
  for (const auto& m : maps) {
    if (!m || m->cell != kMapCell) continue;
    for (int j = 0; j < m->height; ++j) {
      for (int i = 0; i < m->width; ++i) {
        const std::size_t at = static_cast<std::size_t>((m->origin.second + j - j0) * w + (m->origin.first + i - i0));
        states[at] = std::max(states[at], m->states[static_cast<std::size_t>(j) * static_cast<std::size_t>(m->width) + static_cast<std::size_t>(i)]);
      }
    }
  }
  msg::OccupancyGrid g;
  g.header = {stamp, "map"};
  g.map_load_time = stamp;
  g.resolution = static_cast<float>(kMapCell);
  g.width = static_cast<std::uint32_t>(w);
  g.height = static_cast<std::uint32_t>(h);
  g.origin = Pose3::from_pose2({i0 * kMapCell, j0 * kMapCell, 0.0});
  g.data.resize(states.size());
  for (std::size_t k = 0; k < states.size(); ++k) {
    g.data[k] = states[k] == MapSquares::occupied ? std::int8_t{100} : (states[k] == MapSquares::free ? std::int8_t{0} : std::int8_t{-1});
  }
  return g;
}
}  // namespace

void Session::base_map_step() {
  Controllers& c = *controllers_;
  for (std::size_t b = 0; b < mission_->base_nodes().size(); ++b) {
    for (const Datagram& d : mission_->take_base_inbox(b)) {
      for (std::size_t k = 0; k < c.explorers.size(); ++k) {
        if (!c.explorers[k] || mission_->robot_node(static_cast<int>(k)) != d.from) continue;
        if (auto m = read_map_datagram(d.bytes)) {
          c.base_maps[k] = std::move(*m);
          c.base_map_new = true;
        }
      }
    }
  }
  const SimTime now = sim_->state().time;
  if (!c.base_map_new || now < c.next_base_map) return;
  c.next_base_map = now + SimTime::from_seconds(kBaseMapEvery);
  c.base_map_new = false;
  if (const auto g = team_map(c.base_maps, now)) mission_->score_map(*g);
}

void Session::command_look(int robot, double yaw) {
  Controllers::Pan& pan = controllers_->pans[static_cast<std::size_t>(robot)];
  if (pan.in_head >= 0) {
    pan.head[static_cast<std::size_t>(pan.in_head)] = yaw;
    sim_->command_head(robot, pan.head);
  } else {
    pan.joint.position[0] = yaw;
    sim_->command_joints(robot, pan.joint);
  }
  controllers_->queued_look[static_cast<std::size_t>(robot)] = yaw;
}

void Session::run_controllers() {
  Controllers& c = *controllers_;
  std::vector<std::size_t> busy;
  for (std::size_t r = 0; r < c.inbox.size(); ++r) {
    if (!c.inbox[r].empty()) busy.push_back(r);
  }
  // each robot's explorer hears its own messages in the order they were published, on a worker
  // thread (explorers share nothing); what they ask for is then commanded in robot order
  struct Asked {
    msg::Twist cmd;
    std::optional<double> look;
  };
  std::vector<std::vector<Asked>> asked(busy.size());
  parallel_for(busy.size(), [&](std::size_t i) {
    const std::size_t r = busy[i];
    autonomy::Explorer& ex = *c.explorers[r];
    for (const msg::Message& m : c.inbox[r]) {
      if (const auto* odom = std::get_if<msg::Odometry>(&m)) {
        ex.on_odometry(*odom);
      } else if (const auto* joints = std::get_if<msg::JointState>(&m)) {
        ex.on_joint_state(*joints);
      } else if (const auto* scan = std::get_if<msg::LaserScan>(&m)) {
        ex.on_scan(*scan);
        const msg::Twist cmd = ex.command(scan->header.stamp);
        asked[i].push_back({cmd, ex.look_command(scan->header.stamp)});
      }
    }
    c.inbox[r].clear();
  });
  for (std::size_t i = 0; i < busy.size(); ++i) {
    const int ri = static_cast<int>(busy[i]);
    for (const Asked& a : asked[i]) {
      sim_->command_velocity(ri, a.cmd);
      c.queued[busy[i]] = a.cmd;
      if (a.look) command_look(ri, *a.look);
    }
  }
}

void Session::step_once() {
  // what the controllers queue during this step is for the next one
  for (auto& q : controllers_->queued) q.reset();
  for (auto& q : controllers_->queued_look) q.reset();
  sim_->step();
  run_controllers();
  record();
  if (mission_) mission_step();
}

bool Session::step_until(SimTime t) {
  while (sim_->time() < t) {
    step_once();
    if (sim_->in_trouble()) return false;
  }
  return true;
}

RunResult Session::result() const {
  const State& s = sim_->state();
  RunResult r;
  r.scenario = scenario_.name;
  r.seed = scenario_.seed;
  r.sim_time = s.time.seconds();
  r.wall_time = wall_time_;
  r.real_time_factor = wall_time_ > 0 ? r.sim_time / wall_time_ : 0;
  r.stop_reason = stop_reason_;
  r.trouble = sim_->in_trouble();
  for (std::size_t v = 0; v < s.victims.size(); ++v) {
    VictimResult vr;
    vr.name = sim_->world().victims[v].name;
    vr.found = s.victims[v].first_seen.ns >= 0;
    vr.time = vr.found ? s.victims[v].first_seen.seconds() : -1;
    vr.by = s.victims[v].seen_by;
    r.victims_found += vr.found;
    r.victims.push_back(vr);
  }
  r.victim_detection = std::string(sim_->victim_detector().name());
  r.coverage = coverage();
  for (std::size_t k = 0; k < controllers_->explorers.size(); ++k) {
    if (controllers_->explorers[k]) r.explorers.emplace_back(sim_->world().robots[k].name, controllers_->explorers[k]->stats());
  }
  for (const auto& rs : s.robots) {
    r.collisions += rs.collisions;
    r.distance += rs.distance;
  }
  for (const auto& t : sim_->bus().topics()) r.message_counts.emplace_back(t.name, sim_->bus().count(t.id));
  r.state_hash = state_hash(s);
  if (mission_) r.mission = mission_->result();
  return r;
}

RunResult Session::run(const std::atomic<bool>* stop, const std::function<void(const RunResult&)>& progress) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const double wall_before = wall_time_;
  // an infinite duration runs until `stop` (rescuesim run --ros1 without --duration)
  const SimTime end = std::isfinite(scenario_.duration) ? SimTime::from_seconds(scenario_.duration)
                                                        : SimTime{std::numeric_limits<std::int64_t>::max()};
  const SimTime start_time = sim_->time();
  auto last_report = t0;
  stop_reason_ = "duration";
  const auto all_found = [&] {
    // with a mission, found means reported and accepted by the referee
    if (mission_) return mission_->referee().victim_count() > 0 && mission_->referee().victims_found() == mission_->referee().victim_count();
    for (const auto& v : sim_->state().victims) {
      if (v.first_seen.ns < 0) return false;
    }
    return !sim_->state().victims.empty();
  };
  // synchronous with an outside controller: count the velocity commands each scan is owed
  // (the Bus calls this on this thread, as the scan is published, before any bridge sends it)
  const bool sync = options_.sync_timeout > 0;
  std::uint64_t commands_owed = sim_->velocity_commands();
  std::vector<SubscriptionId> scan_subscriptions;
  if (sync) {
    for (std::size_t r = 0; r < sim_->world().robots.size(); ++r) {
      for (const auto& s : sim_->world().robots[r].spec.sensors) {
        if (!s.enabled || s.type != SensorSpec::Type::lidar) continue;
        scan_subscriptions.push_back(sim_->bus().subscribe(sim_->topic_name(static_cast<int>(r), s.topic),
                                                           [&commands_owed](const Topic&, const msg::Message&) { ++commands_owed; }));
      }
    }
  }
  const auto wait_for_controller = [&] {
    if (sim_->velocity_commands() >= commands_owed) return;
    if (!sim_->wait_for_velocity_commands(commands_owed, std::chrono::duration<double>(options_.sync_timeout))) {
      if (sync_timeouts_++ == 0) {
        log::warn("sync: no cmd_vel answered the scan at {:.2f} s within {} s of wall time; stepping on (a controller that is "
                  "not there yet, or does not answer every scan)", sim_->time().seconds(), options_.sync_timeout);
      }
      commands_owed = sim_->velocity_commands();  // what was missed is not owed any more
    }
  };
  // long runs give freed memory back now and then (threads' malloc arenas keep it otherwise)
  const SimTime trim_every = SimTime::from_seconds(options_.return_memory_every > 0 ? options_.return_memory_every : 0);
  SimTime next_trim = sim_->time() + trim_every;
  // pacing starts afresh whenever the control surface says so (after a pause, a reset, a new rate)
  auto pace_t0 = t0;
  SimTime pace_start = start_time;
  std::uint64_t pace_epoch = control_ ? control_->pacing_epoch() : 0;
  while (sim_->time() < end) {
    if (trim_every.ns > 0 && sim_->time() >= next_trim) {
      return_free_memory();
      next_trim = sim_->time() + trim_every;
    }
    if (stop && stop->load(std::memory_order_relaxed)) {
      stop_reason_ = "interrupted";
      break;
    }
    // the control surface: requests run here, between steps; while paused this waits
    bool stepping_job = false;
    if (control_) {
      if (!control_->before_step(stop)) {
        stop_reason_ = control_->run_state() == control::RunState::quitting ? "quit by request" : "interrupted";
        break;
      }
      stepping_job = control_->run_state() != control::RunState::playing;
      if (control_->pacing_epoch() != pace_epoch || stepping_job) {
        pace_epoch = control_->pacing_epoch();
        pace_t0 = clock::now();
        pace_start = sim_->time();
      }
    }
    if (sync) wait_for_controller();
    step_once();
    if (control_) control_->after_step();
    if (sim_->in_trouble()) {
      stop_reason_ = sim_->state().trouble.first;
      log::warn("run stopped: {}", stop_reason_);
      break;
    }
    if (scenario_.stop_when_all_found && all_found()) {
      stop_reason_ = "all victims found";
      break;
    }
    // realtime: wait for the wall clock to catch up with sim time / rate (steps asked for while
    // paused are taken at once, as lockstep steps)
    const bool realtime = control_ ? control_->realtime() : scenario_.realtime;
    if (realtime && !stepping_job) {
      const double rate = control_ ? control_->rate() : scenario_.rate;
      const double due = (sim_->time() - pace_start).seconds() / rate;
      const double now = std::chrono::duration<double>(clock::now() - pace_t0).count();
      if (due > now) std::this_thread::sleep_for(std::chrono::duration<double>(due - now));
    }
    if (progress && (sim_->state().step & 63) == 0) {
      const auto now = clock::now();
      if (now - last_report > std::chrono::milliseconds(100)) {
        last_report = now;
        wall_time_ = wall_before + std::chrono::duration<double>(now - t0).count();
        progress(result());
      }
    }
  }
  if (control_) control_->close();
  for (SubscriptionId h : scan_subscriptions) sim_->bus().unsubscribe(h);
  if (sync_timeouts_ > 1) log::warn("sync: {} scans in all got no cmd_vel in time", sync_timeouts_);
  // frames still being rendered belong to this run
  sim_->flush_cameras();
  wall_time_ = wall_before + std::chrono::duration<double>(clock::now() - t0).count();
  return result();
}

}  // namespace rescuesim
