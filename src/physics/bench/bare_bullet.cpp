// The bare-Bullet baseline: a Physics built as usual, then its Bullet world stepped directly
// through the folder's internal header.

#include "physics/bench/bare_bullet.h"

#include <chrono>

#include "physics/physics_internal.h"

namespace rescuesim {

double bare_bullet_steps_per_second(const World& world, const PhysicsOptions& options, int steps, double wheel_speed) {
  Physics physics(world, options);
  Physics::Impl& impl = physics.internals();
  physics_internal::hold_velocity_joints(world, impl, wheel_speed);
  const std::vector<btMultiBodyDynamicsWorld*> worlds = physics_internal::bullet_worlds(impl);
  // time only the steps (of every group's world, one after another, as they were built)
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) {
    for (btMultiBodyDynamicsWorld* w : worlds) w->stepSimulation(btScalar(options.dt), 0, btScalar(options.dt));
  }
  return steps / std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace rescuesim
