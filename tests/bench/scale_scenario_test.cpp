// The scale scenario of `rescuesim bench --scale` (issue 17): its maze, its robots, and a short
// run in which every robot's lidar scans at its rate. Counts, not times: the speed figures live
// in the bench.

#include "bench/scale_scenario.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "msgs/digest.h"
#include "robots/rescue_robot.h"
#include "session/session.h"

namespace rescuesim::bench {
namespace {

TEST(ScaleScenario, TwelveByTwelveCellsUpTo144RobotsThenTheSmallestSquareThatHoldsThem) {
  EXPECT_EQ(scale_maze_cells(1), 12);
  EXPECT_EQ(scale_maze_cells(144), 12);
  EXPECT_EQ(scale_maze_cells(145), 13);  // ceil(sqrt(145)) = 13
  EXPECT_EQ(scale_maze_cells(300), 18);  // 17^2 = 289 < 300 <= 324 = 18^2
  const ModelMap models = builtin_models();
  EXPECT_THROW(scale_scenario(0, 1, models), Error);
  EXPECT_THROW(scale_scenario(10001, 1, models), Error);
}

TEST(ScaleScenario, TenRobotsAtDistinctCellsEachScanAtTenHertz) {
  const ModelMap models = builtin_models();
  const Scenario s = scale_scenario(10, 3.0, models);
  ASSERT_TRUE(s.maze.has_value());
  EXPECT_EQ(s.maze->cols, 12);
  EXPECT_NEAR(s.maze->cell_size * s.maze->cols, 20.0, 1e-9);
  EXPECT_EQ(s.maze->victims, 0);
  EXPECT_EQ(s.maze->rubble, 0);
  ASSERT_EQ(s.robots.size(), 10u);
  SessionOptions so;
  so.cameras = false;
  Session session(s, models, so);
  // robot k at cell floor(144 k / 10): ten different cells
  std::set<std::pair<long, long>> cells;
  for (const auto& r : session.sim().world().robots) {
    const Vec3 p = r.X_W_start.p;
    cells.insert({std::lround(std::floor(p.x() / s.maze->cell_size)), std::lround(std::floor(p.y() / s.maze->cell_size))});
    EXPECT_EQ(r.spec.sensors.front().type, SensorSpec::Type::lidar);
  }
  EXPECT_EQ(cells.size(), 10u);
  std::size_t beams = 0;
  double range_max = 0;
  session.sim().bus().subscribe("/r7/scan", [&](const Topic&, const msg::Message& m) {
    const auto& scan = std::get<msg::LaserScan>(m);
    beams = scan.ranges.size();
    range_max = scan.range_max;
  });
  const RunResult r = session.run();
  EXPECT_EQ(r.sim_time, 3.0);
  // 10 Hz for 3 s, from the first step at 0 s through the last at 3.0 s: 31 scans from every robot
  for (int k = 1; k <= 10; ++k) {
    const std::string topic = "/r" + std::to_string(k) + "/scan";
    const auto it = std::find_if(r.message_counts.begin(), r.message_counts.end(), [&](const auto& c) { return c.first == topic; });
    ASSERT_NE(it, r.message_counts.end()) << topic;
    EXPECT_EQ(it->second, 31u) << topic;
  }
  EXPECT_EQ(beams, 1081u);
  EXPECT_EQ(range_max, 30.0);
}

/// Sixteen robots of the scale scenario (two physics worlds, automatic) for 2 s at `threads`
/// worker threads: the state hash, a digest of every message in publication order, and every
/// robot's distance driven.
struct Fingerprint {
  std::uint64_t state = 0, messages = 0;
  std::vector<double> distances;
  bool operator==(const Fingerprint&) const = default;
};
Fingerprint sixteen_robots(int threads) {
  const ModelMap models = builtin_models();
  SessionOptions so;
  so.cameras = false;
  set_worker_threads(threads);
  Session session(scale_scenario(16, 2.0, models), models, so);
  Fingerprint f;
  session.sim().bus().subscribe("", [&](const Topic& t, const msg::Message& m) {
    f.messages = f.messages * 1099511628211ull ^ (msg::digest(m) + static_cast<std::uint64_t>(t.id));
  });
  session.run();
  set_worker_threads(0);
  f.state = state_hash(session.sim().state());
  for (const auto& r : session.sim().state().robots) f.distances.push_back(r.distance);
  return f;
}

TEST(ScaleScenario, OneTwoOrFourWorkerThreadsGiveTheSameRun) {
  const Fingerprint one = sixteen_robots(1);
  // the robots moved: the wall followers drove (the run is not trivially the same)
  for (double d : one.distances) EXPECT_GT(d, 0.2);
  EXPECT_TRUE(sixteen_robots(2) == one);
  EXPECT_TRUE(sixteen_robots(4) == one);
}

}  // namespace
}  // namespace rescuesim::bench
