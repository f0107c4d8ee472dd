#include "physics/physics.h"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "physics/bullet_convert.h"
#include "physics/physics_internal.h"
#include "world/robot_lumping.h"

namespace rescuesim {

using bullet::from_bt;
using bullet::to_bt;

namespace {

/// What a Bullet collision object stands for, stored in its user index.
enum Tag : int { kStatic = 0, kDynamic = 1, kRobot = 2 };
int encode(Tag tag, int index, int sub = 0) { return (tag << 28) | (sub << 16) | index; }
Tag tag_of(int code) { return static_cast<Tag>(code >> 28); }
int index_of(int code) { return code & 0xffff; }
int sub_of(int code) { return (code >> 16) & 0xfff; }

/// How far apart two shapes may be for Bullet to keep a (speculative) contact between them (m).
constexpr double kContactDistance = 0.03;

/// A rigid body's sleeping state in State's terms, and back in Bullet's.
BodyState::Sleep sleep_of(const btCollisionObject& b) {
  switch (b.getActivationState()) {
    case ISLAND_SLEEPING: return BodyState::Sleep::asleep;
    case WANTS_DEACTIVATION: return BodyState::Sleep::drowsy;
    default: return BodyState::Sleep::awake;
  }
}
int bullet_activation(BodyState::Sleep s) {
  switch (s) {
    case BodyState::Sleep::asleep: return ISLAND_SLEEPING;
    case BodyState::Sleep::drowsy: return WANTS_DEACTIVATION;
    case BodyState::Sleep::awake: break;
  }
  return ACTIVE_TAG;
}

bool finite(const Pose3& X) {
  return std::isfinite(X.p.x()) && std::isfinite(X.p.y()) && std::isfinite(X.p.z()) && std::isfinite(X.q.w()) &&
         std::isfinite(X.q.x()) && std::isfinite(X.q.y()) && std::isfinite(X.q.z());
}

}  // namespace

/// One robot as a Featherstone multibody: one Bullet link per rigid body of the robot (links
/// joined by fixed joints are lumped into one body, see world/robot_lumping.h).
struct RobotBody {
  btMultiBody* mb = nullptr;
  LumpedRobot lumped;                       // bodies and moving joints, and where each link sits; a moving
                                            // joint's Bullet link is its lumped index (lumped.lumped_joint)
  std::vector<int> bt_link;                 // per body: Bullet link index, -1 for the base
  std::vector<btMultiBodyLinkCollider*> colliders;  // per body
  std::vector<btMultiBodyJointMotor*> motors;       // per original joint, nullptr when uncontrolled
  std::vector<Pose3> X_BF;                  // per body: Bullet's frame (centre of mass, principal axes) in the body frame
  std::vector<char> top;                    // per original link: it is its body's own frame
};

struct Physics::Impl {
  const World& world;
  PhysicsOptions options;
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btMultiBodyConstraintSolver solver;
  btMultiBodyDynamicsWorld dynamics{&dispatcher, &broadphase, &solver, &config};
  bullet::ShapeStore shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motion_states;
  std::vector<std::unique_ptr<btRigidBody>> statics;     // static geometry (one or one compound)
  std::vector<std::unique_ptr<btRigidBody>> rubble;      // per World::dynamics
  std::vector<std::unique_ptr<btMultiBody>> multibodies;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> constraints;
  std::vector<RobotBody> robots;

  Impl(const World& w, const PhysicsOptions& o) : world(w), options(o) {
    // contacts are kept from 3 cm apart for every shape (Bullet's default scales the distance
    // down for small shapes), so bodies meet the ground on the step they reach it
    dispatcher.setDispatcherFlags(dispatcher.getDispatcherFlags() & ~btCollisionDispatcher::CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD);
    gContactBreakingThreshold = btScalar(kContactDistance);
    dynamics.setGravity(btVector3(0, 0, btScalar(-w.gravity)));
    dynamics.getSolverInfo().m_numIterations = o.solver_iterations;
    build_statics();
    build_rubble();
    for (std::size_t r = 0; r < w.robots.size(); ++r) build_robot(static_cast<int>(r));
  }

