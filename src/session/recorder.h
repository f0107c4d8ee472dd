#pragma once
/// What a run records as it goes, a RunSystem (sim/run_system.h): the trajectory of the
/// scenario's robots (ground truth and odometry at a sample rate, thinned evenly when it grows
/// long), the coverage of the free floor (CoverageGrid) and each robot's last laser scan (for
/// sensors/laser.png). Robots spawned while running are not recorded: they come and go, and the
/// trajectory is kept in groups of one sample per robot.

#include <any>
#include <cstdint>
#include <vector>

#include "core/index.h"
#include "core/polygon.h"
#include "core/pose.h"
#include "core/sim_time.h"
#include "msgs/messages.h"
#include "sim/run_system.h"
#include "world/world_spec.h"

namespace rescuesim {

/// One trajectory sample.
struct TrajectoryPoint {
  double t = 0;
  RobotIndex robot{0};
  Pose2 truth, odom;
  double v = 0, w = 0;
};

/// The free floor in square cells (kCell), and the cells a robot has passed within kRadius of.
class CoverageGrid {
 public:
  static constexpr double kCell = 0.5;    ///< m
  static constexpr double kRadius = 1.0;  ///< m around the path counts as covered

  /// The cells of `spec`'s floor that no wall or block covers (at their centres).
  explicit CoverageGrid(const WorldSpec& spec);
  /// Marks the free cells within kRadius of `p_W` as covered.
  void pass(const Vec2& p_W);
  /// Covered free cells over free cells (0 when the floor has none).
  double fraction() const;

  const std::vector<std::uint8_t>& visited() const { return visited_; }
  void set_visited(std::vector<std::uint8_t> visited) { visited_ = std::move(visited); }

 private:
  Box2 box_;
  int w_ = 0, h_ = 0;
  std::vector<std::uint8_t> free_, visited_;
};

class Recorder final : public RunSystem {
 public:
  /// Samples at `rate` Hz, keeping at most `max_points` samples (SessionOptions); listens to
  /// each scenario robot's first enabled laser.
  Recorder(Simulation& sim, const WorldSpec& spec, double rate, std::size_t max_points);

  std::string_view system_name() const override { return "recorder"; }
  void post_step(Simulation& sim) override { record(sim); }
  std::any save() const override;
  void load(const std::any& memory, Simulation& sim) override;
  /// trajectory.csv, each robot's path on the overview, sensors/laser.png (laser_<robot>.png
  /// with more than one scenario robot): each laser's last scan as a polar plot.
  void write_outputs(const Simulation& sim, RunOutputs& out) const override;

  /// Takes the sample due at the simulation's time (none when it is not due yet).
  void record(const Simulation& sim);

  /// Samples at record_interval(), robots in order per time.
  const std::vector<TrajectoryPoint>& trajectory() const { return memory_.trajectory; }
  SimTime record_interval() const { return memory_.record_interval; }
  double coverage() const { return coverage_.fraction(); }
  /// Per robot: its laser's last scan (empty when it has none or has not scanned yet).
  const std::vector<msg::LaserScan>& last_scans() const { return memory_.last_scans; }

 private:
  struct Memory {
    std::vector<TrajectoryPoint> trajectory;
    SimTime next_record;
    SimTime record_interval;  ///< between trajectory samples: 1/rate, doubled at each thinning
    std::vector<msg::LaserScan> last_scans;
    std::vector<std::uint8_t> visited;  ///< CoverageGrid's (filled by save())
  };
  /// Drops every other sample time from the trajectory and doubles the interval; true when the
  /// sample due now falls on the new grid.
  bool thin_trajectory(std::size_t group);

  std::size_t max_points_;
  CoverageGrid coverage_;
  Memory memory_;
};

}  // namespace rescuesim
