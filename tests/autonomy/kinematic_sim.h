#pragma once
// Test support: a tiny kinematic simulator for the autonomy tests. Walls are line segments
// with a thickness (0.1 m, as in rescuesim worlds), the robot a disc driven as a unicycle from
// Twist commands, the laser a planar fan of rays intersected with the walls' outlines,
// odometry perfect unless told to slip or drift. Mazes are carved by a seeded depth-first
// search on core's Rng, so every run sees the same world.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/pose.h"
#include "core/rng.h"
#include "core/sim_time.h"
#include "msgs/messages.h"

namespace rescuesim::autonomy::testing {

struct Segment {
  Vec2 a, b;
};

// distance (m) from p to the segment
inline double distance_to_segment(const Vec2& p, const Segment& s) {
  const Vec2 ab = s.b - s.a;
  const double t = std::clamp((p - s.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (s.a + t * ab)).norm();
}

// distance along the ray from o in direction u to the nearest segment, +inf for none
inline double ray_cast(const Vec2& o, const Vec2& u, const std::vector<Segment>& walls) {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : walls) {
    const Vec2 e = s.b - s.a, w = s.a - o;
    const double den = u.x() * e.y() - u.y() * e.x();
    if (std::abs(den) < 1e-12) continue;
    const double t = (w.x() * e.y() - w.y() * e.x()) / den;  // along the ray
    const double v = (w.x() * u.y() - w.y() * u.x()) / den;  // along the segment
    if (t > 0 && v >= 0 && v <= 1) best = std::min(best, t);
  }
  return best;
}

// a square box [x0, x1] x [y0, y1] as four segments
inline std::vector<Segment> box(double x0, double y0, double x1, double y1) {
  return {{{x0, y0}, {x1, y0}}, {{x1, y0}, {x1, y1}}, {{x1, y1}, {x0, y1}}, {{x0, y1}, {x0, y0}}};
}

// an n x n perfect maze of square cells (m) with its lower-left corner at the origin, carved
// by randomised depth-first search from cell (0, 0)
inline std::vector<Segment> carve_maze(int n, double cell, std::uint64_t seed) {
  // open_east[x][y]: passage from (x, y) to (x + 1, y); open_north likewise to (x, y + 1)
  std::vector<std::vector<bool>> open_east(n, std::vector<bool>(n, false)), open_north = open_east, seen = open_east;
  Rng rng(seed, "maze");
  std::vector<std::pair<int, int>> stack{{0, 0}};
  seen[0][0] = true;
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    std::vector<std::pair<int, int>> next;
    const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int nx = x + dx[k], ny = y + dy[k];
      if (nx >= 0 && ny >= 0 && nx < n && ny < n && !seen[nx][ny]) next.emplace_back(nx, ny);
    }
    if (next.empty()) {
      stack.pop_back();
      continue;
    }
    const auto [nx, ny] = next[rng.below(static_cast<std::uint32_t>(next.size()))];
    if (nx != x) open_east[std::min(x, nx)][y] = true;
    else open_north[x][std::min(y, ny)] = true;
    seen[nx][ny] = true;
    stack.emplace_back(nx, ny);
  }
  std::vector<Segment> walls = box(0, 0, n * cell, n * cell);
  for (int x = 0; x < n; ++x) {
    for (int y = 0; y < n; ++y) {
      if (x + 1 < n && !open_east[x][y]) walls.push_back({{(x + 1) * cell, y * cell}, {(x + 1) * cell, (y + 1) * cell}});
      if (y + 1 < n && !open_north[x][y]) walls.push_back({{x * cell, (y + 1) * cell}, {(x + 1) * cell, (y + 1) * cell}});
    }
  }
  return walls;
}

// the four sides of a wall of the given thickness around its centre line
inline std::vector<Segment> outline(const Segment& s, double thickness) {
  const Vec2 u = (s.b - s.a).normalized(), n(-u.y(), u.x());
  const double h = thickness / 2;
  const Vec2 a0 = s.a - h * u - h * n, a1 = s.a - h * u + h * n, b0 = s.b + h * u - h * n, b1 = s.b + h * u + h * n;
  return {{a0, b0}, {b0, b1}, {b1, a1}, {a1, a0}};
}

// the robot, its laser and its odometry in a world of walls
class KinematicSim {
 public:
  static constexpr double kWallThickness = 0.1;  // m

  KinematicSim(std::vector<Segment> walls, Pose2 start, Pose2 X_BS, double radius, double range_max = 10.0)
      : walls_(std::move(walls)), X_WB_(start), X_BS_(X_BS), radius_(radius), range_max_(range_max) {
    for (const Segment& w : walls_) {
      for (const Segment& e : outline(w, kWallThickness)) edges_.push_back(e);
    }
  }

