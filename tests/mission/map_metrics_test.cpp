// Map scoring (mission/map_metrics.h: the SLAM demonstration's and the referee's) on worlds and maps
// small enough to check by hand: a perfect map scores 1, a map shifted by more than the
// tolerance fails, hidden walls are not counted against recall, and the trajectory error of
// known offsets comes out as computed on paper.

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "core/error.h"
#include "mission/map_metrics.h"

namespace rescuesim::map_eval {
namespace {

// a closed 6 m x 4 m room of 10 cm walls, 2 m high, with a 0.8 m x 0.8 m cabinet inside
WorldSpec room() {
  WorldSpec w;
  w.floor_min = Vec2(0, 0);
  w.floor_max = Vec2(6, 4);
  const Vec2 c[4] = {{0.05, 0.05}, {5.95, 0.05}, {5.95, 3.95}, {0.05, 3.95}};
  for (int k = 0; k < 4; ++k) {
    WallSpec wall;
    wall.a = c[k];
    wall.b = c[(k + 1) % 4];
    wall.thickness = 0.1;
    wall.height = 2.0;
    w.walls.push_back(wall);
  }
  BlockSpec cabinet;
  cabinet.outline = {{4, 1}, {4.8, 1}, {4.8, 1.8}, {4, 1.8}};
  cabinet.height = 1.2;
  w.blocks.push_back(cabinet);
  return w;
}

// a map that says exactly what the truth says: occupied where it is, free elsewhere
SlamMap map_of(const Grid& truth) {
  SlamMap m;
  m.grid = truth;
  for (auto& c : m.grid.cells) c = c ? kOccupied : kFree;
  return m;
}

long count(const Grid& g) {
  long n = 0;
  for (auto c : g.cells) n += c != 0;
  return n;
}

TEST(SlamMetrics, TrueOccupancyHasWallsAndTallObstaclesOnly) {
  WorldSpec w = room();
  BlockSpec low;  // a 20 cm step: under a laser 0.31 m above the floor
  low.outline = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  low.height = 0.2;
  w.blocks.push_back(low);
  const Grid g = true_occupancy(w, 0.05, 0.31);
  int i, j;
  g.cell_of(Vec2(3.0, 0.05), i, j);  // on the south wall
  EXPECT_EQ(g.at(i, j), 1);
  g.cell_of(Vec2(4.4, 1.4), i, j);  // inside the cabinet
  EXPECT_EQ(g.at(i, j), 1);
  g.cell_of(Vec2(1.5, 1.5), i, j);  // on the low step
  EXPECT_EQ(g.at(i, j), 0);
  g.cell_of(Vec2(3.0, 2.0), i, j);  // the middle of the room
  EXPECT_EQ(g.at(i, j), 0);
}

TEST(SlamMetrics, OnlyTheFirstSurfaceABeamHitsIsVisible) {
  // one beam along +x from (1, 2): it stops at the cabinet's west face (x = 4) and never
  // reaches the east wall behind it
  const Grid truth = true_occupancy(room(), 0.05, 0.31);
  LaserModel one_beam;
  one_beam.X_BL = {0, 0, 0};
  one_beam.min_angle = one_beam.max_angle = 0;
  one_beam.beams = 1;
  const Grid seen = visible_surface(truth, {Pose2{1, 1.4, 0}}, one_beam);
  ASSERT_EQ(count(seen), 1);
  for (int j = 0; j < seen.height; ++j)
    for (int i = 0; i < seen.width; ++i)
      if (seen.at(i, j)) {
        EXPECT_NEAR(seen.centre(i, j).x(), 3.975, 0.051);  // the cell touching x = 4
        EXPECT_NEAR(seen.centre(i, j).y(), 1.4, 0.026);
      }
  // a beam that is too short sees nothing
  one_beam.max_range = 2.0;
  EXPECT_EQ(count(visible_surface(truth, {Pose2{1, 1.4, 0}}, one_beam)), 0);
}

TEST(SlamMetrics, PerfectMapScoresOneAndShiftedMapFails) {
  const WorldSpec w = room();
  const Grid truth = true_occupancy(w, 0.05, 0.31);
  LaserModel laser;
  laser.X_BL = {0, 0, 0};
  laser.min_angle = -M_PI;
  laser.max_angle = M_PI;
  laser.beams = 2000;
  const Grid seen = visible_surface(truth, {Pose2{2, 2, 0}}, laser);
  const Grid none = ignore_mask(w, truth, 0.3);  // no victims: nothing ignored
  ASSERT_EQ(count(none), 0);
  ASSERT_GT(count(seen), 300);  // the inner faces of the walls and of the cabinet

  SlamMap map = map_of(truth);
  const MapScore perfect = score_map(map, Pose2{}, truth, seen, none);
  EXPECT_DOUBLE_EQ(perfect.precision, 1.0);
  EXPECT_DOUBLE_EQ(perfect.recall, 1.0);

  // one cell off is within the tolerance
  map.grid.origin += Vec2(0.05, 0);
  const MapScore one = score_map(map, Pose2{}, truth, seen, none);
  EXPECT_DOUBLE_EQ(one.precision, 1.0);
  EXPECT_DOUBLE_EQ(one.recall, 1.0);

  // 0.4 m off in x and y (8 cells each): only where the shifted walls cross the true ones, and
  // where the cabinet overlaps itself, do cells still match
  map.grid.origin = truth.origin + Vec2(0.4, 0.4);
  const MapScore off = score_map(map, Pose2{}, truth, seen, none);
  EXPECT_LT(off.precision, 0.3);
  EXPECT_LT(off.recall, 0.3);

  // the same shift undone by the alignment scores perfectly again
  const MapScore undone = score_map(map, Pose2{-0.4, -0.4, 0}, truth, seen, none);
  EXPECT_DOUBLE_EQ(undone.precision, 1.0);
  EXPECT_DOUBLE_EQ(undone.recall, 1.0);
}

TEST(SlamMetrics, CellsNearVictimsAreIgnored) {
  WorldSpec w = room();
  VictimSpec v;
  v.pose = {2, 2, 0};
  w.victims.push_back(v);
  const Grid truth = true_occupancy(w, 0.05, 0.31);
  const Grid ignore = ignore_mask(w, truth, 0.3);
  SlamMap map = map_of(truth);
  int i, j;
  map.grid.cell_of(Vec2(2, 2), i, j);
  map.grid.at(i, j) = kOccupied;  // the laser saw the person
  map.grid.cell_of(Vec2(3, 3), i, j);
  map.grid.at(i, j) = kOccupied;  // a ghost in the middle of the room
  const MapScore s = score_map(map, Pose2{}, truth, truth, ignore);
  EXPECT_EQ(s.map_ignored, 1);
  EXPECT_EQ(s.map_matched, s.map_occupied - 1);
}

TEST(SlamMetrics, TrajectoryErrorOfKnownOffsets) {
  // an L-shaped path of 11 poses along x then y
  std::vector<Pose2> truth, est;
  for (int k = 0; k <= 10; ++k) truth.push_back(k <= 5 ? Pose2{double(k), 0, 0} : Pose2{5, double(k - 5), M_PI / 2});
  // the same path in a frame rotated by 30 degrees about an offset origin: alignment undoes it
  const Pose2 X_MW{3, -1, M_PI / 6};
  for (const auto& p : truth) est.push_back(X_MW * p);
  EXPECT_NEAR(trajectory_error(truth, est, Alignment::start).rmse, 0.0, 1e-9);
  EXPECT_NEAR(trajectory_error(truth, est, Alignment::least_squares).rmse, 0.0, 1e-9);

  // the second half (poses 6..10, 5 of 11) drifts 0.3 m sideways: start-aligned RMSE is
  // sqrt(5 * 0.09 / 11); the least-squares fit spreads the error, so it is lower
  est = truth;
  for (int k = 6; k <= 10; ++k) est[k].x += 0.3;
  const auto e = trajectory_error(truth, est, Alignment::start);
  EXPECT_NEAR(e.rmse, std::sqrt(5 * 0.09 / 11), 1e-9);
  EXPECT_NEAR(e.max, 0.3, 1e-9);
  EXPECT_EQ(e.pairs, 11u);
  EXPECT_LT(trajectory_error(truth, est, Alignment::least_squares).rmse, e.rmse);
}

TEST(SlamMetrics, ReadsMapServerFilesAndNamesBadOnes) {
  const auto dir = std::filesystem::temp_directory_path() / ("slam_metrics_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  // a 3 x 2 image: top row (north) occupied, free, unknown; bottom row all free
  {
    std::ofstream pgm(dir / "map.pgm", std::ios::binary);
    pgm << "P5\n# a comment\n3 2\n255\n";
    const unsigned char px[6] = {0, 254, 205, 254, 254, 254};
    pgm.write(reinterpret_cast<const char*>(px), 6);
    std::ofstream(dir / "map.yaml") << "image: map.pgm\nresolution: 0.1\norigin: [-1.0, 2.0, 0.0]\nnegate: 0\n"
                                       "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
  }
  const SlamMap m = read_map(dir / "map.yaml");
  ASSERT_EQ(m.grid.width, 3);
  ASSERT_EQ(m.grid.height, 2);
  EXPECT_DOUBLE_EQ(m.grid.origin.x(), -1.0);
  EXPECT_DOUBLE_EQ(m.grid.origin.y(), 2.0);
  EXPECT_EQ(m.grid.at(0, 1), kOccupied);  // row j = 1 is the image's first row
  EXPECT_EQ(m.grid.at(1, 1), kFree);
  EXPECT_EQ(m.grid.at(2, 1), kUnknown);
  EXPECT_EQ(m.grid.at(2, 0), kFree);

  std::ofstream(dir / "bad.yaml") << "image: map.pgm\norigin: [0, 0, 0]\n";
  try {
    read_map(dir / "bad.yaml");
    ADD_FAILURE() << "a map without a resolution was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("resolution"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rescuesim::map_eval
