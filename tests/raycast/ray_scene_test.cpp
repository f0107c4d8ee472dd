// RayScene against geometry computed by hand: a wall at a known distance, rubble moved by
// update(), robots hidden from themselves, occlusion, and the same answers on 1 and N threads.

#include "raycast/ray_scene.h"

#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <vector>

#include "core/parallel.h"
#include "core/rng.h"

namespace rescuesim {
namespace {

/// An empty 10 m × 10 m floor around the origin.
WorldSpec empty_spec() {
  WorldSpec s;
  s.name = "raycast_test";
  s.materials = default_materials();
  s.floor_min = {-5, -5};
  s.floor_max = {5, 5};
  return s;
}

/// A wall whose west face is the plane x = 2 (0.1 m thick, 1 m high, 40 m long).
WallSpec wall_at_x2() { return WallSpec{{2.05, -20}, {2.05, 20}, 0.1, 1.0, "wall", {}}; }

/// A one-link robot: a 0.4 × 0.4 × 0.3 m box centred on its base link.
RobotSpec box_robot() {
  RobotSpec r;
  r.model = "box_bot";
  LinkSpec base;
  base.name = "base_link";
  base.shapes.push_back({Geometry::box({0.4, 0.4, 0.3}), Pose3{}, "robot_body", true});
  r.links.push_back(base);
  return r;
}

World compile(const WorldSpec& spec) { return compile_world(spec, {{"box_bot", box_robot()}}); }

RayHit cast_one(const RayScene& scene, const Vec3& origin, const Vec3& direction, float max_distance = INFINITY, RobotIndex ignore = {}) {
  const Ray ray{origin, direction.normalized(), max_distance};
  RayHit hit;
  scene.cast(std::span<const Ray>(&ray, 1), std::span<RayHit>(&hit, 1), ignore);
  return hit;
}

TEST(RaySceneWall, DistanceFollowsTheCosineLawFromManyOriginsAndAngles) {
  WorldSpec spec = empty_spec();
  spec.walls.push_back(wall_at_x2());
  const World world = compile(spec);
  const RayScene scene(world);

  // to the plane x = 2 from (ox, oy, oz) along yaw θ and pitch φ: d = (2 − ox) / (cos φ cos θ)
  const std::vector<Vec3> origins = {{0, 0, 0.5}, {0.5, -1, 0.3}, {-1, 1.2, 0.8}, {1.9, 0, 0.1}};
  for (const Vec3& o : origins) {
    for (double yaw : {0.0, 0.3, -0.6, 1.0, -1.2}) {
      for (double pitch : {0.0, 0.05, -0.04}) {
        const Vec3 dir(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch));
        const double expected = (2.0 - o.x()) / (std::cos(pitch) * std::cos(yaw));
        const double z_hit = o.z() + expected * dir.z();
        if (z_hit < 0.01 || z_hit > 0.99) continue;  // over or under the wall
        const RayHit h = cast_one(scene, o, dir);
        SCOPED_TRACE(::testing::Message() << "origin " << o.transpose() << " yaw " << yaw << " pitch " << pitch);
        EXPECT_NEAR(h.distance, expected, 1e-4);
        EXPECT_EQ(h.source, RayHit::Source::static_object);
        EXPECT_EQ(world.statics[static_cast<std::size_t>(h.index)].kind, ObjectKind::wall);
        EXPECT_NEAR(h.normal.x(), -1.0, 1e-6);
        EXPECT_NEAR(h.normal.y(), 0.0, 1e-6);
        EXPECT_NEAR(h.normal.z(), 0.0, 1e-6);
        EXPECT_FALSE(h.robot.valid());
      }
    }
  }
}

TEST(RaySceneWall, NormalFacesTheRayFromEitherSide) {
  WorldSpec spec = empty_spec();
  spec.walls.push_back(wall_at_x2());
  const RayScene scene(compile(spec));
  // from beyond the wall, its east face x = 2.1 faces back toward +x
  const RayHit h = cast_one(scene, {4, 0, 0.5}, {-1, 0, 0});
  EXPECT_NEAR(h.distance, 1.9, 1e-4);
  EXPECT_NEAR(h.normal.x(), 1.0, 1e-6);
  // the floor from above: distance = height, normal up
  const RayHit f = cast_one(scene, {0, 0, 0.7}, {0, 0, -1});
  EXPECT_NEAR(f.distance, 0.7, 1e-5);
  EXPECT_EQ(f.source, RayHit::Source::static_object);
  EXPECT_EQ(f.index, 0);
  EXPECT_NEAR(f.normal.z(), 1.0, 1e-6);
}

TEST(RaySceneMiss, NothingInTheWayIsInfinity) {
  WorldSpec spec = empty_spec();
  spec.walls.push_back(wall_at_x2());
  const RayScene scene(compile(spec));
  for (const Vec3& dir : {Vec3(0, 0, 1), Vec3(-1, 0, 0), Vec3(0, 1, 0.2)}) {
    const RayHit h = cast_one(scene, {0, 0, 0.5}, dir);
    EXPECT_TRUE(std::isinf(h.distance) && h.distance > 0);
    EXPECT_EQ(h.source, RayHit::Source::none);
    EXPECT_EQ(h.index, -1);
    EXPECT_FALSE(h.hit());
  }
}

TEST(RaySceneMiss, MaxDistanceIsHonoured) {
  WorldSpec spec = empty_spec();
  spec.walls.push_back(wall_at_x2());
  const RayScene scene(compile(spec));
  EXPECT_TRUE(std::isinf(cast_one(scene, {0, 0, 0.5}, {1, 0, 0}, 1.9f).distance));
  EXPECT_NEAR(cast_one(scene, {0, 0, 0.5}, {1, 0, 0}, 2.1f).distance, 2.0, 1e-4);
}

TEST(RaySceneMiss, NonFiniteRayIsNaN) {
  const RayScene scene(compile(empty_spec()));
  const RayHit h = cast_one(scene, {NAN, 0, 0.5}, {1, 0, 0});
  EXPECT_TRUE(std::isnan(h.distance));
  EXPECT_FALSE(h.hit());
}

/// The wall at x = 2 and a 0.2 x 0.2 x 0.1 m rubble box centred on (1, 0): its west face x = 0.9.
World wall_and_box() {
  WorldSpec spec = empty_spec();
  spec.walls.push_back(wall_at_x2());
  RubbleSpec box;
  box.pose = {1.0, 0.0, 0.0};
  box.size = {0.2, 0.2, 0.1};
  spec.rubble.push_back(box);
  return compile(spec);
}

TEST(RaySceneDynamic, RubbleIsHitWhereUpdatePutIt) {
  const World world = wall_and_box();
  RayScene scene(world);

  // at its start the box's west face is x = 0.9
  const Vec3 o(0, 0, 0.05);
  RayHit h = cast_one(scene, o, {1, 0, 0});
  EXPECT_NEAR(h.distance, 0.9, 1e-4);
  EXPECT_EQ(h.source, RayHit::Source::dynamic_object);
  EXPECT_EQ(h.index, 0);
  EXPECT_NEAR(h.normal.x(), -1.0, 1e-6);

  // moved to (0, 1) and turned 90°: +x now reaches the wall, +y meets the box's south face at 0.9
  State state = initial_state(world);
  state.dynamics[0].X_WB = Pose3::from_pose2({0.0, 1.0, M_PI / 2}, world.dynamics[0].X_WO.p.z());
  scene.update(state);
  h = cast_one(scene, o, {1, 0, 0});
  EXPECT_NEAR(h.distance, 2.0, 1e-4);
  EXPECT_EQ(h.source, RayHit::Source::static_object);
  h = cast_one(scene, o, {0, 1, 0});
  EXPECT_NEAR(h.distance, 0.9, 1e-4);
  EXPECT_EQ(h.source, RayHit::Source::dynamic_object);
  EXPECT_NEAR(h.normal.y(), -1.0, 1e-6);
}

TEST(RaySceneDynamic, ASleepingBodyIsTracedInTheFlatSceneAndLeavesItWhenItWakes) {
  const World world = wall_and_box();
  RayScene scene(world);
  const Vec3 o(0, 0, 0.05);
  const auto expect_box = [&](const Vec3& dir, double distance, const Vec3& normal) {
    const RayHit h = cast_one(scene, o, dir);
    EXPECT_NEAR(h.distance, distance, 1e-4);
    EXPECT_EQ(h.source, RayHit::Source::dynamic_object);
    EXPECT_EQ(h.index, 0);
    EXPECT_NEAR((h.normal - normal).norm(), 0.0, 1e-6);
  };

  // asleep where it starts: its west face x = 0.9, now one geometry with the wall
  State state = initial_state(world);
  state.dynamics[0].sleep = BodyState::Sleep::asleep;
  scene.update(state);
  expect_box({1, 0, 0}, 0.9, {-1, 0, 0});
  EXPECT_EQ(scene.triangle_count(), 36u);  // floor, wall and box, 12 each, counted once

  // awake, moved to (0, 1) and turned 90 degrees: +x reaches the wall, +y meets the box at 0.9
  state.dynamics[0].sleep = BodyState::Sleep::awake;
  state.dynamics[0].X_WB = Pose3::from_pose2({0.0, 1.0, M_PI / 2}, world.dynamics[0].X_WO.p.z());
  scene.update(state);
  EXPECT_NEAR(cast_one(scene, o, {1, 0, 0}).distance, 2.0, 1e-4);
  expect_box({0, 1, 0}, 0.9, {0, -1, 0});

  // asleep there: the flat scene is rebuilt with the box at its new pose, nothing at the old one
  state.dynamics[0].sleep = BodyState::Sleep::asleep;
  scene.update(state);
  EXPECT_EQ(cast_one(scene, o, {1, 0, 0}).source, RayHit::Source::static_object);
  expect_box({0, 1, 0}, 0.9, {0, -1, 0});
}

/// Two box robots: "a" at (1, 0) and "b" at (−1, 0); their boxes span 0.8..1.2 m from the origin.
World two_robot_world() {
  WorldSpec spec = empty_spec();
  spec.walls.push_back(wall_at_x2());
  spec.robots.push_back({"a", "box_bot", {1, 0, 0}, {}});
  spec.robots.push_back({"b", "box_bot", {-1, 0, 0}, {}});
  return compile(spec);
}

TEST(RaySceneRobots, IgnoredRobotIsInvisibleButOthersAreHit) {
  const World world = two_robot_world();
  const RayScene scene(world);
  const Vec3 o(0, 0, 0.2);

  RayHit h = cast_one(scene, o, {1, 0, 0});
  EXPECT_NEAR(h.distance, 0.8, 1e-4);
  EXPECT_EQ(h.source, RayHit::Source::robot_link);
  EXPECT_EQ(h.robot, RobotIndex(0));
  EXPECT_EQ(h.index, 0);
  EXPECT_NEAR(h.normal.x(), -1.0, 1e-6);

  // robot 0 ignoring itself sees the wall behind it, but still sees robot 1
  h = cast_one(scene, o, {1, 0, 0}, INFINITY, RobotIndex(0));
  EXPECT_NEAR(h.distance, 2.0, 1e-4);
  EXPECT_EQ(h.source, RayHit::Source::static_object);
  h = cast_one(scene, o, {-1, 0, 0}, INFINITY, RobotIndex(0));
  EXPECT_NEAR(h.distance, 0.8, 1e-4);
  EXPECT_EQ(h.source, RayHit::Source::robot_link);
  EXPECT_EQ(h.robot, RobotIndex(1));
  EXPECT_NEAR(h.normal.x(), 1.0, 1e-6);

  // robot 1 ignoring itself sees robot 0
  h = cast_one(scene, o, {1, 0, 0}, INFINITY, RobotIndex(1));
  EXPECT_EQ(h.robot, RobotIndex(0));
}

TEST(RaySceneRobots, LinksFollowUpdate) {
  const World world = two_robot_world();
  RayScene scene(world);
  State state = initial_state(world);
  // robot 0 drives to (0, 1.5): +x is clear to the wall, +y meets its south face at 1.3
  state.robots[0].X_WL[0].p.head<2>() = Vec2(0, 1.5);
  scene.update(state);
  EXPECT_NEAR(cast_one(scene, {0, 0, 0.2}, {1, 0, 0}).distance, 2.0, 1e-4);
  const RayHit h = cast_one(scene, {0, 0, 0.2}, {0, 1, 0});
  EXPECT_NEAR(h.distance, 1.3, 1e-4);
  EXPECT_EQ(h.robot, RobotIndex(0));
}

TEST(RaySceneOccluded, SegmentsThroughWallsAndRobots) {
  const World world = two_robot_world();
  const RayScene scene(world);
  // through the wall at x = 2 (above the robots)
  EXPECT_TRUE(scene.occluded({0, 0, 0.5}, {3, 0, 0.5}));
  EXPECT_FALSE(scene.occluded({0, 0, 0.5}, {1.5, 0, 0.5}));
  // a point on the wall's face is not hidden by that face
  EXPECT_FALSE(scene.occluded({0, 0, 0.5}, {2.0, 0, 0.5}));
  // robot 0 stands between the origin and x = 1.5 at z = 0.2, unless it is ignored
  EXPECT_TRUE(scene.occluded({0, 0, 0.2}, {1.5, 0, 0.2}));
  EXPECT_FALSE(scene.occluded({0, 0, 0.2}, {1.5, 0, 0.2}, RobotIndex(0)));
  EXPECT_TRUE(scene.occluded({0, 0, 0.2}, {1.5, 0, 0.2}, RobotIndex(1)));
  EXPECT_FALSE(scene.occluded({0, 0, 0.5}, {0, 0, 0.5}));
}

TEST(RaySceneCount, BoxesAreTwelveTriangles) {
  WorldSpec spec = empty_spec();
  spec.walls.push_back(wall_at_x2());
  EXPECT_EQ(RayScene(compile(spec)).triangle_count(), 24u);  // floor + wall
  EXPECT_EQ(RayScene(two_robot_world()).triangle_count(), 48u);
}

TEST(RaySceneMove, MovedSceneKeepsWorking) {
  WorldSpec spec = empty_spec();
  spec.walls.push_back(wall_at_x2());
  RayScene a(compile(spec));
  RayScene b = std::move(a);
  EXPECT_NEAR(cast_one(b, {0, 0, 0.5}, {1, 0, 0}).distance, 2.0, 1e-4);
}

/// A 6 × 6 m maze drawn by hand, with rubble, a victim and a robot.
World maze_world() {
  WorldSpec spec = empty_spec();
  spec.floor_min = {0, 0};
  spec.floor_max = {6, 6};
  const double t = 0.05, h = 1.0;
  auto wall = [&](Vec2 a, Vec2 b) { spec.walls.push_back(WallSpec{a, b, t, h, "wall", {}}); };
  wall({0, 0}, {6, 0});
  wall({6, 0}, {6, 6});
  wall({6, 6}, {0, 6});
  wall({0, 6}, {0, 0});
  wall({1.5, 0}, {1.5, 4.5});
  wall({3, 1.5}, {3, 6});
  wall({4.5, 0}, {4.5, 3});
  wall({3, 4.5}, {4.5, 4.5});
  wall({1.5, 4.5}, {0.5, 4.5});
  RubbleSpec box;
  box.pose = {2.2, 2.0, 0.4};
  spec.rubble.push_back(box);
  RubbleSpec can;
  can.shape = RubbleSpec::Shape::cylinder;
  can.pose = {5.2, 5.0, 0.0};
  can.size = {0.3, 0.3, 0.4};
  spec.rubble.push_back(can);
  VictimSpec v;
  v.name = "v1";
  v.pose = {3.75, 2.2, 0.3};
  spec.victims.push_back(v);
  spec.robots.push_back({"r", "box_bot", {0.75, 0.75, 0.5}, {}});
  return compile(spec);
}

std::vector<Ray> random_rays(int n, std::uint64_t seed) {
  Rng rng(seed, "rays");
  std::vector<Ray> rays;
  for (int i = 0; i < n; ++i) {
    const Vec3 o(rng.uniform(0.1, 5.9), rng.uniform(0.1, 5.9), rng.uniform(0.02, 1.3));
    Vec3 d(rng.normal(), rng.normal(), 0.3 * rng.normal());
    rays.push_back({o, d.normalized(), static_cast<float>(rng.uniform(0.5, 12.0))});
  }
  return rays;
}

/// Every field of every hit, bit for bit.
bool bitwise_equal(const std::vector<RayHit>& a, const std::vector<RayHit>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const bool same = std::memcmp(&a[i].distance, &b[i].distance, sizeof(float)) == 0 &&
                      std::memcmp(a[i].normal.data(), b[i].normal.data(), 3 * sizeof(double)) == 0 && a[i].source == b[i].source &&
                      a[i].index == b[i].index && a[i].robot == b[i].robot;
    if (!same) return false;
  }
  return true;
}