  ~Impl() {
    for (auto& c : constraints) dynamics.removeMultiBodyConstraint(c.get());
    for (auto& mb : multibodies) dynamics.removeMultiBody(mb.get());
    for (auto& c : colliders) dynamics.removeCollisionObject(c.get());
    for (auto& b : rubble) dynamics.removeRigidBody(b.get());
    for (auto& b : statics) dynamics.removeRigidBody(b.get());
  }

  const MaterialSpec& material(int i) const { return world.materials[static_cast<std::size_t>(i)]; }

  btRigidBody* add_body(btCollisionShape* shape, const Pose3& X, double mass, const Vec3& inertia, const MaterialSpec& m, int code) {
    motion_states.push_back(std::make_unique<btDefaultMotionState>(to_bt(X)));
    btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), motion_states.back().get(), shape, to_bt(inertia));
    info.m_friction = btScalar(m.friction);
    info.m_restitution = btScalar(m.restitution);
    auto body = std::make_unique<btRigidBody>(info);
    body->setUserIndex(code);
    btRigidBody* raw = body.get();
    dynamics.addRigidBody(raw);
    (mass > 0 ? rubble : statics).push_back(std::move(body));
    return raw;
  }

  void build_statics() {
    if (options.compound_statics) {
      // one body for all walls and obstacles: fewer broadphase entries, one friction for all
      btCompoundShape* all = shapes.compound();
      for (std::size_t i = 0; i < world.statics.size(); ++i) {
        all->addChildShape(to_bt(world.statics[i].X_WO), shapes.make(world.statics[i].geometry));
      }
      add_body(all, Pose3{}, 0, Vec3::Zero(), material(world.statics[0].material), encode(kStatic, 0));
      return;
    }
    for (std::size_t i = 0; i < world.statics.size(); ++i) {
      const StaticObject& s = world.statics[i];
      if (s.kind == ObjectKind::floor) {
        // the floor as a plane at z = 0: plane contacts are found before bodies touch, so a
        // falling body lands on the step it arrives rather than one step late
        add_body(shapes.plane(), Pose3{}, 0, Vec3::Zero(), material(s.material), encode(kStatic, static_cast<int>(i)));
        continue;
      }
      add_body(shapes.make(s.geometry), s.X_WO, 0, Vec3::Zero(), material(s.material), encode(kStatic, static_cast<int>(i)));
    }
  }

  void build_rubble() {
    for (std::size_t i = 0; i < world.dynamics.size(); ++i) {
      const DynamicObject& d = world.dynamics[i];
      btRigidBody* b = add_body(shapes.make(d.geometry), d.X_WO, d.mass, d.inertia, material(d.material), encode(kDynamic, static_cast<int>(i)));
      b->setRollingFriction(0.002f);
      b->setSpinningFriction(0.002f);
      // rubble resting on the ground starts asleep, until something touches it
      if (resting_on_ground(*b)) b->setActivationState(ISLAND_SLEEPING);
    }
  }

  /// True when a body's lowest point lies on the floor or on a platform top (within 1 mm).
  bool resting_on_ground(const btRigidBody& b) const {
    btVector3 lo, hi;
    b.getCollisionShape()->getAabb(b.getWorldTransform(), lo, hi);
    // rubble is boxes and cylinders, whose bounding boxes are exact
    const double bottom = lo.z();
    if (std::abs(bottom) < 1e-3) return true;
    for (const auto& s : world.statics) {
      if (s.kind == ObjectKind::platform && std::abs(bottom - (s.X_WO.p.z() + s.geometry.size.z())) < 1e-3) return true;
    }
    return false;
  }

  void build_robot(int r) {
    const RobotInstance& inst = world.robots[static_cast<std::size_t>(r)];
    RobotBody body;
    body.lumped = lump_fixed_joints(inst.spec);
    const RobotSpec& spec = body.lumped.spec;  // one link per rigid body, moving joints only
    const int n_links = static_cast<int>(spec.joints.size());
    const LinkSpec& base = spec.links[0];
    body.X_BF.resize(spec.links.size());
    body.bt_link.assign(spec.links.size(), -1);
    for (std::size_t l = 0; l < spec.links.size(); ++l) body.X_BF[l] = Pose3{spec.links[l].com, spec.links[l].inertia_axes};

    auto mb = std::make_unique<btMultiBody>(n_links, btScalar(base.mass), to_bt(base.inertia), false, false);
    // each moving joint makes its child body a Bullet link, numbered like the joint
    for (int j = 0; j < n_links; ++j) {
      const JointSpec& js = spec.joints[static_cast<std::size_t>(j)];
      const int parent = spec.link_index(js.parent), child = spec.link_index(js.child);
      body.bt_link[static_cast<std::size_t>(child)] = j;
      const LinkSpec& pl = spec.links[static_cast<std::size_t>(parent)];
      const LinkSpec& cl = spec.links[static_cast<std::size_t>(child)];
      const Pose3& X_PF = body.X_BF[static_cast<std::size_t>(parent)];
      const Pose3& X_CF = body.X_BF[static_cast<std::size_t>(child)];
      const int bt_parent = body.bt_link[static_cast<std::size_t>(parent)];
      // Bullet frames sit at each body's centre of mass along its principal axes; ours at the joint
      const btQuaternion rot_parent_to_this = to_bt((X_PF.q.conjugate() * js.X_PJ.q * X_CF.q).conjugate());
      const btVector3 parent_com_to_pivot = to_bt(X_PF.q.conjugate() * (js.X_PJ.p - pl.com));
      const btVector3 pivot_to_com = to_bt(X_CF.q.conjugate() * cl.com);
      const btVector3 axis = to_bt(X_CF.q.conjugate() * js.axis.normalized());
      switch (js.type) {
        case JointSpec::Type::fixed:
          mb->setupFixed(j, btScalar(cl.mass), to_bt(cl.inertia), bt_parent, rot_parent_to_this, parent_com_to_pivot, pivot_to_com, true);
          break;
        case JointSpec::Type::prismatic:
          mb->setupPrismatic(j, btScalar(cl.mass), to_bt(cl.inertia), bt_parent, rot_parent_to_this, axis, parent_com_to_pivot, pivot_to_com, true);
          break;
        case JointSpec::Type::revolute:
        case JointSpec::Type::continuous:
          mb->setupRevolute(j, btScalar(cl.mass), to_bt(cl.inertia), bt_parent, rot_parent_to_this, axis, parent_com_to_pivot, pivot_to_com, true);
          break;
      }
    }
    mb->finalizeMultiDof();
    mb->setBaseWorldTransform(to_bt(inst.X_W_start * body.X_BF[0]));
    for (int j = 0; j < n_links; ++j) {
      if (spec.joints[static_cast<std::size_t>(j)].type != JointSpec::Type::fixed) mb->setJointPos(j, btScalar(spec.joints[static_cast<std::size_t>(j)].initial));
    }
    mb->setCanSleep(false);
    mb->setHasSelfCollision(false);
    mb->setLinearDamping(0.0f);
    mb->setAngularDamping(0.0f);
    mb->setUseGyroTerm(true);
    dynamics.addMultiBody(mb.get());

    // colliders: each body's shapes, placed relative to its Bullet frame
    body.colliders.assign(spec.links.size(), nullptr);
    for (std::size_t l = 0; l < spec.links.size(); ++l) {
      const LinkSpec& ls = spec.links[l];
      btCompoundShape* compound = shapes.compound();
      double friction = 0.5, restitution = 0.0;
      const Pose3 X_FB = body.X_BF[l].inverse();
      for (const auto& sh : ls.shapes) {
        if (!sh.collides) continue;
        compound->addChildShape(to_bt(X_FB * sh.X_LG), shapes.make(sh.geometry));
        const MaterialSpec& m = material(world.material_index(sh.material));
        friction = m.friction;
        restitution = m.restitution;
      }
      if (compound->getNumChildShapes() == 0) continue;
      auto col = std::make_unique<btMultiBodyLinkCollider>(mb.get(), body.bt_link[l]);
      col->setCollisionShape(compound);
      col->setFriction(btScalar(friction));
      col->setRestitution(btScalar(restitution));
      if (ls.friction_scale != Vec3::Ones()) col->setAnisotropicFriction(to_bt(ls.friction_scale));
      col->setUserIndex(encode(kRobot, static_cast<int>(l), r));
      dynamics.addCollisionObject(col.get(), btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
      if (body.bt_link[l] < 0) {
        mb->setBaseCollider(col.get());
      } else {
        mb->getLink(body.bt_link[l]).m_collider = col.get();
      }
      body.colliders[l] = col.get();
      colliders.push_back(std::move(col));
    }

    // actuators, per joint of the description: velocity motors (position loops run on top of
    // them), Coulomb friction on passive joints (a motor holding zero speed with a bounded
    // force, as pybullet does), and limits
    const RobotSpec& full = inst.spec;
    for (std::size_t l = 0; l < full.links.size(); ++l) {
      body.top.push_back(spec.links[static_cast<std::size_t>(body.lumped.body_of_link[l])].name == full.links[l].name);
    }
    body.motors.assign(full.joints.size(), nullptr);
    for (std::size_t j = 0; j < full.joints.size(); ++j) {
      const JointSpec& js = full.joints[j];
      const int bt = body.lumped.lumped_joint[j];
      if (bt < 0) continue;
      const bool passive = js.control == JointSpec::Control::none;
      if (!passive || js.friction > 0) {
        const double force = passive ? js.friction : js.max_effort;
        auto motor = std::make_unique<btMultiBodyJointMotor>(mb.get(), bt, 0.0f, btScalar(force * options.dt));
        if (!passive) body.motors[j] = motor.get();
        dynamics.addMultiBodyConstraint(motor.get());
        constraints.push_back(std::move(motor));
      }
      if (js.type == JointSpec::Type::revolute || js.type == JointSpec::Type::prismatic) {
        auto limit = std::make_unique<btMultiBodyJointLimitConstraint>(mb.get(), bt, btScalar(js.lower), btScalar(js.upper));
        dynamics.addMultiBodyConstraint(limit.get());
        constraints.push_back(std::move(limit));
      }
    }
    body.mb = mb.get();
    multibodies.push_back(std::move(mb));
    robots.push_back(std::move(body));
    sync_colliders(robots.back());
  }

  /// Updates the link colliders' world transforms from the multibody's joint state.
  static void sync_colliders(RobotBody& b) {
    btAlignedObjectArray<btQuaternion> world_to_local;
    btAlignedObjectArray<btVector3> local_origin;
    b.mb->forwardKinematics(world_to_local, local_origin);
    b.mb->updateCollisionObjectWorldTransforms(world_to_local, local_origin);
  }

  /// Pose of a body's frame in the world, from its collider (or the multibody for the base).
  Pose3 body_pose(const RobotBody& b, std::size_t body) const {
    btTransform T;
    if (b.bt_link[body] < 0) {
      T = b.mb->getBaseWorldTransform();
    } else {
      T = b.mb->getLink(b.bt_link[body]).m_cachedWorldTransform;
    }
    return from_bt(T) * b.X_BF[body].inverse();
  }

  /// Drives each actuated joint toward its target: velocity joints directly, position joints
  /// through a proportional loop on velocity; viscous damping as a joint force against the motion.
  void apply_targets(const RobotSpec& spec, RobotBody& b, const RobotState& s) {
    for (std::size_t j = 0; j < spec.joints.size(); ++j) {
      const JointSpec& js = spec.joints[j];
      const int bt = b.lumped.lumped_joint[j];
      if (bt >= 0 && js.damping > 0) b.mb->addJointTorque(bt, btScalar(-js.damping * b.mb->getJointVel(bt)));
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

  void read_robot(const RobotSpec& spec, const RobotBody& b, RobotState& s, bool stepped = true) const {
    const std::size_t n = spec.joints.size();
    s.q.resize(n);
    s.qd.resize(n);
    s.effort.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
      const int bt = b.lumped.lumped_joint[j];
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

  /// Puts Bullet's hidden state into the one canonical form that depends only on the bodies'
  /// poses (Bullet's advice for repeatable runs): every collision object is taken out of the
  /// world — which frees their broadphase proxies, overlapping pairs and contact manifolds with
  /// the warm-start impulses in them — the then empty broadphase is reset (tree, ids, staging)
  /// and the solver's seed zeroed, and the objects go back in the order they were built in.
  /// Multibodies and their motors and limits stay: their order never changes and they keep no
  /// memory between steps beyond what State holds.
  void canonicalise() {
    for (auto it = colliders.rbegin(); it != colliders.rend(); ++it) dynamics.removeCollisionObject(it->get());
    for (auto it = rubble.rbegin(); it != rubble.rend(); ++it) dynamics.removeRigidBody(it->get());
    for (auto it = statics.rbegin(); it != statics.rend(); ++it) dynamics.removeRigidBody(it->get());
    broadphase.resetPool(&dispatcher);
    solver.reset();
    for (auto& b : statics) dynamics.addRigidBody(b.get());
    for (auto& b : rubble) dynamics.addRigidBody(b.get());
    for (auto& c : colliders) dynamics.addCollisionObject(c.get(), btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
  }

  /// Names of what touches each robot, and whether a new collision began.
  void read_contacts(State& state) {
    std::vector<std::vector<int>> touching(robots.size());
    const int n = dispatcher.getNumManifolds();
    for (int i = 0; i < n; ++i) {
      const btPersistentManifold* m = dispatcher.getManifoldByIndexInternal(i);
      bool contact = false;
      for (int k = 0; k < m->getNumContacts() && !contact; ++k) contact = m->getContactPoint(k).getDistance() < 0.002f;
      if (!contact) continue;
      const int a = m->getBody0()->getUserIndex(), b = m->getBody1()->getUserIndex();
      if (tag_of(a) == kRobot) touching[static_cast<std::size_t>(sub_of(a))].push_back(b);
      if (tag_of(b) == kRobot) touching[static_cast<std::size_t>(sub_of(b))].push_back(a);
    }
    for (std::size_t r = 0; r < robots.size(); ++r) {
      // the robot's own links touching each other are not contacts with the world
      std::vector<std::string> names;
      for (int code : touching[r]) {
        if (tag_of(code) == kRobot && static_cast<std::size_t>(sub_of(code)) == r) continue;
        names.push_back(name_of(code));
      }
      std::sort(names.begin(), names.end());
      names.erase(std::unique(names.begin(), names.end()), names.end());
      RobotState& rs = state.robots[r];
      if (names == rs.touching) continue;
      // a collision is a contact that begins with something the robot should not hit
      for (const auto& name : names) {
        if (obstacle_names.count(name) && !std::binary_search(rs.touching.begin(), rs.touching.end(), name)) ++rs.collisions;
      }
      rs.touching = std::move(names);
    }
  }

  /// What a contact is called: the object's name, or the victim's for any of their body parts.
  std::string name_of(int code) const {
    switch (tag_of(code)) {
      case kStatic: {
        if (options.compound_statics) return "static";
        const StaticObject& s = world.statics[static_cast<std::size_t>(index_of(code))];
        return s.victim >= 0 ? world.victims[static_cast<std::size_t>(s.victim)].name : s.name;
      }
      case kDynamic: return world.dynamics[static_cast<std::size_t>(index_of(code))].name;
      case kRobot: return world.robots[static_cast<std::size_t>(sub_of(code))].name;
    }
    return "?";
  }

  /// Names of the things a robot should not hit: walls, obstacles, victims, other robots.
  std::set<std::string> obstacle_names = [this] {
    std::set<std::string> out;
    for (const auto& s : world.statics) {
      if (s.kind == ObjectKind::wall || s.kind == ObjectKind::obstacle) out.insert(s.name);
    }
    for (const auto& v : world.victims) out.insert(v.name);
    for (const auto& r : world.robots) out.insert(r.name);
    return out;
  }();

  void check_trouble(State& state) const {
    const Box2 reach{world.floor.min - Vec2::Constant(options.escape_distance), world.floor.max + Vec2::Constant(options.escape_distance)};
    auto check = [&](const Pose3& X, const std::string& what) {
      if (!finite(X)) {
        if (state.trouble.first.empty()) state.trouble.first = what + " has a non-finite pose at t = " + std::to_string(state.time.seconds()) + " s";
        ++state.trouble.nan_poses;
      } else if (!reach.contains(X.p.head<2>()) || X.p.z() < -options.escape_distance || X.p.z() > options.escape_distance) {
        if (state.trouble.first.empty()) {
          state.trouble.first = what + " was flung out of the world (to " + std::to_string(X.p.x()) + ", " + std::to_string(X.p.y()) +
                                ", " + std::to_string(X.p.z()) + ") at t = " + std::to_string(state.time.seconds()) + " s";
        }
        ++state.trouble.escaped;
      }
    };
    for (std::size_t i = 0; i < state.dynamics.size(); ++i) check(state.dynamics[i].X_WB, world.dynamics[i].name);
    for (std::size_t r = 0; r < state.robots.size(); ++r) check(state.robots[r].base.X_WB, "robot '" + world.robots[r].name + "'");
  }
};

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
  for (std::size_t r = 0; r < m.robots.size(); ++r) m.apply_targets(m.world.robots[r].spec, m.robots[r], state.robots[r]);
  m.dynamics.stepSimulation(btScalar(options_.dt), 0, btScalar(options_.dt));
  // read back
  for (std::size_t i = 0; i < m.rubble.size(); ++i) {
    const btRigidBody& b = *m.rubble[i];
    state.dynamics[i] = {from_bt(b.getWorldTransform()), from_bt(b.getLinearVelocity()), from_bt(b.getAngularVelocity()), sleep_of(b),
                         b.getDeactivationTime()};
  }
  for (std::size_t r = 0; r < m.robots.size(); ++r) m.read_robot(m.world.robots[r].spec, m.robots[r], state.robots[r]);
  m.read_contacts(state);
  m.check_trouble(state);
}

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
    RobotBody& rb = m.robots[r];
    const RobotState& rs = state.robots[r];
    const RobotSpec& spec = m.world.robots[r].spec;
    const Vec3& com = rb.lumped.spec.links[0].com;
    rb.mb->setBaseWorldTransform(to_bt(rs.base.X_WB * rb.X_BF[0]));
    rb.mb->setBaseOmega(to_bt(rs.base.w_WB));
    rb.mb->setBaseVel(to_bt(rs.base.v_WB + rs.base.w_WB.cross(rs.base.X_WB.q * com)));
    for (std::size_t j = 0; j < spec.joints.size() && j < rs.q.size(); ++j) {
      const int bt = rb.lumped.lumped_joint[j];
      if (bt < 0) continue;
      rb.mb->setJointPos(bt, btScalar(rs.q[j]));
      rb.mb->setJointVel(bt, btScalar(rs.qd[j]));
    }
    Impl::sync_colliders(rb);
  }
  // contact caches, broadphase and solver: the same canonical form whatever came before
  m.canonicalise();
}

PhysicsStats Physics::stats() const {
  PhysicsStats s;
  s.static_bodies = static_cast<int>(impl_->statics.size());
  s.dynamic_bodies = static_cast<int>(impl_->rubble.size());
  s.multibodies = static_cast<int>(impl_->robots.size());
  for (const auto& r : impl_->robots) s.multibody_links += r.mb->getNumLinks();
  return s;
}

namespace physics_internal {

btMultiBodyDynamicsWorld& bullet_world(Physics::Impl& impl) { return impl.dynamics; }

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
