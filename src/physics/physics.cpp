// The public Physics over its Bullet engine (physics_impl.h lists the files that build, step and
// restore it): construction, the start state, one step, counts, and the bench's internal handles.

#include "physics/physics.h"

#include "physics/physics_impl.h"
#include "physics/physics_internal.h"

namespace rescuesim {

using bullet::from_bt;

namespace {

/// A rigid body's sleeping state in State's terms.
BodyState::Sleep sleep_of(const btCollisionObject& b) {
  switch (b.getActivationState()) {
    case ISLAND_SLEEPING: return BodyState::Sleep::asleep;
    case WANTS_DEACTIVATION: return BodyState::Sleep::drowsy;
    default: return BodyState::Sleep::awake;
  }
}

}  // namespace

Physics::Physics(const World& world, const PhysicsOptions& options) : options_(options) {
  if (!(options.dt > 0) || options.dt > 0.1) throw Error({"", 0, "physics.dt"}, "time step must be in (0, 0.1] s");
  impl_ = std::make_unique<Impl>(world, options);
}

Physics::~Physics() = default;

void Physics::init_state(State& state) const {
  // the kinematic start state, then what Bullet made of it (its single-precision poses, and
  // which rubble starts asleep)
  const World& w = impl_->world;
  State start = initial_state(w);
  state.dynamics = std::move(start.dynamics);
  for (std::size_t i = 0; i < state.dynamics.size(); ++i) state.dynamics[i].sleep = sleep_of(*impl_->rubble[i]);
  state.robots = std::move(start.robots);
  for (std::size_t r = 0; r < w.robots.size(); ++r) impl_->read_robot(w.robots[r].spec, impl_->robots[r], state.robots[r], false);
}

void Physics::step(State& state) {
  Impl& m = *impl_;
  if (m.groups.size() > 1) m.regroup();
  for (std::size_t r = 0; r < m.robots.size(); ++r) m.update_held(r, state.robots[r]);
  m.step_groups(state);
  for (std::size_t i = 0; i < m.rubble.size(); ++i) {
    const btRigidBody& b = *m.rubble[i];
    state.dynamics[i] = {from_bt(b.getWorldTransform()), from_bt(b.getLinearVelocity()), from_bt(b.getAngularVelocity()), sleep_of(b),
                         b.getDeactivationTime()};
  }
  m.check_trouble(state);
}

PhysicsStats Physics::stats() const {
  PhysicsStats s;
  s.static_bodies = static_cast<int>(impl_->static_parts.size());
  s.groups = static_cast<int>(impl_->groups.size());
  s.dynamic_bodies = static_cast<int>(impl_->rubble.size());
  s.multibodies = static_cast<int>(impl_->robots.size());
  for (const auto& r : impl_->robots) {
    s.multibody_links += r.mb->getNumLinks();
    s.multibody_dofs += r.mb->getNumDofs();
  }
  return s;
}

namespace physics_internal {

std::vector<btMultiBodyDynamicsWorld*> bullet_worlds(Physics::Impl& impl) {
  std::vector<btMultiBodyDynamicsWorld*> out;
  for (auto& g : impl.groups) out.push_back(&g->dynamics);
  return out;
}

void hold_velocity_joints(const World& world, Physics::Impl& impl, double speed) {
  for (std::size_t r = 0; r < impl.robots.size(); ++r) {
    const RobotSpec& spec = world.robots[r].spec;
    for (std::size_t j = 0; j < spec.joints.size(); ++j) {
      btMultiBodyJointMotor* m = impl.robots[r].motors[j];
      if (m) m->setVelocityTarget(btScalar(spec.joints[j].control == JointSpec::Control::velocity ? speed : 0.0), 1.0f);
    }
  }
}

}  // namespace physics_internal

}  // namespace rescuesim