TEST(RaySceneDeterminism, OneThreadAndAllThreadsGiveIdenticalHits) {
  const World world = maze_world();
  const std::vector<Ray> rays = random_rays(10000, 7);

  // build and cast on one thread, then build and cast again on all cores
  set_worker_threads(1);
  std::vector<RayHit> one(rays.size());
  {
    const RayScene scene(world);
    scene.cast(rays, one, RobotIndex(0));
  }
  set_worker_threads(0);
  std::vector<RayHit> all(rays.size());
  {
    const RayScene scene(world);
    scene.cast(rays, all, RobotIndex(0));
  }
  EXPECT_TRUE(bitwise_equal(one, all));

  // the maze is closed, so the rays hit a good share of everything
  int hits = 0, statics = 0, dynamics = 0;
  for (const RayHit& h : all) {
    hits += h.hit();
    statics += h.source == RayHit::Source::static_object;
    dynamics += h.source == RayHit::Source::dynamic_object;
  }
  EXPECT_GT(hits, 5000);
  EXPECT_GT(statics, 4000);
  EXPECT_GT(dynamics, 0);

  // and a second cast of the same batch is the same again
  std::vector<RayHit> again(rays.size());
  const RayScene scene(world);
  scene.cast(rays, again, RobotIndex(0));
  EXPECT_TRUE(bitwise_equal(all, again));
}

