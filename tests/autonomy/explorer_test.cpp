// The frontier explorer driven in closed loop on a kinematic simulator (autonomy/kinematic_sim.h:
// 2-D walls, an ideal laser, unicycle motion): it waits for scan and odometry, explores random
// mazes without touching a wall, leaves a pillar it would circle for ever, gets out of dead ends
// and slipping wheels by planning to a frontier, and reaches goals. Every run is a function of
// sim time only (no wall clock): what happened is attached to a failing assertion as a trace.

#include "autonomy/explorer.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

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
  const int steps = static_cast<int>(std::lround(seconds / kDt));
  for (int k = 0; k < steps && run.visited.size() != all_cells; ++k) {
    const SimTime t = SimTime::from_ms(50) * k;
    if (before_step) before_step(t);
    explorer.on_odometry(sim.odometry(t));
    if (k % 2 == 0) {
      explorer.on_scan(sim.scan(t));
    }
    const msg::Twist cmd = explorer.command(t);
    sim.step(cmd, kDt);
    ++run.steps;
    const Vec2 p = sim.pose().position();
    if (run.visited.emplace(static_cast<int>(std::floor(p.x() / cell)), static_cast<int>(std::floor(p.y() / cell))).second) {
      run.first_visit_s.push_back((t + SimTime::from_ms(50)).seconds());
    }
  }
  return run;
}

// what a run did, for the trace of a failing assertion
std::string describe(const char* name, const RunLog& run, const KinematicSim& sim, const Explorer& e) {
  const ExplorerStats& s = e.stats();
  return fmt::format(
      "[{}] cells {}, distance {:.1f} m, min clearance {:.3f} m, collisions {}; plans {}, trips {}, reached {}, stuck(progress {}, "
      "blocked {}, looping {}), no frontier {}, path blocked {}, path stuck {}, abandoned {}, backups {}; last new cell at {:.1f} s",
      name, run.visited.size(), sim.distance(), sim.min_clearance(), sim.collisions(), s.plans, s.frontier_trips, s.frontiers_reached,
      s.stuck_no_progress, s.stuck_blocked, s.stuck_looping, s.no_frontier, s.path_blocked, s.path_stuck, s.abandoned, s.backups,
      run.time_to(run.first_visit_s.size()));
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
  EXPECT_EQ(e.map(SimTime{}).header.frame_id, "map");
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
  SCOPED_TRACE(describe(name.c_str(), run, sim, explorer));
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
  SCOPED_TRACE(describe("pillar", run, sim, explorer));
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
  SCOPED_TRACE(describe("dead end", run, sim, explorer));
  EXPECT_GE(explorer.stats().stuck_no_progress, 1);
  EXPECT_NE(explorer.last_stuck_reason(), StuckReason::none);
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
  SCOPED_TRACE(describe("slipping", run, sim, explorer));
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
  SCOPED_TRACE(describe("270 degrees", run, later, second));
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

TEST(Explorer, AWallFollowerMapsAtItsMapPeriodAndSteersTheSame) {
  // the laser at 10 Hz for 60 s: 600 scans. With map_period 0.5 s one scan in five is mapped,
  // the robot drives exactly as when it maps every scan (it steers by the laser), and the
  // map holds the same walls
  const auto run_with = [](double period, Pose2& end, long& occupied) {
    KinematicSim sim(testing::box(0, 0, 8, 6), {4.0, 1.0, 0.0}, kLaserMount, kRadius, 3.0);
    ExplorerConfig config;
    config.frontier_trips = false;
    config.scan_matching = false;
    config.map_period = period;
    Explorer explorer(kLaserMount, config);
    drive(explorer, sim, 60.0, 1.0);
    end = sim.pose();
    occupied = 0;
    const OccupancyMapper& map = explorer.mapper();
    for (int y = 0; y < map.height(); ++y) {
      for (int x = 0; x < map.width(); ++x) occupied += map.is_occupied({x, y});
    }
    return explorer.stats().scans;
  };
  Pose2 every_end, fifth_end;
  long every_occupied = 0, fifth_occupied = 0;
  EXPECT_EQ(run_with(0.0, every_end, every_occupied), 600);
  EXPECT_EQ(run_with(0.5, fifth_end, fifth_occupied), 120);
  EXPECT_EQ(fifth_end.x, every_end.x);
  EXPECT_EQ(fifth_end.y, every_end.y);
  EXPECT_EQ(fifth_end.yaw, every_end.yaw);
  // the walls' outline: 2 x (8 + 6) m at 0.05 m cells is about 560 cells
  EXPECT_GT(every_occupied, 450);
  EXPECT_NEAR(static_cast<double>(fifth_occupied), static_cast<double>(every_occupied), 0.05 * every_occupied);
}

TEST(Explorer, ADrivenPathMapsEveryScanWhateverTheMapPeriod) {
  KinematicSim sim(testing::carve_maze(4, 1.5, 3), {0.75, 0.75, 0.0}, kLaserMount, kRadius);
  ExplorerConfig config;
  config.frontier_trips = false;
  config.map_period = 0.5;
  Explorer explorer(kLaserMount, config);
  explorer.set_goal({5.25, 5.25});
  drive(explorer, sim, 10.0, 1.5);
  ASSERT_EQ(explorer.mode(), ExplorerMode::to_goal);
  EXPECT_EQ(explorer.stats().scans + explorer.stats().slipping_scans, 100);
}

// the explorer with a forward camera of 60 degrees and 4 m modelled (no joint turns it)
ExplorerConfig with_camera() {
  ExplorerConfig config;
  config.frontier_first = true;
  config.look.enabled = true;
  config.look.fan.hfov = M_PI / 3;
  config.look.fan.range = 4.0;
  return config;
}

// the share of the map's free cells the camera has looked at
double looked_share(const Explorer& e) {
  const OccupancyMapper& map = e.mapper();
  long free = 0, looked = 0;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      if (!map.is_free({x, y})) continue;
      ++free;
      looked += e.looked().looked({x, y});
    }
  }
  return free > 0 ? static_cast<double>(looked) / free : 0.0;
}

