#include "physics/physics.h"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "core/parallel.h"
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
/// How far apart (m, each side) two bodies' bounding boxes must stay for them to step in
/// different groups: 10 cm beyond the contact distance, besides four steps of their speed.
constexpr double kGroupMargin = kContactDistance + 0.1;

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

/// Floor patches of other materials (World::ground), as the floor's body sees them. A patch is
/// not a solid of its own: a thin slab on the floor would give every wheel an edge to catch on
/// and a second contact (two frictions under one wheel), and a slab sunk flush with the floor
/// would still leave its rim for Bullet's contact generation to find. Instead the floor stays
/// one plane, and each contact with it takes its friction from the material under the contact
/// point: Bullet's contact-added callback, which Bullet calls for every contact point it makes or
/// refreshes with a body flagged CF_CUSTOM_MATERIAL_CALLBACK (only the floor is, and only in a
/// world with patches, so other worlds step exactly as before). The friction is combined as
/// Bullet combines it elsewhere, the product of the two bodies' (clamped to 10); likewise the
/// restitution.
struct GroundPatches {
  struct Patch {
    Polygon2 outline;
    Box2 box;
    double friction, restitution;
  };
  std::vector<Patch> patches;
  int floor_child = -1;  ///< with compound statics, the floor's child index in the compound (else -1)

  /// The patch under a point of the floor, or nullptr for the floor's own material.
  const Patch* at(const Vec2& p) const {
    for (const Patch& g : patches) {
      if (g.box.contains(p) && contains(g.outline, p)) return &g;
    }
    return nullptr;
  }
};

/// gContactAddedCallback: a floor contact's friction and restitution from the patch under it.
/// A pure function of the contact and the world, so it is safe on the worker threads.
bool ground_contact(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int, int index0, const btCollisionObjectWrapper* w1, int,
                    int index1) {
  const btCollisionObject* o0 = w0->getCollisionObject();
  const btCollisionObject* o1 = w1->getCollisionObject();
  const bool floor0 = (o0->getCollisionFlags() & btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK) && o0->getUserPointer();
  const bool floor1 = !floor0 && (o1->getCollisionFlags() & btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK) && o1->getUserPointer();
  if (!floor0 && !floor1) return false;
  const auto* ground = static_cast<const GroundPatches*>((floor0 ? o0 : o1)->getUserPointer());
  if (ground->floor_child >= 0 && (floor0 ? index0 : index1) != ground->floor_child) return false;
  // A is the manifold's body 0, which is w0's object
  const btVector3 p = floor0 ? cp.getPositionWorldOnA() : cp.getPositionWorldOnB();
  const GroundPatches::Patch* patch = ground->at(Vec2(p.x(), p.y()));
  if (!patch) return false;
  const btCollisionObject* other = floor0 ? o1 : o0;
  cp.m_combinedFriction = std::clamp(btScalar(patch->friction) * other->getFriction(), btScalar(-10), btScalar(10));
  cp.m_combinedRestitution = btScalar(patch->restitution) * other->getRestitution();
  return true;
}

/// A track belt over one collision shape of a robot body (LinkShape::belt_joint).
struct Belt {
  int child;         // the shape's index in its body's compound
  btVector3 axis;    // the belt's axis (the shape's z axis) in the collider's frame
  int sprocket;      // the Bullet link whose joint velocity drives it
  btScalar radius;   // m
};

/// The surface velocity of a belt at a contact, world frame: the belt turns around its axis at
/// radius × sprocket speed, so where its outward normal is n it moves along axis × n (a belt
/// driving forward runs backward underneath). Zero when the shape carries no belt.
btVector3 belt_velocity(const btMultiBody* mb, int link, int child, const btVector3& n_out) {
  if (!mb) return btVector3(0, 0, 0);
  const btMultiBodyLinkCollider* col = link < 0 ? mb->getBaseCollider() : mb->getLink(link).m_collider;
  const auto* belts = col ? static_cast<const std::vector<Belt>*>(col->getUserPointer()) : nullptr;
  if (!belts) return btVector3(0, 0, 0);
  for (const Belt& b : *belts) {
    if (b.child != child) continue;
    const btVector3 axis = col->getWorldTransform().getBasis() * b.axis;
    return (b.radius * mb->getJointVel(b.sprocket)) * axis.cross(n_out);
  }
  return btVector3(0, 0, 0);
}

