// Restoring: a State's poses, velocities, sleeping states and held joints put into Bullet, and
// Bullet's hidden state (contact caches, broadphase, solver seed) into its canonical form.

#include "physics/physics_impl.h"

namespace rescuesim {

using bullet::to_bt;

namespace {

/// A rigid body's sleeping state in Bullet's terms.
int bullet_activation(BodyState::Sleep s) {
  switch (s) {
    case BodyState::Sleep::asleep: return ISLAND_SLEEPING;
    case BodyState::Sleep::drowsy: return WANTS_DEACTIVATION;
    case BodyState::Sleep::awake: break;
  }
  return ACTIVE_TAG;
}

}  // namespace

void Physics::restore(const State& state) {
  Impl& m = *impl_;
  for (std::size_t i = 0; i < m.rubble.size() && i < state.dynamics.size(); ++i) {
    btRigidBody& b = *m.rubble[i];
    const BodyState& d = state.dynamics[i];
    b.setLinearVelocity(to_bt(d.v_WB));
    b.setAngularVelocity(to_bt(d.w_WB));
    // also sets the interpolation transform and velocities and the world inertia tensor
    b.setCenterOfMassTransform(to_bt(d.X_WB));
    b.getMotionState()->setWorldTransform(b.getWorldTransform());
    b.forceActivationState(bullet_activation(d.sleep));
    b.setDeactivationTime(btScalar(d.still_time));
    b.setHitFraction(1);
  }
  for (std::size_t r = 0; r < m.robots.size() && r < state.robots.size(); ++r) {
    Impl::RobotBody& rb = m.robots[r];
    const RobotState& rs = state.robots[r];
    const RobotSpec& spec = m.world.robots[r].spec;
    const Vec3& com = rb.lumped.spec.links[0].com;
    m.update_held(r, rs);
    rb.mb->setBaseWorldTransform(to_bt(rs.base.X_WB * rb.X_BF[0]));
    rb.mb->setBaseOmega(to_bt(rs.base.w_WB));
    rb.mb->setBaseVel(to_bt(rs.base.v_WB + rs.base.w_WB.cross(rs.base.X_WB.q * com)));
    for (std::size_t j = 0; j < spec.joints.size() && j < rs.q.size(); ++j) {
      const int bt = rb.lumped.lumped_joint[j];
      if (bt < 0 || rb.held[j]) continue;
      rb.mb->setJointPos(bt, btScalar(rs.q[j]));
      rb.mb->setJointVel(bt, btScalar(rs.qd[j]));
    }
    Impl::sync_colliders(rb);
  }
  // contact caches, broadphase and solver: the same canonical form whatever came before
  m.canonicalise();
}

void Physics::Impl::canonicalise() {
  for (std::size_t r = robots.size(); r-- > 0;) detach_robot(r);
  for (std::size_t i = rubble.size(); i-- > 0;) detach_rubble(i);
  const auto [rg, dg] = grouping();
  for (auto& g : groups) {
    for (auto it = g->statics.rbegin(); it != g->statics.rend(); ++it) g->dynamics.removeRigidBody(it->get());
    g->broadphase.resetPool(&g->dispatcher);
    g->solver.reset();
    for (auto& b : g->statics) g->dynamics.addRigidBody(b.get());
  }
  for (std::size_t i = 0; i < rubble.size(); ++i) attach_rubble(i, dg[i]);
  for (std::size_t r = 0; r < robots.size(); ++r) attach_robot(r, rg[r]);
}

}  // namespace rescuesim