/// The maze with every rubble body asleep where it was put: traced in the flat scene.
State sleeping_rubble(const World& world) {
  State s = initial_state(world);
  for (BodyState& b : s.dynamics) b.sleep = BodyState::Sleep::asleep;
  return s;
}

TEST(RaySceneDeterminism, HitDoesNotDependOnPlaceInTheBatch) {
  const World world = maze_world();
  const std::vector<Ray> rays = random_rays(3000, 11);
  // rubble as instances (awake), then in the flat scene with the walls (asleep)
  for (const bool asleep : {false, true}) {
    SCOPED_TRACE(asleep ? "rubble asleep" : "rubble awake");
    RayScene scene(world);
    if (asleep) scene.update(sleeping_rubble(world));
    std::vector<RayHit> batch(rays.size());
    scene.cast(rays, batch, RobotIndex(0));
    int dynamics = 0;
    for (const RayHit& h : batch) dynamics += h.source == RayHit::Source::dynamic_object;
    EXPECT_GT(dynamics, 0);

    // the same rays one lane later in their packets, and each on its own
    std::vector<Ray> shifted = rays;
    shifted.insert(shifted.begin(), Ray{});
    std::vector<RayHit> shifted_hits(shifted.size());
    scene.cast(shifted, shifted_hits, RobotIndex(0));
    shifted_hits.erase(shifted_hits.begin());
    std::vector<RayHit> single(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
      scene.cast(std::span<const Ray>(&rays[i], 1), std::span<RayHit>(&single[i], 1), RobotIndex(0));
    }
    EXPECT_TRUE(bitwise_equal(batch, shifted_hits));
    EXPECT_TRUE(bitwise_equal(batch, single));
  }
}

}  // namespace
}  // namespace rescuesim