  // a scan with a beam every degree over the field of view (full circle by default) from the
  // current pose, stamped t (REP-117 ranges)
  msg::LaserScan scan(SimTime t) const {
    msg::LaserScan s;
    s.header = {t, "laser"};
    const int beams = static_cast<int>(std::lround(fov_deg_));
    s.angle_increment = static_cast<float>(M_PI / 180);
    s.angle_min = static_cast<float>(-fov_deg_ / 2 * M_PI / 180);
    s.angle_max = s.angle_min + (beams - 1) * s.angle_increment;
    s.range_min = 0.05f;
    s.range_max = static_cast<float>(range_max_);
    s.scan_time = 0.1f;
    const Pose2 X_WS = X_WB_ * X_BS_;
    for (int i = 0; i < beams; ++i) {
      const double a = X_WS.yaw + s.angle_min + i * static_cast<double>(s.angle_increment);
      const double r = ray_cast(X_WS.position(), Vec2(std::cos(a), std::sin(a)), edges_);
      if (r < s.range_min) s.ranges.push_back(-std::numeric_limits<float>::infinity());
      else if (r >= range_max_) s.ranges.push_back(std::numeric_limits<float>::infinity());
      else s.ranges.push_back(static_cast<float>(r));
    }
    return s;
  }

  // odometry: perfect (odom coincides with the world frame) until the wheels slip
  msg::Odometry odometry(SimTime t) const {
    msg::Odometry o;
    o.header = {t, "odom"};
    o.child_frame_id = "base_link";
    o.pose = Pose3::from_pose2(X_OW_ * X_WB_);
    return o;
  }

  // drives for dt seconds in small substeps; a substep that would overlap a wall is refused
  // and counted as a collision
  void step(const msg::Twist& cmd, double dt) {
    constexpr int kSub = 10;
    const double h = dt / kSub;
    for (int k = 0; k < kSub; ++k) {
      // a heading drift turns the odom frame about the robot, so later motion is counted askew
      if (drift_ != 0) X_OW_ = X_OW_ * X_WB_ * Pose2{0, 0, drift_ * h} * X_WB_.inverse();
      const double v = frozen_ ? 0.0 : cmd.linear.x(), w = frozen_ ? 0.0 : cmd.angular.z();
      if (slipping_) {
        // the wheels turn, the robot does not: odometry drifts away from the world
        const Pose2 X_OB = X_OW_ * X_WB_;
        const Pose2 moved = X_OB * Pose2{v * h, 0.0, w * h};
        X_OW_ = moved * X_WB_.inverse();
        continue;
      }
      Pose2 next = X_WB_;
      next.x += v * std::cos(X_WB_.yaw + 0.5 * w * h) * h;
      next.y += v * std::sin(X_WB_.yaw + 0.5 * w * h) * h;
      next.yaw = wrap_angle(X_WB_.yaw + w * h);
      const double c = clearance(next.position());
      if (c < radius_) {
        ++collisions_;
        continue;
      }
      min_clearance_ = std::min(min_clearance_, c);
      distance_ += (next.position() - X_WB_.position()).norm();
      X_WB_ = next;
    }
  }

  // distance from p to the nearest wall surface (its centre line less half its thickness)
  double clearance(const Vec2& p) const {
    double c = std::numeric_limits<double>::infinity();
    for (const Segment& s : walls_) c = std::min(c, distance_to_segment(p, s) - kWallThickness / 2);
    return c;
  }

  const Pose2& pose() const { return X_WB_; }
  int collisions() const { return collisions_; }
  double min_clearance() const { return min_clearance_; }
  double distance() const { return distance_; }
  // while frozen the wheels are blocked: neither robot nor odometry moves
  void set_frozen(bool f) { frozen_ = f; }
  // a laser seeing only `degrees` round its front (360: all round)
  void set_fov(double degrees) { fov_deg_ = degrees; }
  // while slipping the wheels spin without moving the robot (wedged on low debris), and
  // odometry counts the spinning
  void set_slipping(bool s) { slipping_ = s; }
  // odometry's heading runs off at this rate (rad/s, a gyro bias), moving or not
  void set_heading_drift(double rad_per_s) { drift_ = rad_per_s; }
  // the odometry pose of base_link (odom frame) now
  Pose2 odometry_pose() const { return X_OW_ * X_WB_; }

 private:
  std::vector<Segment> walls_;  // centre lines
  std::vector<Segment> edges_;  // their outlines, for the laser
  Pose2 X_WB_;
  Pose2 X_BS_;
  double radius_;
  double range_max_;
  Pose2 X_OW_;  // odometry's drift: the world frame in the odom frame
  bool frozen_ = false;
  bool slipping_ = false;
  double drift_ = 0;  // rad/s
  double fov_deg_ = 360;
  int collisions_ = 0;
  double min_clearance_ = std::numeric_limits<double>::infinity();
  double distance_ = 0;
};

}  // namespace rescuesim::autonomy::testing