/// Bullet's multibody solver, with moving contact surfaces: tracks. Bullet's rigid-body solver
/// takes a target sliding velocity per contact (btManifoldPoint::m_contactMotion1, the
/// conveyor-belt hook that Gazebo's tracked vehicles use through ODE's surface motion), but
/// its multibody solver (3.24 and upstream) ignores it and overwrites the friction
/// directions. So after Bullet has made its friction rows, each row at a contact with a belt
/// gets the belt's velocity as its target: the row's right-hand side is (target − relative
/// velocity) × its effective mass, and the target makes the two surfaces grip where the belt's
/// material and the ground move alike (v_A + u_A = v_B + u_B). The friction limit (μ × the
/// normal impulse) is untouched, so a belt slips where a real one would.
class BeltSolver final : public btMultiBodyConstraintSolver {
 public:
  bool belts = false;  ///< some collider carries a belt (else nothing is done per row)

  void convertContacts(btPersistentManifold** manifolds, int n, const btContactSolverInfo& info) override {
    btMultiBodyConstraintSolver::convertContacts(manifolds, n, info);
    if (!belts) return;
    for (int i = 0; i < m_multiBodyFrictionContactConstraints.size(); ++i) {
      btMultiBodySolverConstraint& c = m_multiBodyFrictionContactConstraints[i];
      const auto* cp = static_cast<const btManifoldPoint*>(c.m_originalContactPoint);
      // the normal points from B to A: A's surface faces −n, B's faces +n
      const btVector3 u = belt_velocity(c.m_multiBodyA, c.m_linkA, cp->m_index0, -cp->m_normalWorldOnB) -
                          belt_velocity(c.m_multiBodyB, c.m_linkB, cp->m_index1, cp->m_normalWorldOnB);
      if (u.fuzzyZero()) continue;
      // the row drives (v_A − v_B) · its direction to its target, here −(u_A − u_B)
      c.m_rhs -= u.dot(c.m_contactNormal1) * c.m_jacDiagABInv;
    }
  }
};

}  // namespace

/// One robot as a Featherstone multibody: one Bullet link per rigid body of the robot (links
/// joined by fixed joints are lumped into one body, see world/robot_lumping.h).
struct RobotBody {
  /// How one moving joint makes its child body a Bullet link (the arguments of setupRevolute and
  /// its kin), kept to rebuild the multibody when a self-locking joint is held or let go.
  struct LinkSetup {
    JointSpec::Type type;
    btScalar mass;
    btVector3 inertia;
    int parent;
    btQuaternion rot_parent_to_this;  // at q = 0
    btVector3 axis, parent_com_to_pivot, pivot_to_com;
  };
  btMultiBody* mb = nullptr;
  std::unique_ptr<btMultiBody> owned_mb;
  std::vector<LinkSetup> setup;             // per Bullet link
  std::vector<char> held;                   // per original joint: held rigid by its self-locking gear
  std::vector<double> held_q;               // per original joint: the position it is held at
  std::vector<std::unique_ptr<btMultiBodyConstraint>> owned_constraints;
  LumpedRobot lumped;                       // bodies and moving joints, and where each link sits; a moving
                                            // joint's Bullet link is its lumped index (lumped.lumped_joint)
  std::vector<int> bt_link;                 // per body: Bullet link index, -1 for the base
  std::vector<btMultiBodyLinkCollider*> colliders;  // per body
  std::vector<btMultiBodyJointMotor*> motors;       // per original joint, nullptr when uncontrolled
  std::vector<Pose3> X_BF;                  // per body: Bullet's frame (centre of mass, principal axes) in the body frame
  std::vector<char> top;                    // per original link: it is its body's own frame
  std::vector<btMultiBodyConstraint*> constraints;  // motors and limits, in build order
  std::vector<std::unique_ptr<std::vector<Belt>>> belts;  // per body with belts: its colliders' user pointer
};

