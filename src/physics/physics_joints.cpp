// A robot's multibody and its joints: the multibody made with its held joints fixed, motors
// and limits, self-locking gears taking hold and letting go, targets applied before a step
// and joint states, link poses and base velocity read back after it.

#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>

#include <algorithm>
#include <cmath>

#include "physics/physics_impl.h"

namespace rescuesim {

using bullet::from_bt;
using bullet::to_bt;

std::unique_ptr<btMultiBody> Physics::Impl::make_multibody(const RobotBody& body) {
  const LinkSpec& base = body.lumped.spec.links[0];
  const int n_links = static_cast<int>(body.setup.size());
  std::vector<int> held_at(body.setup.size(), -1);  // per Bullet link: the original joint it is held for
  for (std::size_t j = 0; j < body.held.size(); ++j) {
    if (body.held[j]) held_at[static_cast<std::size_t>(body.lumped.lumped_joint[j])] = static_cast<int>(j);
  }
  auto mb = std::make_unique<btMultiBody>(n_links, btScalar(base.mass), to_bt(base.inertia), false, false);
  for (int j = 0; j < n_links; ++j) {
    const RobotBody::LinkSetup& ls = body.setup[static_cast<std::size_t>(j)];
    const int held = held_at[static_cast<std::size_t>(j)];
    if (held >= 0) {
      // the rotation a revolute joint at q has (btMultibodyLink::updateCacheMultiDof), or the
      // offset a prismatic one has, made permanent
      const btScalar q = btScalar(body.held_q[static_cast<std::size_t>(held)]);
      const bool slides = ls.type == JointSpec::Type::prismatic;
      const btQuaternion rot = slides ? ls.rot_parent_to_this : btQuaternion(ls.axis, -q) * ls.rot_parent_to_this;
      const btVector3 to_com = slides ? ls.pivot_to_com + q * ls.axis : ls.pivot_to_com;
      mb->setupFixed(j, ls.mass, ls.inertia, ls.parent, rot, ls.parent_com_to_pivot, to_com, true);
      continue;
    }
    switch (ls.type) {
      case JointSpec::Type::fixed:
        mb->setupFixed(j, ls.mass, ls.inertia, ls.parent, ls.rot_parent_to_this, ls.parent_com_to_pivot, ls.pivot_to_com, true);
        break;
      case JointSpec::Type::prismatic:
        mb->setupPrismatic(j, ls.mass, ls.inertia, ls.parent, ls.rot_parent_to_this, ls.axis, ls.parent_com_to_pivot, ls.pivot_to_com,
                           true);
        break;
      case JointSpec::Type::revolute:
      case JointSpec::Type::continuous:
        mb->setupRevolute(j, ls.mass, ls.inertia, ls.parent, ls.rot_parent_to_this, ls.axis, ls.parent_com_to_pivot, ls.pivot_to_com, true);
        break;
    }
  }
  mb->finalizeMultiDof();
  mb->setCanSleep(false);
  mb->setHasSelfCollision(false);
  mb->setLinearDamping(0.0f);
  mb->setAngularDamping(0.0f);
  mb->setUseGyroTerm(true);
  return mb;
}

void Physics::Impl::attach_colliders(RobotBody& body) {
  for (std::size_t l = 0; l < body.colliders.size(); ++l) {
    btMultiBodyLinkCollider* col = body.colliders[l];
    if (!col) continue;
    col->m_multiBody = body.mb;
    if (body.bt_link[l] < 0) {
      body.mb->setBaseCollider(col);
    } else {
      body.mb->getLink(body.bt_link[l]).m_collider = col;
    }
  }
}

void Physics::Impl::make_constraints(const RobotSpec& full, RobotBody& body) const {
  body.motors.assign(full.joints.size(), nullptr);
  body.constraints.clear();
  body.owned_constraints.clear();
  for (std::size_t j = 0; j < full.joints.size(); ++j) {
    const JointSpec& js = full.joints[j];
    const int bt = body.lumped.lumped_joint[j];
    if (bt < 0 || body.held[j]) continue;
    const bool passive = js.control == JointSpec::Control::none;
    if (!passive || js.friction > 0) {
      const double force = passive ? js.friction : js.max_effort;
      auto motor = std::make_unique<btMultiBodyJointMotor>(body.mb, bt, 0.0f, btScalar(force * options.dt));
      // its impulse storage now, not at its first solve: a robot with no collision shape at all
      // (PyBullet's pan-tilt) is never in an island, so Bullet never solves or sizes its motors,
      // and read_robot would read an impulse that does not exist. The solver finalises a
      // constraint only when it is not yet, so the motors' numbers are the same either way.
      motor->finalizeMultiDof();
      if (!passive) body.motors[j] = motor.get();
      body.constraints.push_back(motor.get());
      body.owned_constraints.push_back(std::move(motor));
    }
    if (js.type == JointSpec::Type::revolute || js.type == JointSpec::Type::prismatic) {
      auto limit = std::make_unique<btMultiBodyJointLimitConstraint>(body.mb, bt, btScalar(js.lower), btScalar(js.upper));
      body.constraints.push_back(limit.get());
      body.owned_constraints.push_back(std::move(limit));
    }
  }
}

bool Physics::Impl::holds(const JointSpec& js, const RobotState& s, std::size_t j) {
  if (!js.self_locking || js.control != JointSpec::Control::position) return false;
  if (j >= s.q.size() || j >= s.qd.size() || j >= s.joint_target.size()) return false;
  return std::abs(s.joint_target[j] - s.q[j]) <= kSelfLockTolerance && std::abs(s.qd[j]) <= kSelfLockSpeed;
}

void Physics::Impl::update_held(std::size_t r, const RobotState& s) {
  RobotBody& b = robots[r];
  const RobotSpec& full = world.robots[r].spec;
  const std::vector<JointSpec>& joints = full.joints;
  // a held joint is held where the State has it (read_robot reports its held position)
  bool same = true;
  for (std::size_t j = 0; j < joints.size() && same; ++j) {
    const bool h = holds(joints[j], s, j);
    same = h == (b.held[j] != 0) && (!h || s.q[j] == b.held_q[j]);
  }
  if (same) return;
  std::vector<char> hold(joints.size(), 0);
  std::vector<double> held_q(joints.size(), 0.0);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    hold[j] = holds(joints[j], s, j);
    if (hold[j]) held_q[j] = s.q[j];
  }
  btMultiBody* old = b.mb;
  btMultiBodyDynamicsWorld* w = robot_group[r] >= 0 ? &groups[static_cast<std::size_t>(robot_group[r])]->dynamics : nullptr;
  if (w) {
    for (auto it = b.constraints.rbegin(); it != b.constraints.rend(); ++it) w->removeMultiBodyConstraint(*it);
    w->removeMultiBody(old);
  }
  const std::vector<char> was = std::exchange(b.held, hold);
  const std::vector<double> was_q = std::exchange(b.held_q, std::move(held_q));
  std::unique_ptr<btMultiBody> mb = make_multibody(b);
  mb->setBaseWorldTransform(old->getBaseWorldTransform());
  mb->setBaseVel(old->getBaseVel());
  mb->setBaseOmega(old->getBaseOmega());
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const int bt = b.lumped.lumped_joint[j];
    if (bt < 0 || hold[j]) continue;
    mb->setJointPos(bt, was[j] ? btScalar(was_q[j]) : old->getJointPos(bt));
    mb->setJointVel(bt, was[j] ? btScalar(0) : old->getJointVel(bt));
  }
  b.constraints.clear();
  b.owned_constraints.clear();  // the old multibody's, before it goes
  b.owned_mb = std::move(mb);
  b.mb = b.owned_mb.get();
  attach_colliders(b);
  make_constraints(full, b);
  if (w) {
    w->addMultiBody(b.mb);
    for (btMultiBodyConstraint* c : b.constraints) w->addMultiBodyConstraint(c);
  }
  sync_colliders(b);
}