TEST(Explorer, GroundItsCameraHasNotSeenSendsItLookingRoundAnOpenRoom) {
  // a 6 m room the 360-degree laser maps at once: no frontier is ever left, so without the
  // camera modelled it never plans; with a forward camera it must turn and drive to look at
  // the ground behind it and round it
  {
    KinematicSim sim(testing::box(0, 0, 6, 6), {1.5, 3.0, 0.0}, kLaserMount, kRadius);
    ExplorerConfig config;
    config.frontier_first = true;
    Explorer explorer(kLaserMount, config);
    drive(explorer, sim, 10.0, 1.5);
    EXPECT_EQ(explorer.stats().look_trips, 0);
    EXPECT_EQ(explorer.looked().count(), 0);
  }
  KinematicSim sim(testing::box(0, 0, 6, 6), {1.5, 3.0, 0.0}, kLaserMount, kRadius);
  Explorer explorer(kLaserMount, with_camera());
  explorer.on_odometry(sim.odometry(SimTime{}));
  explorer.on_scan(sim.scan(SimTime{}));
  const OccupancyMapper& map = explorer.mapper();
  // the map frame is the odom frame, here the simulator's world
  EXPECT_LT(explorer.X_MO().position().norm(), 1e-9);
  // after the first scan: 2 m ahead seen, 1 m behind not
  EXPECT_TRUE(explorer.looked().looked(*map.world_to_cell({3.5, 3.0})));
  EXPECT_FALSE(explorer.looked().looked(*map.world_to_cell({0.5, 3.0})));
  const double first = looked_share(explorer);
  EXPECT_LT(first, 0.5);
  const RunLog run = drive(explorer, sim, 90.0, 1.5);
  SCOPED_TRACE(describe("look round", run, sim, explorer));
  EXPECT_GE(explorer.stats().look_trips, 1);
  EXPECT_GT(looked_share(explorer), 0.9);
  EXPECT_TRUE(explorer.looked().looked(*map.world_to_cell({0.5, 3.0})));
  EXPECT_EQ(sim.collisions(), 0);
}