/// One Bullet world of its own: a share of the robots and rubble, and its own static body for
/// every static object (the shapes are shared, and only read while stepping). Groups share no
/// mutable Bullet object, so they step at the same time on different threads. Debian's Bullet
/// is built without BT_THREADSAFE, which rules out stepping the islands of one world in parallel;
/// worlds of their own need nothing of Bullet but that two instances be independent. What is
/// left shared are Bullet's statistics counters (plain ints such as gNumManifold), whose value
/// nothing reads. Its profiler is compiled out (no BT_ENABLE_PROFILE).
struct PhysicsGroup {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  BeltSolver solver;
  btMultiBodyDynamicsWorld dynamics{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btRigidBody>> statics;  // one per static object (or one compound), build order

  explicit PhysicsGroup(const btDefaultCollisionConstructionInfo& info) : config(info) {}
};

struct Physics::Impl {
  const World& world;
  PhysicsOptions options;
  bullet::ShapeStore shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motion_states;
  /// The static objects' shapes, poses, materials and user codes, built once for every group.
  struct StaticPart {
    btCollisionShape* shape;
    Pose3 X;
    int material;
    int code;
  };
  std::vector<StaticPart> static_parts;
  std::unique_ptr<GroundPatches> ground;  // World::ground for the floor's contact callback; null without patches
  std::vector<std::unique_ptr<btRigidBody>> rubble;      // per World::dynamics
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
  std::vector<RobotBody> robots;
  std::vector<std::unique_ptr<PhysicsGroup>> groups;
  std::vector<int> robot_group;   // per robot: the group whose world holds it (-1: none yet)
  std::vector<int> rubble_group;  // per rubble body

  Impl(const World& w, const PhysicsOptions& o) : world(w), options(o) {
    // contacts are kept from 3 cm apart for every shape (Bullet's default scales the distance
    // down for small shapes), so bodies meet the ground on the step they reach it
    gContactBreakingThreshold = btScalar(kContactDistance);
    const int n_groups = group_count(o.groups, static_cast<int>(w.robots.size()));
    btDefaultCollisionConstructionInfo info;
    // Bullet's pools (4096 manifolds and algorithms, about 4 MB) are sized for one world; a group
    // holds a share of the bodies, and a pool that runs out falls back to the heap
    info.m_defaultMaxPersistentManifoldPoolSize = std::max(256, 4096 / n_groups);
    info.m_defaultMaxCollisionAlgorithmPoolSize = std::max(256, 4096 / n_groups);
    for (int g = 0; g < n_groups; ++g) {
      auto group = std::make_unique<PhysicsGroup>(info);
      group->dispatcher.setDispatcherFlags(group->dispatcher.getDispatcherFlags() & ~btCollisionDispatcher::CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD);
      group->dynamics.setGravity(btVector3(0, 0, btScalar(-w.gravity)));
      group->dynamics.getSolverInfo().m_numIterations = o.solver_iterations;
      groups.push_back(std::move(group));
    }
    build_statics();
    build_ground();
    for (auto& g : groups) add_statics(*g);
    build_rubble();
    for (std::size_t r = 0; r < w.robots.size(); ++r) build_robot(static_cast<int>(r));
    robot_group.assign(robots.size(), -1);
    rubble_group.assign(rubble.size(), -1);
    regroup();
  }

  ~Impl() {
    for (std::size_t r = 0; r < robots.size(); ++r) detach_robot(r);
    for (std::size_t i = 0; i < rubble.size(); ++i) detach_rubble(i);
    for (auto& g : groups) {
      for (auto& b : g->statics) g->dynamics.removeRigidBody(b.get());
    }
  }

  /// How many groups: `requested`, or with 0 one per 8 robots (up to 32), and a single group
  /// below 8 robots, where splitting gains little (see docs/physics.md). A function of the
  /// scenario alone, never of the machine, so results do not depend on the thread count.
  static int group_count(int requested, int robots) {
    if (requested > 0) return requested;
    if (robots < 8) return 1;
    return std::clamp(robots / 8, 2, 32);
  }

  const MaterialSpec& material(int i) const { return world.materials[static_cast<std::size_t>(i)]; }