void Physics::Impl::sync_colliders(RobotBody& b) {
  btAlignedObjectArray<btQuaternion> world_to_local;
  btAlignedObjectArray<btVector3> local_origin;
  b.mb->forwardKinematics(world_to_local, local_origin);
  b.mb->updateCollisionObjectWorldTransforms(world_to_local, local_origin);
}

Pose3 Physics::Impl::body_pose(const RobotBody& b, std::size_t body) const {
  btTransform T;
  if (b.bt_link[body] < 0) {
    T = b.mb->getBaseWorldTransform();
  } else {
    T = b.mb->getLink(b.bt_link[body]).m_cachedWorldTransform;
  }
  return from_bt(T) * b.X_BF[body].inverse();
}

void Physics::Impl::apply_targets(const RobotSpec& spec, RobotBody& b, const RobotState& s) {
  for (std::size_t j = 0; j < spec.joints.size(); ++j) {
    const JointSpec& js = spec.joints[j];
    const int bt = b.lumped.lumped_joint[j];
    if (bt < 0 || b.held[j]) continue;
    if (js.damping > 0) b.mb->addJointTorque(bt, btScalar(-js.damping * b.mb->getJointVel(bt)));
    btMultiBodyJointMotor* m = b.motors[j];
    if (!m) continue;
    const double target = j < s.joint_target.size() ? s.joint_target[j] : 0.0;
    double vel = target;
    if (js.control == JointSpec::Control::position) {
      const double q = b.mb->getJointPos(bt);
      vel = js.kp * (target - q);
    }
    vel = std::clamp(vel, -js.max_velocity, js.max_velocity);
    m->setVelocityTarget(btScalar(vel), 1.0f);
  }
}

