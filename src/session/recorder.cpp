#include "session/recorder.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "sim/simulation.h"

namespace rescuesim {

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
        sim.bus().subscribe(sim.topic_name(static_cast<int>(r), s.topic),
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
    memory_.trajectory.push_back({s.time.seconds(), static_cast<int>(r), truth, rs.odom, v_B.x(), rs.base.w_WB.z()});
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

}  // namespace rescuesim
