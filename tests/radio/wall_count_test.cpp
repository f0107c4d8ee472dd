// Wall counting between radios through the ray scene, on walls placed by hand: each wall
// crossed counts once, grazing a face, ending or starting inside a wall, and what does not
// count (floor, rubble).

#include "radio/wall_count.h"

#include <gtest/gtest.h>

#include <cmath>

#include "radio_test_worlds.h"

namespace rescuesim {
namespace {

using radio_test::walls_across_x;

TEST(WallCounter, CountsEachWallCrossedOnce) {
  // walls centred at x = 3 and x = 6 (faces at 2.95/3.05 and 5.95/6.05)
  const World world = walls_across_x({3, 6});
  const RayScene scene(world);
  const WallCounter walls(scene, world);
  EXPECT_EQ(walls.count({0, 0, 0.5}, {10, 0, 0.5}), 2);
  EXPECT_EQ(walls.count({10, 0, 0.5}, {0, 0, 0.5}), 2);  // either direction
  EXPECT_EQ(walls.count({0, 0, 0.5}, {4, 0, 0.5}), 1);   // only the first
  EXPECT_EQ(walls.count({0, 0, 0.5}, {2, 0, 0.5}), 0);   // stops short of both
  EXPECT_EQ(walls.count({0, 0, 1.5}, {10, 0, 1.5}), 0);  // above the 1 m walls
  // slanted, still through both (y stays within ±5 where the walls are)
  EXPECT_EQ(walls.count({0, -2, 0.2}, {10, 3, 0.8}), 2);
  // the cap
  EXPECT_EQ(walls.count({0, 0, 0.5}, {10, 0, 0.5}, 1), 1);
}

TEST(WallCounter, SegmentInTheFacePlaneDoesNotCountTheWall) {
  // the wall at x = 3 has its west face in the plane x = 2.95; a segment lying in that plane
  // (within the face) grazes it, and the ray tracer reports no hit for a ray in a triangle's
  // plane: not counted. 1 mm off the face, outside: not counted either.
  const World world = walls_across_x({3});
  const RayScene scene(world);
  const WallCounter walls(scene, world);
  EXPECT_EQ(walls.count({2.95, -3, 0.5}, {2.95, 3, 0.5}), 0);
  EXPECT_EQ(walls.count({2.949, -3, 0.5}, {2.949, 3, 0.5}), 0);
  // inside the wall, along its length: it enters through neither face; it starts and ends
  // inside, and the end caps at y = ±5 are not reached: 0
  EXPECT_EQ(walls.count({3.0, -3, 0.5}, {3.0, 3, 0.5}), 0);
}

TEST(WallCounter, SegmentEndingOrStartingInsideAWallCountsItOnce) {
  const World world = walls_across_x({3, 6});
  const RayScene scene(world);
  const WallCounter walls(scene, world);
  EXPECT_EQ(walls.count({0, 0, 0.5}, {3.0, 0, 0.5}), 1);   // ends in the first wall
  EXPECT_EQ(walls.count({0, 0, 0.5}, {6.0, 0, 0.5}), 2);   // through the first, ends in the second
  EXPECT_EQ(walls.count({3.0, 0, 0.5}, {10, 0, 0.5}), 2);  // starts in the first (its exit face), through the second
}

TEST(WallCounter, FloorAndRubbleAreNotWalls) {
  WorldSpec s;
  s.name = "radio_test";
  s.materials = default_materials();
  s.floor_min = {-2, -8};
  s.floor_max = {12, 8};
  RubbleSpec box;
  box.pose = Pose2{5, 0, 0};
  box.size = {0.4, 0.4, 0.3};
  s.rubble.push_back(box);
  const World world = compile_world(s, {});
  const RayScene scene(world);
  const WallCounter walls(scene, world);
  EXPECT_EQ(walls.count({0, 0, 0.1}, {10, 0, 0.1}), 0);   // through the rubble box
  EXPECT_EQ(walls.count({0, 0, 0.5}, {4, 0, -0.1}), 0);   // into the floor slab
  EXPECT_EQ(walls.count({0, 0, 0.5}, {4, 0, 0.5}), 0);
}

TEST(WallCounter, NonFiniteOrDegenerateSegmentsCountZero) {
  const World world = walls_across_x({3});
  const RayScene scene(world);
  const WallCounter walls(scene, world);
  EXPECT_EQ(walls.count({std::nan(""), 0, 0.5}, {10, 0, 0.5}), 0);
  EXPECT_EQ(walls.count({0, 0, 0.5}, {INFINITY, 0, 0.5}), 0);
  EXPECT_EQ(walls.count({1, 0, 0.5}, {1, 0, 0.5}), 0);
}

TEST(WallCounter, BatchMatchesOneByOne) {
  const World world = walls_across_x({1.5, 2.5, 3.5, 4.5, 5.5, 6.5, 7.5});
  const RayScene scene(world);
  const WallCounter walls(scene, world);
  std::vector<RadioSegment> segs;
  for (int i = 0; i < 40; ++i) {
    segs.push_back({{0, -4 + 0.2 * i, 0.5}, {10 - 0.2 * i, 4 - 0.2 * i, 0.3}});
  }
  std::vector<int> batch(segs.size());
  walls.count(segs, batch);
  for (std::size_t i = 0; i < segs.size(); ++i) {
    EXPECT_EQ(batch[i], walls.count(segs[i].p_W, segs[i].q_W)) << "segment " << i;
  }
  // the first: x from 0 to 10 crosses all 7 walls (y from −4 to 4 within their ±5)
  EXPECT_EQ(batch[0], 7);
}

}  // namespace
}  // namespace rescuesim