TEST(Explorer, GroundATeammateHasLookedAtIsLeftToIt) {
  // the open room again, but a teammate said it has looked at all of it: nothing to look for
  KinematicSim sim(testing::box(0, 0, 6, 6), {1.5, 3.0, 0.0}, kLaserMount, kRadius);
  Explorer explorer(kLaserMount, with_camera());
  explorer.on_odometry(sim.odometry(SimTime{}));
  explorer.on_scan(sim.scan(SimTime{}));
  std::vector<Vec2> squares;
  for (double y = 0.25; y < 6; y += 0.5) {
    for (double x = 0.25; x < 6; x += 0.5) squares.emplace_back(x, y);
  }
  explorer.add_team_seen(squares, 0.5);
  const RunLog run = drive(explorer, sim, 20.0, 1.5);
  SCOPED_TRACE(describe("team saw it", run, sim, explorer));
  EXPECT_EQ(explorer.stats().look_trips, 0);
  EXPECT_TRUE(explorer.looked().looked_by_team(*explorer.mapper().world_to_cell({0.5, 3.0})));
}

TEST(Explorer, FrontiersATeammateHasLookedAtAreItsOwnWhenNothingElseIsLeft) {
  // a room with a door to a corridor that turns a corner: the only frontier is round the
  // corner. A teammate has looked at everything, but this robot's map does not know what lies
  // beyond that frontier, so it still goes there rather than think it is done
  const std::vector<Segment> walls = {{{0, 0}, {0, 6}},     {{0, 0}, {6, 0}},     {{0, 6}, {6, 6}},   {{6, 0}, {6, 2.5}},
                                      {{6, 3.5}, {6, 6}},   {{6, 2.5}, {9, 2.5}}, {{6, 3.5}, {10, 3.5}}, {{9, 2.5}, {9, -3}},
                                      {{10, 3.5}, {10, -3}}, {{9, -3}, {10, -3}}};
  std::vector<Vec2> squares;
  for (double y = -3.75; y < 6; y += 0.5) {
    for (double x = 0.25; x < 12; x += 0.5) squares.emplace_back(x, y);
  }
  for (const bool teammate : {false, true}) {
    KinematicSim sim(walls, {1.5, 3.0, 0.0}, kLaserMount, kRadius);
    Explorer explorer(kLaserMount, with_camera());
    explorer.on_odometry(sim.odometry(SimTime{}));
    explorer.on_scan(sim.scan(SimTime{}));
    if (teammate) explorer.add_team_seen(squares, 0.5);
    const RunLog run = drive(explorer, sim, 30.0, 1.5);
    SCOPED_TRACE(describe(teammate ? "teammate looked" : "alone", run, sim, explorer));
    EXPECT_GE(explorer.stats().frontier_trips, 1);
    EXPECT_EQ(explorer.stats().team_frontier_trips > 0, teammate);
    EXPECT_EQ(explorer.stats().look_trips > 0, !teammate);  // the room itself is the teammate's
    EXPECT_GT(sim.pose().x, 6.0);                            // through the door either way
    EXPECT_EQ(sim.collisions(), 0);
  }
}