void Physics::Impl::read_robot(const RobotSpec& spec, const RobotBody& b, RobotState& s, bool stepped) const {
  const std::size_t n = spec.joints.size();
  s.q.resize(n);
  s.qd.resize(n);
  s.effort.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const int bt = b.lumped.lumped_joint[j];
    if (b.held[j]) {  // its gear carries the load: the motor's is zero
      s.q[j] = b.held_q[j];
      s.qd[j] = 0.0;
      s.effort[j] = 0.0;
      continue;
    }
    s.q[j] = bt >= 0 ? b.mb->getJointPos(bt) : 0.0;
    s.qd[j] = bt >= 0 ? b.mb->getJointVel(bt) : 0.0;
    // motors have no impulse to report before their first solve
    s.effort[j] = b.motors[j] && stepped ? b.motors[j]->getAppliedImpulse(0) / options.dt : 0.0;
  }
  const LumpedRobot& lr = b.lumped;
  std::vector<Pose3> X_WB(lr.spec.links.size());
  for (std::size_t k = 0; k < X_WB.size(); ++k) X_WB[k] = body_pose(b, k);
  s.X_WL.resize(spec.links.size());
  for (std::size_t l = 0; l < spec.links.size(); ++l) {
    const auto body = static_cast<std::size_t>(lr.body_of_link[l]);
    // a body's top link is the body frame itself: no product, so no round-off
    s.X_WL[l] = b.top[l] ? X_WB[body] : X_WB[body] * lr.X_BL[l];
  }
  s.base.X_WB = s.X_WL[0];
  // the base's velocity at the link-frame origin, from the centre-of-mass velocity
  const Vec3 w = from_bt(b.mb->getBaseOmega());
  const Vec3 v_com = from_bt(b.mb->getBaseVel());
  s.base.w_WB = w;
  s.base.v_WB = v_com + w.cross(s.base.X_WB.q * (-lr.spec.links[0].com));
}

}  // namespace rescuesim