  static std::unique_ptr<btRigidBody> make_body(btCollisionShape* shape, btMotionState* motion, const Pose3& X, double mass,
                                                const Vec3& inertia, const MaterialSpec& m, int code) {
    btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), motion, shape, to_bt(inertia));
    info.m_startWorldTransform = to_bt(X);
    info.m_friction = btScalar(m.friction);
    info.m_restitution = btScalar(m.restitution);
    auto body = std::make_unique<btRigidBody>(info);
    body->setUserIndex(code);
    return body;
  }

  void build_statics() {
    if (options.compound_statics) {
      // one body for all walls and obstacles: fewer broadphase entries, one friction for all
      btCompoundShape* all = shapes.compound();
      for (std::size_t i = 0; i < world.statics.size(); ++i) {
        all->addChildShape(to_bt(world.statics[i].X_WO), shapes.make(world.statics[i].geometry));
      }
      static_parts.push_back({all, Pose3{}, world.statics[0].material, encode(kStatic, 0)});
      return;
    }
    for (std::size_t i = 0; i < world.statics.size(); ++i) {
      const StaticObject& s = world.statics[i];
      // the floor as a plane at z = 0: plane contacts are found before bodies touch, so a
      // falling body lands on the step it arrives rather than one step late
      if (s.kind == ObjectKind::floor) {
        static_parts.push_back({shapes.plane(), Pose3{}, s.material, encode(kStatic, static_cast<int>(i))});
      } else {
        static_parts.push_back({shapes.make(s.geometry), s.X_WO, s.material, encode(kStatic, static_cast<int>(i))});
      }
    }
  }

  /// The floor patches (World::ground) with their materials; nothing when the world has none.
  void build_ground() {
    if (world.ground.empty()) return;
    ground = std::make_unique<GroundPatches>();
    for (const GroundArea& g : world.ground) {
      const MaterialSpec& m = material(g.material);
      ground->patches.push_back({g.outline, bounds(g.outline), m.friction, m.restitution});
    }
    ground->floor_child = options.compound_statics ? 0 : -1;
    gContactAddedCallback = ground_contact;
  }

  /// A group's own static bodies, in build order; the floor's (static part 0, World::statics[0])
  /// asks for the floor patches' callback when there are patches.
  void add_statics(PhysicsGroup& g) const {
    for (const StaticPart& part : static_parts) {
      g.statics.push_back(make_body(part.shape, nullptr, part.X, 0, Vec3::Zero(), material(part.material), part.code));
      if (ground && &part == &static_parts.front() && world.statics[0].kind == ObjectKind::floor) {
        btRigidBody* floor = g.statics.back().get();
        floor->setCollisionFlags(floor->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
        floor->setUserPointer(ground.get());
      }
      g.dynamics.addRigidBody(g.statics.back().get());
    }
  }

  void build_rubble() {
    for (std::size_t i = 0; i < world.dynamics.size(); ++i) {
      const DynamicObject& d = world.dynamics[i];
      motion_states.push_back(std::make_unique<btDefaultMotionState>(to_bt(d.X_WO)));
      rubble.push_back(make_body(shapes.make(d.geometry), motion_states.back().get(), d.X_WO, d.mass, d.inertia, material(d.material),
                                 encode(kDynamic, static_cast<int>(i))));
      btRigidBody* b = rubble.back().get();
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
    body.X_BF.resize(spec.links.size());
    body.bt_link.assign(spec.links.size(), -1);
    for (std::size_t l = 0; l < spec.links.size(); ++l) body.X_BF[l] = Pose3{spec.links[l].com, spec.links[l].inertia_axes};
    // each moving joint makes its child body a Bullet link, numbered like the joint
    for (int j = 0; j < n_links; ++j) {
      const JointSpec& js = spec.joints[static_cast<std::size_t>(j)];
      const int parent = spec.link_index(js.parent), child = spec.link_index(js.child);
      body.bt_link[static_cast<std::size_t>(child)] = j;
      const LinkSpec& pl = spec.links[static_cast<std::size_t>(parent)];
      const LinkSpec& cl = spec.links[static_cast<std::size_t>(child)];
      const Pose3& X_PF = body.X_BF[static_cast<std::size_t>(parent)];
      const Pose3& X_CF = body.X_BF[static_cast<std::size_t>(child)];
      // Bullet frames sit at each body's centre of mass along its principal axes; ours at the joint
      body.setup.push_back({js.type, btScalar(cl.mass), to_bt(cl.inertia), body.bt_link[static_cast<std::size_t>(parent)],
                            to_bt((X_PF.q.conjugate() * js.X_PJ.q * X_CF.q).conjugate()), to_bt(X_CF.q.conjugate() * js.axis.normalized()),
                            to_bt(X_PF.q.conjugate() * (js.X_PJ.p - pl.com)), to_bt(X_CF.q.conjugate() * cl.com)});
    }
    body.held.assign(inst.spec.joints.size(), 0);
    body.held_q.assign(inst.spec.joints.size(), 0.0);
    body.owned_mb = make_multibody(body);
    body.mb = body.owned_mb.get();
    body.mb->setBaseWorldTransform(to_bt(inst.X_W_start * body.X_BF[0]));
    for (int j = 0; j < n_links; ++j) {
      if (spec.joints[static_cast<std::size_t>(j)].type != JointSpec::Type::fixed) body.mb->setJointPos(j, btScalar(spec.joints[static_cast<std::size_t>(j)].initial));
    }

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
      auto col = std::make_unique<btMultiBodyLinkCollider>(body.mb, body.bt_link[l]);
      if (auto belts = belts_of(body, l); !belts->empty()) {
        col->setUserPointer(belts.get());
        body.belts.push_back(std::move(belts));
        for (auto& g : groups) g->solver.belts = true;
      }
      col->setCollisionShape(compound);
      col->setFriction(btScalar(friction));
      col->setRestitution(btScalar(restitution));
      if (ls.friction_scale != Vec3::Ones()) col->setAnisotropicFriction(to_bt(ls.friction_scale));
      col->setUserIndex(encode(kRobot, static_cast<int>(l), r));
      body.colliders[l] = col.get();
      colliders.push_back(std::move(col));
    }
    attach_colliders(body);

    const RobotSpec& full = inst.spec;
    for (std::size_t l = 0; l < full.links.size(); ++l) {
      body.top.push_back(spec.links[static_cast<std::size_t>(body.lumped.body_of_link[l])].name == full.links[l].name);
    }
    make_constraints(full, body);
    robots.push_back(std::move(body));
    sync_colliders(robots.back());
  }

  /// The belts over body `l`'s colliding shapes, numbered as its compound's children.
  static std::unique_ptr<std::vector<Belt>> belts_of(const RobotBody& body, std::size_t l) {
    auto belts = std::make_unique<std::vector<Belt>>();
    int child = 0;
    const Pose3 X_FB = body.X_BF[l].inverse();
    for (const auto& sh : body.lumped.spec.links[l].shapes) {
      if (!sh.collides) continue;
      if (!sh.belt_joint.empty()) {
        const int j = body.lumped.spec.joint_index(sh.belt_joint);
        const Vec3 axis = (X_FB * sh.X_LG).q * Vec3::UnitZ();
        if (j >= 0) belts->push_back({child, to_bt(axis), j, btScalar(sh.belt_radius)});
      }
      ++child;
    }
    return belts;
  }

  /// A multibody of the robot's Bullet links, each held joint (RobotBody::held) a fixed link at
  /// its held position; at rest at the origin.
  static std::unique_ptr<btMultiBody> make_multibody(const RobotBody& body) {
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
          mb->setupPrismatic(j, ls.mass, ls.inertia, ls.parent, ls.rot_parent_to_this, ls.axis, ls.parent_com_to_pivot, ls.pivot_to_com, true);
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

  /// Points the robot's colliders at its (new) multibody.
  static void attach_colliders(RobotBody& body) {
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

  /// The robot's actuators, per joint of the description: velocity motors (position loops run on
  /// top of them), Coulomb friction on passive joints (a motor holding zero speed with a bounded
  /// force, as pybullet does), and limits; none for a held joint, whose gear holds it.
  void make_constraints(const RobotSpec& full, RobotBody& body) const {
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

  /// Whether joint `j`'s self-locking gear holds it for the coming step, from the State alone
  /// (so a restore holds the same joints): a self-locking position joint standing within
  /// kSelfLockTolerance of its target and moving slower than kSelfLockSpeed. A held joint
  /// reports zero speed, so it stays held until its target moves away.
  static bool holds(const JointSpec& js, const RobotState& s, std::size_t j) {
    if (!js.self_locking || js.control != JointSpec::Control::position) return false;
    if (j >= s.q.size() || j >= s.qd.size() || j >= s.joint_target.size()) return false;
    return std::abs(s.joint_target[j] - s.q[j]) <= kSelfLockTolerance && std::abs(s.qd[j]) <= kSelfLockSpeed;
  }

  /// Holds and lets go of a robot's self-locking joints as `holds` says. Nothing is allocated
  /// when nothing changes (every step, nearly always). On a change: a new multibody (Bullet fixes
  /// the degrees of freedom of a multibody when it is made), with the old one's pose and
  /// velocities, a joint taken hold of at rest where it stands and one let go at rest where it was
  /// held; new motors and limits. The colliders stay in the world, and their contacts with them.
  void update_held(std::size_t r, const RobotState& s) {
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

  void read_robot(const RobotSpec& spec, const RobotBody& b, RobotState& s, bool stepped = true) const {
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

  /// Puts a robot's multibody, its colliders and its motors and limits into group `g`'s world,
  /// in build order.
  void attach_robot(std::size_t r, int g) {
    RobotBody& b = robots[r];
    btMultiBodyDynamicsWorld& w = groups[static_cast<std::size_t>(g)]->dynamics;
    w.addMultiBody(b.mb);
    for (btMultiBodyLinkCollider* c : b.colliders) {
      if (c) w.addCollisionObject(c, btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
    }
    for (btMultiBodyConstraint* c : b.constraints) w.addMultiBodyConstraint(c);
    robot_group[r] = g;
  }

  /// Takes a robot out of its group's world, in reverse build order. Bullet removes by swapping
  /// with the last element, so that taking out the newest first leaves the rest in place.
  void detach_robot(std::size_t r) {
    if (robot_group[r] < 0) return;
    RobotBody& b = robots[r];
    btMultiBodyDynamicsWorld& w = groups[static_cast<std::size_t>(robot_group[r])]->dynamics;
    for (auto it = b.constraints.rbegin(); it != b.constraints.rend(); ++it) w.removeMultiBodyConstraint(*it);
    for (auto it = b.colliders.rbegin(); it != b.colliders.rend(); ++it) {
      if (*it) w.removeCollisionObject(*it);
    }
    w.removeMultiBody(b.mb);
    robot_group[r] = -1;
  }

  void attach_rubble(std::size_t i, int g) {
    groups[static_cast<std::size_t>(g)]->dynamics.addRigidBody(rubble[i].get());
    rubble_group[i] = g;
  }

  void detach_rubble(std::size_t i) {
    if (rubble_group[i] < 0) return;
    groups[static_cast<std::size_t>(rubble_group[i])]->dynamics.removeRigidBody(rubble[i].get());
    rubble_group[i] = -1;
  }

  /// Which group each robot (entities 0..R-1) and rubble body (R..R+D-1) belongs in: bodies that
  /// could touch within the next step share a group, and the rest keep a home of their own.
  /// Each body's bounding box is grown by kGroupMargin plus the distance its speed carries it over
  /// four steps; bodies whose grown boxes overlap, directly or through others, form a cluster,
  /// and a cluster lives in group (its lowest entity) mod G. So a robot alone is always in group
  /// r mod G, and the grouping is a function of the bodies' poses and speeds alone: a restore
  /// rebuilds it exactly, and it never depends on the thread count.
  std::pair<std::vector<int>, std::vector<int>> grouping() const {
    const std::size_t R = robots.size(), D = rubble.size(), n = R + D;
    const int G = static_cast<int>(groups.size());
    std::vector<int> rg(R, 0), dg(D, 0);
    if (G == 1) return {rg, dg};
    struct Box {
      btVector3 lo, hi;
    };
    std::vector<Box> box(n);
    const btScalar step = btScalar(4 * options.dt);
    auto grow = [&](Box& bx, const btVector3& v) {
      const btScalar m = btScalar(kGroupMargin) + v.length() * step;
      bx.lo -= btVector3(m, m, m);
      bx.hi += btVector3(m, m, m);
    };
    for (std::size_t r = 0; r < R; ++r) {
      Box& bx = box[r];
      bool first = true;
      for (const btMultiBodyLinkCollider* c : robots[r].colliders) {
        if (!c) continue;
        btVector3 lo, hi;
        c->getCollisionShape()->getAabb(c->getWorldTransform(), lo, hi);
        if (first) {
          bx = {lo, hi};
          first = false;
        } else {
          bx.lo.setMin(lo);
          bx.hi.setMax(hi);
        }
      }
      if (first) bx = {robots[r].mb->getBasePos(), robots[r].mb->getBasePos()};
      grow(bx, robots[r].mb->getBaseVel());
    }
    for (std::size_t i = 0; i < D; ++i) {
      const btRigidBody& b = *rubble[i];
      b.getCollisionShape()->getAabb(b.getWorldTransform(), box[R + i].lo, box[R + i].hi);
      grow(box[R + i], b.getLinearVelocity());
    }
    // union-find, the root of a set its lowest entity; overlaps by sweeping boxes sorted on x
    std::vector<std::size_t> parent(n);
    for (std::size_t e = 0; e < n; ++e) parent[e] = e;
    auto find = [&](std::size_t e) {
      while (parent[e] != e) e = parent[e] = parent[parent[e]];
      return e;
    };
    std::vector<std::size_t> order(n);
    for (std::size_t e = 0; e < n; ++e) order[e] = e;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return box[a].lo.x() < box[b].lo.x() || (box[a].lo.x() == box[b].lo.x() && a < b);
    });
    for (std::size_t k = 0; k < n; ++k) {
      const Box& a = box[order[k]];
      // boxes with NaN corners (a body in trouble) compare false and touch nothing
      for (std::size_t l = k + 1; l < n && box[order[l]].lo.x() <= a.hi.x(); ++l) {
        const Box& b = box[order[l]];
        if (b.lo.y() > a.hi.y() || a.lo.y() > b.hi.y() || b.lo.z() > a.hi.z() || a.lo.z() > b.hi.z()) continue;
        const std::size_t ra = find(order[k]), rb = find(order[l]);
        if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
      }
    }
    for (std::size_t r = 0; r < R; ++r) rg[r] = static_cast<int>(find(r) % static_cast<std::size_t>(G));
    for (std::size_t i = 0; i < D; ++i) dg[i] = static_cast<int>(find(R + i) % static_cast<std::size_t>(G));
    return {rg, dg};
  }

  /// Moves every body whose group changed into its new group's world: rubble first, then robots,
  /// each in index order (the order they were built in, so one group holds its bodies as the single
  /// world of earlier versions did). A body that moves leaves its contact manifolds behind, and
  /// with them one step's warm start.
  void regroup() {
    const auto [rg, dg] = grouping();
    for (std::size_t i = 0; i < rubble.size(); ++i) {
      if (rubble_group[i] == dg[i]) continue;
      detach_rubble(i);
      attach_rubble(i, dg[i]);
    }
    for (std::size_t r = 0; r < robots.size(); ++r) {
      if (robot_group[r] == rg[r]) continue;
      detach_robot(r);
      attach_robot(r, rg[r]);
    }
  }

  /// Puts Bullet's hidden state into the one canonical form that depends only on the bodies'
  /// poses (Bullet's advice for repeatable runs): the bodies are regrouped, then everything is
  /// taken out of every group's world — which frees their broadphase proxies, overlapping pairs
  /// and contact manifolds with the warm-start impulses in them — the then empty broadphase is
  /// reset (tree, ids, staging) and the solver's seed zeroed, and everything goes back in the
  /// order it was built in.
  void canonicalise() {
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

  /// Names of what touches each robot of group `g` (`members`), and whether a new collision
  /// began. A group's contacts are between its own bodies, so groups can do this side by side.
  void read_contacts(std::size_t g, const std::vector<std::size_t>& members, State& state) const {
    if (members.empty()) return;
    std::vector<std::vector<int>> touching(robots.size());
    const btCollisionDispatcher& dispatcher = groups[g]->dispatcher;
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
    for (std::size_t r : members) {
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
  if (m.groups.size() > 1) m.regroup();
  for (std::size_t r = 0; r < m.robots.size(); ++r) m.update_held(r, state.robots[r]);
  std::vector<std::vector<std::size_t>> members(m.groups.size());
  for (std::size_t r = 0; r < m.robots.size(); ++r) members[static_cast<std::size_t>(m.robot_group[r])].push_back(r);
  // each group on a thread of its own: they share nothing Bullet writes to, and each robot's
  // targets and read-back touch only its own multibody and its own RobotState
  parallel_for(m.groups.size(), [&](std::size_t g) {
    for (std::size_t r : members[g]) m.apply_targets(m.world.robots[r].spec, m.robots[r], state.robots[r]);
    m.groups[g]->dynamics.stepSimulation(btScalar(options_.dt), 0, btScalar(options_.dt));
    for (std::size_t r : members[g]) m.read_robot(m.world.robots[r].spec, m.robots[r], state.robots[r]);
    m.read_contacts(g, members[g], state);
  });
  for (std::size_t i = 0; i < m.rubble.size(); ++i) {
    const btRigidBody& b = *m.rubble[i];
    state.dynamics[i] = {from_bt(b.getWorldTransform()), from_bt(b.getLinearVelocity()), from_bt(b.getAngularVelocity()), sleep_of(b),
                         b.getDeactivationTime()};
  }
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