TEST(Explorer, AFrontierATeammateHasMappedBeyondIsNoTargetAtAll) {
  // the room, the door and the corridor round the corner again; a teammate has looked at
  // everything and said so. When it has also said it mapped the corridor (its squares, 0.1 m,
  // free inside, occupied on the walls), the frontier at the door is explored: this robot
  // does not go through, not even as a last resort. Having mapped only the room, it does.
  const std::vector<Segment> walls = {{{0, 0}, {0, 6}},     {{0, 0}, {6, 0}},     {{0, 6}, {6, 6}},   {{6, 0}, {6, 2.5}},
                                      {{6, 3.5}, {6, 6}},   {{6, 2.5}, {9, 2.5}}, {{6, 3.5}, {10, 3.5}}, {{9, 2.5}, {9, -3}},
                                      {{10, 3.5}, {10, -3}}, {{9, -3}, {10, -3}}};
  const auto on_wall = [&](const Vec2& p) {
    return std::any_of(walls.begin(), walls.end(), [&](const Segment& w) { return distance_to_segment(p, w) <= 0.05; });
  };
  const auto in_room = [](const Vec2& p) { return p.x() > 0 && p.x() < 6 && p.y() > 0 && p.y() < 6; };
  const auto in_corridor = [](const Vec2& p) {
    return (p.x() >= 6 && p.x() < 10 && p.y() > 2.5 && p.y() < 3.5) || (p.x() > 9 && p.x() < 10 && p.y() > -3 && p.y() <= 3.5);
  };
  std::vector<Vec2> looked;
  for (double y = -3.75; y < 6; y += 0.5) {
    for (double x = 0.25; x < 12; x += 0.5) looked.emplace_back(x, y);
  }
  for (const bool corridor : {false, true}) {
    std::vector<std::pair<Vec2, CellState>> mapped;
    for (double y = -3.95; y < 6.1; y += 0.1) {
      for (double x = -0.05; x < 10.1; x += 0.1) {
        const Vec2 p(x, y);
        if (on_wall(p) && (corridor || p.x() <= 6.05)) mapped.emplace_back(p, CellState::occupied);
        else if (in_room(p) || (corridor && in_corridor(p))) mapped.emplace_back(p, CellState::free);
      }
    }
    KinematicSim sim(walls, {1.5, 3.0, 0.0}, kLaserMount, kRadius);
    Explorer explorer(kLaserMount, with_camera());
    explorer.on_odometry(sim.odometry(SimTime{}));
    explorer.on_scan(sim.scan(SimTime{}));
    explorer.add_team_seen(looked, 0.5);
    explorer.add_team_map(mapped, 0.1);
    // every map cell whose centre lies in a square is marked: 2 x 2 cells of 0.05 m per square
    const OccupancyMapper& map = explorer.mapper();
    EXPECT_TRUE(explorer.team_mapped(*map.world_to_cell({3.02, 3.02})));
    EXPECT_EQ(explorer.team_mapped(*map.world_to_cell({8.0, 3.0})), corridor);
    EXPECT_FALSE(explorer.team_mapped(*map.world_to_cell({11.0, 0.0})));
    const RunLog run = drive(explorer, sim, 30.0, 1.5);
    SCOPED_TRACE(describe(corridor ? "teammate mapped the corridor" : "teammate mapped the room", run, sim, explorer));
    EXPECT_EQ(explorer.stats().team_frontier_trips > 0, !corridor);
    EXPECT_EQ(sim.pose().x > 6.0, !corridor);  // through the door only when the corridor is news
    EXPECT_EQ(explorer.stats().look_trips, 0);  // the room is the teammate's either way
    EXPECT_EQ(sim.collisions(), 0);
  }
}

