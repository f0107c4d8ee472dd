#pragma once
/// Internal to src/physics (Bullet types inside): the few handles on a Physics's Bullet engine
/// that the bare-Bullet baseline (src/physics/bench, library rs_physics_bench) needs to step the
/// very same bodies without State, controllers or read-back. Not for production code: Physics's
/// own interface is physics.h.

#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include <vector>

#include "physics/physics.h"

namespace rescuesim::physics_internal {

/// The Bullet worlds of a Physics, one per group (PhysicsOptions::groups), which between them
/// hold its statics (each world a copy), rubble and robot multibodies as built from World.
std::vector<btMultiBodyDynamicsWorld*> bullet_worlds(Physics::Impl& impl);

/// Sets every robot joint motor: velocity-controlled joints to `speed` (rad/s), the others held
/// at zero velocity; `world` is the World the Physics was built from.
void hold_velocity_joints(const World& world, Physics::Impl& impl, double speed);

}  // namespace rescuesim::physics_internal
