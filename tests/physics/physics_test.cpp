// Bullet through our interface: free fall against the hand-computed time, restitution-free
// landing, rubble resting, and trouble detection.

#include "physics/physics.h"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace rescuesim
