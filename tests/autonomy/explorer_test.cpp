#include "autonomy/explorer.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <limits>
#include <set>
#include <string>

#include "autonomy/kinematic_sim.h"

namespace rescuesim::autonomy {
namespace {

using testing::KinematicSim;
using testing::Segment;

constexpr double kRadius = 0.35;
constexpr double kDt = 0.05;  // 20 Hz control and odometry; the laser at 10 Hz
const Pose2 kLaserMount{0.1, 0.0, 0.0};

// what one closed-loop run did
struct RunLog {
  std::set<std::pair<int, int>> visited;  // maze cells the robot's centre entered
  std::vector<double> first_visit_s;      // sim time of each new cell's first visit
  double scan_us = 0, command_us = 0;     // mean wall time per call (measurement only)
  double max_command_us = 0;              // the dearest command (a plan)
  int steps = 0;

  // sim time (s) when n cells had been visited, or -1
  double time_to(std::size_t n) const { return n >= 1 && n <= first_visit_s.size() ? first_visit_s[n - 1] : -1; }
};

// drives the explorer in the simulator for `seconds` of sim time, or until `all_cells` cells
// have been visited; `before_step(t)` may change the world or the robot between steps
RunLog drive(Explorer& explorer, KinematicSim& sim, double seconds, double cell,
             const std::function<void(SimTime)>& before_step = {},
             std::size_t all_cells = std::numeric_limits<std::size_t>::max()) {
  RunLog run;
  using Clock = std::chrono::steady_clock;
  Clock::duration scan_time{}, command_time{};
  int scans = 0;
  const int steps = static_cast<int>(std::lround(seconds / kDt));
  for (int k = 0; k < steps && run.visited.size() != all_cells; ++k) {
    const SimTime t = SimTime::from_ms(50) * k;
    if (before_step) before_step(t);
    explorer.on_odometry(sim.odometry(t));
    if (k % 2 == 0) {
      const msg::LaserScan scan = sim.scan(t);
      const auto t0 = Clock::now();
      explorer.on_scan(scan);
      scan_time += Clock::now() - t0;
      ++scans;
    }
    const auto t0 = Clock::now();
    const msg::Twist cmd = explorer.command(t);
    const auto spent = Clock::now() - t0;
    command_time += spent;
    run.max_command_us = std::max(run.max_command_us, std::chrono::duration<double, std::micro>(spent).count());
    sim.step(cmd, kDt);
    ++run.steps;
    const Vec2 p = sim.pose().position();
    if (run.visited.emplace(static_cast<int>(std::floor(p.x() / cell)), static_cast<int>(std::floor(p.y() / cell))).second) {
      run.first_visit_s.push_back((t + SimTime::from_ms(50)).seconds());
    }
  }
  run.scan_us = std::chrono::duration<double, std::micro>(scan_time).count() / std::max(scans, 1);
  run.command_us = std::chrono::duration<double, std::micro>(command_time).count() / std::max(run.steps, 1);
  return run;
}

void print(const char* name, const RunLog& run, const KinematicSim& sim, const Explorer& e) {
  const ExplorerStats& s = e.stats();
  std::printf(
      "[%s] cells %zu, distance %.1f m, min clearance %.3f m, collisions %d; on_scan %.0f us, command %.0f us "
      "(max %.0f us); "
      "plans %d, trips %d, reached %d, stuck(progress %d, blocked %d, looping %d), no frontier %d, path blocked %d, "
      "path stuck %d, abandoned %d, backups %d\n",
      name, run.visited.size(), sim.distance(), sim.min_clearance(), sim.collisions(), run.scan_us, run.command_us,
      run.max_command_us,
      s.plans, s.frontier_trips, s.frontiers_reached, s.stuck_no_progress, s.stuck_blocked, s.stuck_looping,
      s.no_frontier, s.path_blocked, s.path_stuck, s.abandoned, s.backups);
}

TEST(Explorer, StandsStillUntilItHasScanAndOdometry) {
  Explorer e(kLaserMount);
  EXPECT_EQ(e.command(SimTime{}).linear.x(), 0.0);
  KinematicSim sim(testing::box(-3, -3, 3, 3), {0, 0, 0}, kLaserMount, kRadius);
  e.on_scan(sim.scan(SimTime{}));
  EXPECT_EQ(e.command(SimTime{}).linear.x(), 0.0);
  EXPECT_EQ(e.stats().scans, 0);  // no pose yet: not mapped
  e.on_odometry(sim.odometry(SimTime{}));
  e.on_scan(sim.scan(SimTime{}));
  EXPECT_EQ(e.stats().scans, 1);
  EXPECT_GT(e.command(SimTime{}).linear.x(), 0.0);
  EXPECT_EQ(e.map(SimTime{}).header.frame_id, "odom");
}

// a 6 x 6 maze of 1.5 m cells, carved from the given seed; the robot starts in a corner
class ExplorerMaze : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(ExplorerMaze, VisitsMostCellsWithoutTouchingAWall) {
  constexpr int kN = 6;
  constexpr double kCell = 1.5;
  KinematicSim sim(testing::carve_maze(kN, kCell, GetParam()), {0.75, 0.75, 0.3}, kLaserMount, kRadius);
  Explorer explorer(kLaserMount);
  const RunLog run = drive(explorer, sim, 600.0, kCell, {}, kN * kN);
  const std::string name = "maze seed " + std::to_string(GetParam());
  print(name.c_str(), run, sim, explorer);
  std::printf("[%s] 80%% of cells after %.1f s, all after %.1f s\n", name.c_str(), run.time_to(29), run.time_to(36));
  EXPECT_GE(run.visited.size(), static_cast<std::size_t>(0.8 * kN * kN));
  EXPECT_EQ(sim.collisions(), 0);
  EXPECT_GE(sim.min_clearance(), kRadius);
}

INSTANTIATE_TEST_SUITE_P(Seeds, ExplorerMaze, ::testing::Values(7, 1, 2));

TEST(Explorer, LeavesAPillarItWouldCircleForever) {
  // a 12 m room with a 3 m pillar; a short-range laser sees only the pillar while circling it,
  // so a right-hand wall follower alone would loop around it for ever
  std::vector<Segment> walls = testing::box(0, 0, 12, 12);
  for (const Segment& s : testing::box(4.5, 4.5, 7.5, 7.5)) walls.push_back(s);
  KinematicSim sim(walls, {7.0, 3.9, M_PI}, kLaserMount, kRadius, 3.0);
  Explorer explorer(kLaserMount);
  const RunLog run = drive(explorer, sim, 300.0, 1.5);
  print("pillar", run, sim, explorer);
  EXPECT_GE(explorer.stats().stuck_looping, 1);
  EXPECT_GE(explorer.stats().frontier_trips, 1);
  // it reached the room's outer ring (28 cells of 1.5 m along the outer wall)
  int outer = 0;
  for (const auto& [x, y] : run.visited) outer += (x == 0 || y == 0 || x == 7 || y == 7) ? 1 : 0;
  EXPECT_GE(outer, 20);
  EXPECT_EQ(sim.collisions(), 0);
}

TEST(Explorer, StuckInADeadEndTriggersAStarToAFrontier) {
  // start in the maze's dead end at cell (0, 0) facing its wall, wedged for the first 15 s
  KinematicSim sim(testing::carve_maze(6, 1.5, 7), {0.75, 0.75, M_PI}, kLaserMount, kRadius);
  sim.set_frozen(true);
  Explorer explorer(kLaserMount);
  bool saw_path = false;
  const RunLog run = drive(explorer, sim, 60.0, 1.5, [&](SimTime t) {
    if (t >= SimTime::from_seconds(15)) sim.set_frozen(false);
    saw_path = saw_path || (explorer.mode() == ExplorerMode::to_frontier && !explorer.current_path().poses.empty());
  });
  print("dead end", run, sim, explorer);
  EXPECT_GE(explorer.stats().stuck_no_progress, 1);
  EXPECT_EQ(explorer.last_stuck_reason() == StuckReason::none, false);
  EXPECT_GE(explorer.stats().plans, 1);
  EXPECT_TRUE(saw_path);
  EXPECT_GE(run.visited.size(), 3u);  // and once free it drove on
  EXPECT_EQ(sim.collisions(), 0);
}

TEST(Explorer, SlippingWheelsAreSeenByTheLaserAndItBacksOff) {
  // wedged with spinning wheels for 20 s: odometry runs on, the scans stay the same
  KinematicSim sim(testing::carve_maze(6, 1.5, 7), {0.75, 2.25, M_PI / 2}, kLaserMount, kRadius);
  Explorer explorer(kLaserMount);
  bool reversed = false;
  const RunLog run = drive(explorer, sim, 60.0, 1.5, [&](SimTime t) {
    sim.set_slipping(t >= SimTime::from_seconds(5) && t < SimTime::from_seconds(25));
    reversed = reversed || explorer.mode() == ExplorerMode::backing_up;
  });
  print("slipping", run, sim, explorer);
  EXPECT_GE(explorer.stats().stuck_no_progress, 1);
  EXPECT_GE(explorer.stats().backups, 1);
  EXPECT_TRUE(reversed);
  EXPECT_EQ(sim.collisions(), 0);
}

TEST(Explorer, WithA270DegreeLaserItReversesOnlyOverGroundItKnowsIsFree) {
  // wedged with its back 5 cm from a wall it cannot see: it must not back into it
  KinematicSim blind(testing::carve_maze(6, 1.5, 7), {0.75, 0.45, M_PI / 2}, kLaserMount, kRadius);
  blind.set_fov(270);
  Explorer first(kLaserMount);
  drive(first, blind, 15.0, 1.5, [&](SimTime t) { blind.set_slipping(t < SimTime::from_seconds(15)); });
  EXPECT_GE(first.stats().stuck_no_progress, 1);
  EXPECT_EQ(first.stats().backups, 0);
  EXPECT_EQ(blind.collisions(), 0);

  // wedged after driving a while: the ground it came over is mapped free, so it backs up
  KinematicSim later(testing::carve_maze(6, 1.5, 7), {0.75, 0.75, M_PI / 2}, kLaserMount, kRadius);
  later.set_fov(270);
  Explorer second(kLaserMount);
  const RunLog run = drive(second, later, 40.0, 1.5, [&](SimTime t) {
    later.set_slipping(t >= SimTime::from_seconds(6) && t < SimTime::from_seconds(20));
  });
  print("270 degrees", run, later, second);
  EXPECT_GE(second.stats().backups, 1);
  EXPECT_EQ(later.collisions(), 0);
}

TEST(Explorer, WithoutFrontierTripsItOnlyFollowsWalls) {
  std::vector<Segment> walls = testing::box(0, 0, 12, 12);
  for (const Segment& s : testing::box(4.5, 4.5, 7.5, 7.5)) walls.push_back(s);
  KinematicSim sim(walls, {7.0, 3.9, M_PI}, kLaserMount, kRadius, 3.0);
  ExplorerConfig config;
  config.frontier_trips = false;
  Explorer explorer(kLaserMount, config);
  const RunLog run = drive(explorer, sim, 120.0, 1.5);
  EXPECT_EQ(explorer.stats().plans, 0);
  EXPECT_EQ(explorer.mode(), ExplorerMode::wall_following);
  EXPECT_EQ(run.visited.size(), 12u);  // the ring of cells round the pillar, for ever
  EXPECT_EQ(sim.collisions(), 0);
}

TEST(Explorer, GoalModeDrivesAcrossTheMazeAndStops) {
  KinematicSim sim(testing::carve_maze(6, 1.5, 7), {0.75, 0.75, 0.0}, kLaserMount, kRadius);
  Explorer explorer(kLaserMount);
  const Vec2 goal(8.25, 8.25);
  explorer.set_goal(goal);
  const RunLog run = drive(explorer, sim, 400.0, 1.5);
  print("goal", run, sim, explorer);
  EXPECT_EQ(explorer.mode(), ExplorerMode::at_goal);
  EXPECT_LT((sim.pose().position() - goal).norm(), 0.3);
  EXPECT_EQ(sim.collisions(), 0);
}

TEST(Explorer, SameInputsGiveTheSameRun) {
  auto final_pose = [] {
    KinematicSim sim(testing::carve_maze(6, 1.5, 11), {0.75, 0.75, 0.3}, kLaserMount, kRadius);
    Explorer explorer(kLaserMount);
    drive(explorer, sim, 120.0, 1.5);
    return std::tuple{sim.pose().x, sim.pose().y, sim.pose().yaw, explorer.stats().plans};
  };
  EXPECT_EQ(final_pose(), final_pose());
}

}  // namespace
}  // namespace rescuesim::autonomy