TEST(Explorer, SwingsTheCameraAndLooksWhereTheJointStands) {
  ExplorerConfig config = with_camera();
  config.look.yaw_joint = "pan";
  config.look.sweep_amplitude = 0.8;
  config.look.sweep_period = 4.0;
  Explorer explorer(kLaserMount, config);
  // a sine of 0.8 rad and 4 s: a quarter period in, at the left end; three quarters, the right
  EXPECT_NEAR(*explorer.look_command(SimTime::from_seconds(1.0)), 0.8, 1e-12);
  EXPECT_NEAR(*explorer.look_command(SimTime::from_seconds(3.0)), -0.8, 1e-12);
  EXPECT_NEAR(*explorer.look_command(SimTime::from_seconds(2.0)), 0.0, 1e-12);
  // a camera that looks 0.5 rad left when the joint is at 0 swings about joint -0.5
  ExplorerConfig offset = config;
  offset.look.fixed_yaw = 0.5;
  EXPECT_NEAR(*Explorer(kLaserMount, offset).look_command(SimTime::from_seconds(1.0)), 0.3, 1e-12);
  offset.look.yaw_sign = -1;  // and with the axis pointing down, the joint turns the other way
  EXPECT_NEAR(*Explorer(kLaserMount, offset).look_command(SimTime::from_seconds(1.0)), -0.3, 1e-12);
  // no joint, no amplitude or looking disabled: nothing to command
  EXPECT_FALSE(Explorer(kLaserMount, with_camera()).look_command(SimTime::from_seconds(1.0)));
  ExplorerConfig still = config;
  still.look.sweep_amplitude = 0;
  EXPECT_FALSE(Explorer(kLaserMount, still).look_command(SimTime::from_seconds(1.0)));
  EXPECT_FALSE(Explorer(kLaserMount).look_command(SimTime::from_seconds(1.0)));

  // the joint turned the camera half round: the first scan looks behind the robot
  KinematicSim sim(testing::box(0, 0, 6, 6), {3.0, 3.0, 0.0}, kLaserMount, kRadius);
  msg::JointState js;
  js.name = {"wheel", "pan"};
  js.position = {5.0, M_PI};
  explorer.on_joint_state(js);
  explorer.on_odometry(sim.odometry(SimTime{}));
  explorer.on_scan(sim.scan(SimTime{}));
  const OccupancyMapper& map = explorer.mapper();
  EXPECT_TRUE(explorer.looked().looked(*map.world_to_cell({1.0, 3.0})));   // 2 m behind
  EXPECT_FALSE(explorer.looked().looked(*map.world_to_cell({5.0, 3.0})));  // 2 m ahead
}

TEST(Explorer, AThinReturnStandingAloneIsTakenForAnotherRobotsMast) {
  // a room with a post 2 m ahead: 0.1 m square, as the simulator draws its walls
  std::vector<Segment> walls = testing::box(-1, -3, 8, 3);
  walls.push_back({{2.05, 0.0}, {2.05, 1e-4}});
  KinematicSim sim(walls, {0, 0, 0}, kLaserMount, kRadius);
  ExplorerConfig config;
  config.post_radius = 0.5;
  config.post_width = 0.15;
  Explorer e(kLaserMount, config);
  e.on_odometry(sim.odometry(SimTime{}));
  e.on_scan(sim.scan(SimTime{}));
  ASSERT_EQ(e.masts().size(), 1u);
  EXPECT_NEAR(e.masts()[0].x(), 2.0, 0.01);  // the returns lie on the post's near face
  EXPECT_NEAR(e.masts()[0].y(), 0.0, 0.03);
  // a robot alone (post_radius 0) looks for none
  Explorer alone(kLaserMount);
  alone.on_odometry(sim.odometry(SimTime{}));
  alone.on_scan(sim.scan(SimTime{}));
  EXPECT_TRUE(alone.masts().empty());
}

TEST(Explorer, AWallsEndSeenEdgeOnIsNoMastOnceTheWallIsMapped) {
  // a wall from (2, 1) to (6, 1); its end, seen from on the wall's line, is a thin return alone
  std::vector<Segment> walls = testing::box(-1, -3, 8, 3);
  walls.push_back({{2.0, 1.0}, {6.0, 1.0}});
  ExplorerConfig config;
  config.post_radius = 0.5;
  config.post_width = 0.15;
  // seen first from the wall's line, with nothing mapped yet: taken for a mast (a limit)
  {
    KinematicSim on_line(walls, {1, 1, 0}, kLaserMount, kRadius);
    Explorer e(kLaserMount, config);
    e.on_odometry(on_line.odometry(SimTime{}));
    e.on_scan(on_line.scan(SimTime{}));
    EXPECT_EQ(e.masts().size(), 1u);
  }
  // seen first from beside, where its side shows: then from the wall's line it is no mast
  KinematicSim sim(walls, {1, 0.5, 0}, kLaserMount, kRadius);
  Explorer e(kLaserMount, config);
  SimTime t;
  e.on_odometry(sim.odometry(t));
  e.on_scan(sim.scan(t));
  EXPECT_TRUE(e.masts().empty());
  // a quarter turn left, 0.5 m up, a quarter turn back: 20 steps of 50 ms each
  const auto move = [&](double v, double w) {
    msg::Twist cmd;
    cmd.linear.x() = v;
    cmd.angular.z() = w;
    for (int k = 0; k < 20; ++k) {
      sim.step(cmd, kDt);
      t += SimTime::from_ms(50);
      e.on_odometry(sim.odometry(t));
    }
  };
  move(0, M_PI / 2);
  move(0.5, 0);
  move(0, -M_PI / 2);
  ASSERT_NEAR(sim.pose().y, 1.0, 1e-6);
  ASSERT_NEAR(sim.pose().yaw, 0.0, 1e-6);
  e.on_scan(sim.scan(t));
  EXPECT_EQ(e.stats().scans, 2);
  EXPECT_TRUE(e.masts().empty());
}

