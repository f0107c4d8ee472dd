#pragma once
/// The physics baseline of `rescuesim bench` (library rs_physics_bench, linked only by the CLI
/// and bench/): Bullet stepped bare over the bodies Physics builds, so that Physics's own cost
/// (targets, read-back into State, contacts, trouble checks) shows beside it in the same run.

#include "physics/physics.h"
#include "world/world.h"

namespace rescuesim {

/// A bare Bullet loop over `world`: the same bodies as Physics(world, options), but no State, no
/// controllers, no read-back. Every velocity-controlled joint is held at `wheel_speed` (rad/s),
/// so a wheeled robot drives straight on as Physics would make it. Returns steps per second
/// over `steps` steps from a fresh start (construction not timed).
double bare_bullet_steps_per_second(const World& world, const PhysicsOptions& options, int steps, double wheel_speed);

}  // namespace rescuesim
