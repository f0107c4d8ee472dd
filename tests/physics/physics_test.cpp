// Bullet through our interface: free fall against the hand-computed time, restitution-free
// landing, rubble resting, and trouble detection.

#include "physics/physics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace rescuesim {
namespace {

WorldSpec floor_with_box(double drop_height) {
  WorldSpec w;
  w.floor_min = {-5, -5};
  w.floor_max = {5, 5};
  w.materials = default_materials();
  RubbleSpec box;
  box.shape = RubbleSpec::Shape::box;
  box.size = {0.2, 0.2, 0.2};
  box.mass = 2.0;
  box.pose = {0, 0, 0};
  w.rubble.push_back(box);
  (void)drop_height;
  return w;
}

TEST(Physics, BoxDroppedFromOneMetreLandsAfterSqrtTwoHOverG) {
  World world = compile_world(floor_with_box(1.0), {});
  world.dynamics[0].X_WO.p.z() = 1.0 + 0.1;  // bottom face 1 m above the floor
  world.materials[static_cast<std::size_t>(world.dynamics[0].material)].restitution = 0;
  Physics physics(world);
  State s;
  physics.init_state(s);
  const double dt = physics.dt();
  // t = sqrt(2 h / g) = sqrt(2 / 9.81) = 0.4515 s
  const double expected = std::sqrt(2.0 / 9.81);
  double landed = -1, prev_vz = 0;
  for (int i = 1; i < 1000 && landed < 0; ++i) {
    physics.step(s);
    const double vz = s.dynamics[0].v_WB.z();
    // free fall gains g dt of downward speed each step; a contact takes it away
    if (vz > prev_vz - 0.5 * 9.81 * dt) landed = i * dt;
    prev_vz = vz;
  }
  EXPECT_NEAR(landed, expected, dt + 1e-9);
  for (int i = 0; i < 500; ++i) physics.step(s);
  EXPECT_NEAR(s.dynamics[0].X_WB.p.z(), 0.1, 0.005);  // resting on its bottom face
  EXPECT_NEAR(s.dynamics[0].v_WB.norm(), 0.0, 1e-3);
}

TEST(Physics, FreeFallFollowsTheIntegrator) {
  World world = compile_world(floor_with_box(10.0), {});
  world.dynamics[0].X_WO.p.z() = 50.0;
  Physics physics(world);
  State s;
  physics.init_state(s);
  for (int i = 0; i < 100; ++i) physics.step(s);
  // semi-implicit Euler: after n steps v = -g n dt, z = z0 - g dt^2 n (n + 1) / 2
  const double dt = physics.dt(), n = 100;
  EXPECT_NEAR(s.dynamics[0].v_WB.z(), -9.81 * n * dt, 1e-4);
  EXPECT_NEAR(s.dynamics[0].X_WB.p.z(), 50.0 - 9.81 * dt * dt * n * (n + 1) / 2, 1e-3);
}

TEST(Physics, BodyFlungOutOfTheWorldIsReported) {
  World world = compile_world(floor_with_box(1.0), {});
  world.dynamics[0].X_WO.p.z() = 50.0;
  PhysicsOptions o;
  o.escape_distance = 40.0;
  Physics physics(world, o);
  State s;
  physics.init_state(s);
  s.dynamics[0].v_WB = Vec3(0, 0, 0);
  // falling from 50 m is fine; teleport it far away and step
  s.dynamics[0].X_WB.p = Vec3(1000, 0, 1);
  physics.restore(s);
  physics.step(s);
  EXPECT_EQ(s.trouble.escaped, 1);
  EXPECT_NE(s.trouble.first.find("rubble_0"), std::string::npos) << s.trouble.first;
}

TEST(Physics, BadStepIsRejected) {
  const World world = compile_world(floor_with_box(1.0), {});
  PhysicsOptions o;
  o.dt = 0;
  EXPECT_THROW(Physics(world, o), Error);
}

TEST(Physics, CompoundStaticsBehaveLikeSeparateOnes) {
  for (bool compound : {false, true}) {
    World world = compile_world(floor_with_box(1.0), {});
    world.dynamics[0].X_WO.p.z() = 0.6;
    PhysicsOptions o;
    o.compound_statics = compound;
    Physics physics(world, o);
    State s;
    physics.init_state(s);
    for (int i = 0; i < 1000; ++i) physics.step(s);
    EXPECT_NEAR(s.dynamics[0].X_WB.p.z(), 0.1, 0.005) << compound;
  }
}

/// How far a 0.2 m box of friction 1.0 slides from v0 along +x, starting at x = 0, on a world
/// whose floor patch (if any) of `ground` material covers x in [-1, 3].
double slide_distance(const std::string& ground, double v0, bool compound) {
  WorldSpec spec = floor_with_box(0);
  MaterialSpec rubber;
  rubber.name = "test_rubber";
  rubber.friction = 1.0;
  rubber.restitution = 0;
  spec.set_material(rubber);
  spec.rubble[0].material = "test_rubber";
  if (!ground.empty()) spec.ground.push_back({"patch", {{-1, -1}, {3, -1}, {3, 1}, {-1, 1}}, ground, {}});
  World world = compile_world(spec, {});
  PhysicsOptions o;
  o.compound_statics = compound;
  Physics physics(world, o);
  State s;
  physics.init_state(s);
  for (int i = 0; i < 20; ++i) physics.step(s);  // settle on the floor
  s.dynamics[0].X_WB.p.x() = 0;
  s.dynamics[0].v_WB = Vec3(v0, 0, 0);
  s.dynamics[0].sleep = BodyState::Sleep::awake;
  physics.restore(s);
  for (int i = 0; i < 600; ++i) physics.step(s);  // 3 s: long stopped
  EXPECT_NEAR(s.dynamics[0].v_WB.norm(), 0.0, 1e-3);
  return s.dynamics[0].X_WB.p.x();
}

// A box sliding from v0 stops after v0^2 / (2 mu g). Bullet combines two frictions as their
// product, and the box's is 1.0, so mu is the ground's own: floor 0.9, concrete 0.8, sand 0.4,
// wet tiles 0.25 (world_spec.cpp). From 2 m/s: 0.2265, 0.2548, 0.5097, 0.8155 m. Bullet's box
// stops short of that, on the floor as on the patches: by 3.5-5.5 % on the floor plane (the
// step's discretisation, v0 dt / 2 = 5 mm, and the solver's friction on a normal impulse that
// includes the penetration correction), by 1-8 % on the compound's floor box (more where the
// friction is higher). So each distance is checked to 9 %, and on the plane (the default) the
// ratio of each ground's distance to the floor's, the floor's friction over the ground's
// (0.9 / mu) whatever that bias, to 3 %.
TEST(Physics, ABoxSlidesVSquaredOverTwoMuGOnEachGroundMaterial) {
  const double v0 = 2.0, g = 9.81;
  for (bool compound : {false, true}) {
    const double on_floor = slide_distance("", v0, compound);
    EXPECT_NEAR(on_floor, v0 * v0 / (2 * 0.9 * g), 0.09 * v0 * v0 / (2 * 0.9 * g)) << "compound " << compound;
    for (const auto& [ground, mu] : std::vector<std::pair<std::string, double>>{{"concrete", 0.8}, {"sand", 0.4}, {"wet_tiles", 0.25}}) {
      const double d = slide_distance(ground, v0, compound), expected = v0 * v0 / (2 * mu * g);
      std::printf("%s, compound %d: %.4f m (v0^2 / (2 mu g) = %.4f m), %.3f x the floor's (expected %.3f)\n", ground.c_str(), compound, d,
                  expected, d / on_floor, 0.9 / mu);
      EXPECT_NEAR(d, expected, 0.09 * expected) << ground << " compound " << compound;
      if (!compound) {
        EXPECT_NEAR(d / on_floor, 0.9 / mu, 0.03 * 0.9 / mu) << ground;
      }
    }
  }
}

// Outside a patch the floor keeps its own friction: a patch of sand far from the box changes nothing.
TEST(Physics, AFloorPatchActsOnlyInsideItsFootprint) {
  WorldSpec spec = floor_with_box(0);
  spec.ground.push_back({"far", {{2, 2}, {4, 2}, {4, 4}, {2, 4}}, "wet_tiles", {}});
  World with = compile_world(spec, {}), without = compile_world(floor_with_box(0), {});
  Physics a(with), b(without);
  State sa, sb;
  a.init_state(sa);
  b.init_state(sb);
  for (State* s : {&sa, &sb}) {
    s->dynamics[0].v_WB = Vec3(1.0, 0, 0);
    s->dynamics[0].sleep = BodyState::Sleep::awake;
  }
  a.restore(sa);
  b.restore(sb);
  for (int i = 0; i < 200; ++i) a.step(sa), b.step(sb);
  EXPECT_EQ(sa.dynamics[0].X_WB.p, sb.dynamics[0].X_WB.p);
}

}  // namespace
}  // namespace rescuesim
