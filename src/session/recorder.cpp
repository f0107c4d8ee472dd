#include "session/recorder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/atomic_file.h"
#include "core/error.h"
#include "sim/run_outputs.h"
#include "sim/simulation.h"
#include "viz/canvas.h"

namespace rescuesim {

namespace {

std::string trajectory_csv(const std::vector<TrajectoryPoint>& traj, const World& world) {
  std::string out = "t,robot,x,y,yaw,odom_x,odom_y,odom_yaw,v,w\n";
  char line[256];
  for (const auto& p : traj) {
    std::snprintf(line, sizeof line, "%.3f,%s,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", p.t, world.robot(p.robot).name.c_str(), p.truth.x,
                  p.truth.y, p.truth.yaw, p.odom.x, p.odom.y, p.odom.yaw, p.v, p.w);
    out += line;
  }
  return out;
}

/// A polar plot of a laser scan: the robot at the centre, 1 m rings, returns as dots.
Canvas laser_plot(const msg::LaserScan& scan, const std::string& title) {
  const int size = 520, c = size / 2;
  Canvas img(size, size + 24, {255, 255, 255});
  const double max_r = std::min<double>(scan.range_max > 0 ? scan.range_max : 10.0, 10.0);
  const double scale = (size / 2.0 - 20) / max_r;
  for (int ring = 1; ring <= static_cast<int>(max_r); ++ring) img.circle({c, c}, ring * scale, {225, 225, 225}, 1.0);
  img.line({c - 10.0, double(c)}, {c + 10.0, double(c)}, {150, 150, 150});
  img.line({double(c), c - 10.0}, {double(c), c + 10.0}, {150, 150, 150});
  // x forward points up the image, y left points left
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double a = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
    const Vec2 dir(-std::sin(a), -std::cos(a));
    const float r = scan.ranges[i];
    if (std::isfinite(r)) {
      img.line({double(c), double(c)}, Vec2(c, c) + dir * r * scale, {200, 225, 255}, 1.0, 0.5);
      img.fill_circle(Vec2(c, c) + dir * r * scale, 1.8, {200, 30, 30});
    }
  }
  img.fill_circle({double(c), double(c)}, 5, {44, 160, 44});
  img.text(8, size + 6, title + "  (rings 1 m)", {0, 0, 0}, 1);
  return img;
}

}  // namespace

CoverageGrid::CoverageGrid(const WorldSpec& spec) : box_{spec.floor_min, spec.floor_max} {
  w_ = std::max(1, static_cast<int>(std::ceil(box_.size().x() / kCell)));
  h_ = std::max(1, static_cast<int>(std::ceil(box_.size().y() / kCell)));
  free_.assign(static_cast<std::size_t>(w_ * h_), 1);
  visited_.assign(free_.size(), 0);
  for (int y = 0; y < h_; ++y) {
    for (int x = 0; x < w_; ++x) {
      const Vec2 c = box_.min + Vec2((x + 0.5) * kCell, (y + 0.5) * kCell);
      bool solid = false;
      for (const auto& w : spec.walls) solid = solid || contains(WorldSpec::wall_outline(w), c, 0);
      for (const auto& b : spec.blocks) solid = solid || contains(b.outline, c, 0);
      free_[static_cast<std::size_t>(y * w_ + x)] = solid ? 0 : 1;
    }
  }
}

void CoverageGrid::pass(const Vec2& p_W) {
  const int reach = static_cast<int>(std::ceil(kRadius / kCell));
  const int cx = static_cast<int>(std::floor((p_W.x() - box_.min.x()) / kCell));
  const int cy = static_cast<int>(std::floor((p_W.y() - box_.min.y()) / kCell));
  for (int y = cy - reach; y <= cy + reach; ++y) {
    for (int x = cx - reach; x <= cx + reach; ++x) {
      if (x < 0 || y < 0 || x >= w_ || y >= h_) continue;
      const Vec2 c = box_.min + Vec2((x + 0.5) * kCell, (y + 0.5) * kCell);
      if ((c - p_W).norm() <= kRadius) visited_[static_cast<std::size_t>(y * w_ + x)] = 1;
    }
  }
}

double CoverageGrid::fraction() const {
  int free = 0, seen = 0;
  for (std::size_t i = 0; i < free_.size(); ++i) {
    free += free_[i];
    seen += free_[i] & visited_[i];
  }
  return free > 0 ? static_cast<double>(seen) / free : 0.0;
}

