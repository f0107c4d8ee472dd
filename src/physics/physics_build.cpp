// Building a Physics's Bullet engine from a World: the groups' worlds, the static bodies (one
// per group), the floor patches' materials, rubble, and each robot's multibody with its
// colliders and belts.

#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>

#include <algorithm>
#include <cmath>

#include "physics/physics_impl.h"

namespace rescuesim {

using bullet::to_bt;
using namespace physics_detail;

Physics::Impl::Impl(const World& w, const PhysicsOptions& o) : world(w), options(o) {
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
    group->dispatcher.setDispatcherFlags(group->dispatcher.getDispatcherFlags() &
                                         ~btCollisionDispatcher::CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD);
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

Physics::Impl::~Impl() {
  for (std::size_t r = 0; r < robots.size(); ++r) detach_robot(r);
  for (std::size_t i = 0; i < rubble.size(); ++i) detach_rubble(i);
  for (auto& g : groups) {
    for (auto& b : g->statics) g->dynamics.removeRigidBody(b.get());
  }
}

std::unique_ptr<btRigidBody> Physics::Impl::make_body(btCollisionShape* shape, btMotionState* motion, const Pose3& X, double mass,
                                                      const Vec3& inertia, const MaterialSpec& m, int code) {
  btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), motion, shape, to_bt(inertia));
  info.m_startWorldTransform = to_bt(X);
  info.m_friction = btScalar(m.friction);
  info.m_restitution = btScalar(m.restitution);
  auto body = std::make_unique<btRigidBody>(info);
  body->setUserIndex(code);
  return body;
}

void Physics::Impl::build_statics() {
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

void Physics::Impl::build_ground() {
  if (world.ground.empty()) return;
  ground = std::make_unique<GroundPatches>();
  for (const GroundArea& g : world.ground) {
    const MaterialSpec& m = material(g.material);
    ground->patches.push_back({g.outline, bounds(g.outline), m.friction, m.restitution});
  }
  ground->floor_child = options.compound_statics ? 0 : -1;
  gContactAddedCallback = ground_contact;
}

void Physics::Impl::add_statics(PhysicsGroup& g) const {
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

void Physics::Impl::build_rubble() {
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

bool Physics::Impl::resting_on_ground(const btRigidBody& b) const {
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

void Physics::Impl::build_robot(int r) {
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
    if (spec.joints[static_cast<std::size_t>(j)].type != JointSpec::Type::fixed)
      body.mb->setJointPos(j, btScalar(spec.joints[static_cast<std::size_t>(j)].initial));
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

std::unique_ptr<std::vector<Belt>> Physics::Impl::belts_of(const RobotBody& body, std::size_t l) {
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

}  // namespace rescuesim