TEST(Explorer, GoalModeDrivesAcrossTheMazeAndStops) {
  KinematicSim sim(testing::carve_maze(6, 1.5, 7), {0.75, 0.75, 0.0}, kLaserMount, kRadius);
  Explorer explorer(kLaserMount);
  const Vec2 goal(8.25, 8.25);
  explorer.set_goal(goal);
  const RunLog run = drive(explorer, sim, 400.0, 1.5);
  SCOPED_TRACE(describe("goal", run, sim, explorer));
  EXPECT_EQ(explorer.mode(), ExplorerMode::at_goal);
  EXPECT_LT((sim.pose().position() - goal).norm(), 0.3);
  EXPECT_EQ(sim.collisions(), 0);
}

TEST(Explorer, ScanMatchingKeepsThePoseWhileOdometryHeadingDrifts) {
  // odometry's heading runs off at 0.5 deg/s: after 120 s it is 60 deg off (by construction),
  // and the odometry position far off with it; matched against its own map the explorer's
  // pose stays within 0.15 m (3 cells) and 2 deg of the truth all along. The map frame starts
  // on the odom frame, which starts on the world frame.
  constexpr double kDrift = 0.5 * M_PI / 180;
  KinematicSim sim(testing::carve_maze(6, 1.5, 7), {0.75, 0.75, 0.3}, kLaserMount, kRadius);
  sim.set_heading_drift(kDrift);
  Explorer explorer(kLaserMount);
  double worst_position = 0, worst_heading = 0, odom_position = 0;
  const RunLog run = drive(explorer, sim, 120.0, 1.5, [&](SimTime t) {
    const auto X_MB = explorer.pose_in_map(t);
    if (!X_MB || t.ns % SimTime::from_seconds(1).ns != 0) return;
    // the explorer last heard odometry for t - 50 ms; the sim is at t: compare at the same instant
    const Pose2 truth = sim.pose(), X_OB = sim.odometry_pose();
    const Pose2 X_MB_now = explorer.X_MO() * X_OB;
    worst_position = std::max(worst_position, (X_MB_now.position() - truth.position()).norm());
    worst_heading = std::max(worst_heading, std::abs(wrap_angle(X_MB_now.yaw - truth.yaw)));
    odom_position = (X_OB.position() - truth.position()).norm();
  });
  SCOPED_TRACE(describe("heading drift", run, sim, explorer) +
               fmt::format("; worst map pose error {:.3f} m, {:.2f} deg; odometry {:.2f} m off at the end; matched {}, ambiguous {}, "
                           "unmatched {}",
                           worst_position, worst_heading * 180 / M_PI, odom_position, explorer.stats().scans_matched,
                           explorer.stats().scans_ambiguous, explorer.stats().scans_unmatched));
  EXPECT_NEAR(std::abs(wrap_angle(sim.odometry_pose().yaw - sim.pose().yaw)), 120 * kDrift, 1e-6);
  EXPECT_LT(worst_position, 0.15);
  EXPECT_LT(worst_heading, 2 * M_PI / 180);
  EXPECT_GT(odom_position, 1.0);
  EXPECT_GE(run.visited.size(), 10u);  // it explored meanwhile
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