Recorder::Recorder(Simulation& sim, const WorldSpec& spec, double rate, std::size_t max_points) : max_points_(max_points), coverage_(spec) {
  if (!(rate > 0)) throw Error("SessionOptions::trajectory_rate must be > 0 Hz");
  memory_.record_interval = SimTime::from_seconds(1.0 / rate);
  const std::size_t robots = sim.world().robots.size();
  memory_.last_scans.resize(robots);
  for (std::size_t r = 0; r < robots; ++r) {
    for (const auto& s : sim.world().robots[r].spec.sensors) {
      if (s.enabled && s.type == SensorSpec::Type::lidar && s.lidar.layers == 1) {
        sim.bus().subscribe(sim.topic_name(RobotIndex::at(r), s.topic),
                            [this, r](const Topic&, const msg::Message& m) { memory_.last_scans[r] = std::get<msg::LaserScan>(m); });
        break;
      }
    }
  }
}

bool Recorder::thin_trajectory(std::size_t group) {
  // samples come in groups of one per robot at each sample time: keep groups 0, 2, 4, ...
  std::vector<TrajectoryPoint>& traj = memory_.trajectory;
  const std::size_t groups = traj.size() / group;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < traj.size(); i += 2 * group) {
    for (std::size_t k = 0; k < group && i + k < traj.size(); ++k) traj[kept++] = traj[i + k];
  }
  traj.resize(kept);
  memory_.record_interval = memory_.record_interval + memory_.record_interval;
  // the sample due now is group number `groups`: on the new grid when that is even
  return groups % 2 == 0;
}

void Recorder::record(const Simulation& sim) {
  const State& s = sim.state();
  if (s.time < memory_.next_record) return;
  // the scenario's robots only: robots spawned while running come and go, and the trajectory
  // is kept in groups of one sample per robot
  const std::size_t robots = std::min(s.robots.size(), sim.base_robots());
  if (robots > 0 && memory_.trajectory.size() + robots > max_points_) {
    const SimTime before = memory_.record_interval;
    if (!thin_trajectory(sim.base_robots())) {
      memory_.next_record = s.time + before;  // the sample due now falls between the kept ones
      return;
    }
  }
  memory_.next_record = s.time + memory_.record_interval;
  for (std::size_t r = 0; r < robots; ++r) {
    const RobotState& rs = s.robots[r];
    const Pose2 truth = rs.base.X_WB.to_pose2();
    const Vec3 v_B = rs.base.X_WB.q.conjugate() * rs.base.v_WB;
    memory_.trajectory.push_back({s.time.seconds(), RobotIndex::at(r), truth, rs.odom, v_B.x(), rs.base.w_WB.z()});
    coverage_.pass(truth.position());
  }
}

std::any Recorder::save() const {
  Memory m = memory_;
  m.visited = coverage_.visited();
  return m;
}

void Recorder::load(const std::any& memory, Simulation&) {
  const Memory& m = std::any_cast<const Memory&>(memory);
  memory_ = m;
  coverage_.set_visited(m.visited);
}

void Recorder::write_outputs(const Simulation& sim, RunOutputs& out) const {
  const World& world = sim.world();
  write_file_atomic(out.dir / "trajectory.csv", trajectory_csv(memory_.trajectory, world));
  // each robot's path on the overview, its last position a dot
  for (RobotIndex r : world.robot_indices()) {
    std::vector<Vec2> path;
    for (const auto& p : memory_.trajectory) {
      if (p.robot == r) path.push_back(out.frame.to_px(p.truth.position()));
    }
    out.overview.polyline(path, {20, 160, 60}, 2.0);
    if (!path.empty()) out.overview.fill_circle(path.back(), 5, {20, 120, 40});
  }
  // each laser's last scan
  const std::vector<msg::LaserScan>& scans = memory_.last_scans;
  for (std::size_t r = 0; r < scans.size(); ++r) {
    if (scans[r].ranges.empty()) continue;
    const std::string& name = world.robots[r].name;
    char t[64];
    std::snprintf(t, sizeof t, "%.1f s", scans[r].header.stamp.seconds());
    laser_plot(scans[r], name + " laser at " + t)
        .write_png(out.dir / "sensors" / (sim.base_robots() > 1 ? "laser_" + name + ".png" : "laser.png"));
  }
}

}  // namespace rescuesim
