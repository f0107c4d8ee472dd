// Contacts: the floor patches' materials and the track belts' surface speeds as Bullet makes
// its contacts, what touches each robot after a step (and new collisions), and the trouble
// checks on every body's pose.

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>

#include <algorithm>
#include <cmath>

#include "physics/physics_impl.h"

namespace rescuesim {

namespace physics_detail {

namespace {

bool finite(const Pose3& X) {
  return std::isfinite(X.p.x()) && std::isfinite(X.p.y()) && std::isfinite(X.p.z()) && std::isfinite(X.q.w()) && std::isfinite(X.q.x()) &&
         std::isfinite(X.q.y()) && std::isfinite(X.q.z());
}

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

}  // namespace

const GroundPatches::Patch* GroundPatches::at(const Vec2& p) const {
  for (const Patch& g : patches) {
    if (g.box.contains(p) && contains(g.outline, p)) return &g;
  }
  return nullptr;
}

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

void BeltSolver::convertContacts(btPersistentManifold** manifolds, int n, const btContactSolverInfo& info) {
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

}  // namespace physics_detail

using namespace physics_detail;

void Physics::Impl::read_contacts(std::size_t g, const std::vector<std::size_t>& members, State& state) const {
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

std::string Physics::Impl::name_of(int code) const {
  switch (tag_of(code)) {
    case kStatic: {
      if (options.compound_statics) return "static";
      const StaticObject& s = world.statics[static_cast<std::size_t>(index_of(code))];
      return s.victim.valid() ? world.victim(s.victim).name : s.name;
    }
    case kDynamic: return world.dynamics[static_cast<std::size_t>(index_of(code))].name;
    case kRobot: return world.robots[static_cast<std::size_t>(sub_of(code))].name;
  }
  return "?";
}

std::set<std::string> Physics::Impl::obstacle_names_of(const World& world) {
  std::set<std::string> out;
  for (const auto& s : world.statics) {
    if (s.kind == ObjectKind::wall || s.kind == ObjectKind::obstacle) out.insert(s.name);
  }
  for (const auto& v : world.victims) out.insert(v.name);
  for (const auto& r : world.robots) out.insert(r.name);
  return out;
}

void Physics::Impl::check_trouble(State& state) const {
  const Box2 reach{world.floor.min - Vec2::Constant(options.escape_distance), world.floor.max + Vec2::Constant(options.escape_distance)};
  auto check = [&](const Pose3& X, const std::string& what) {
    if (!finite(X)) {
      if (state.trouble.first.empty())
        state.trouble.first = what + " has a non-finite pose at t = " + std::to_string(state.time.seconds()) + " s";
      ++state.trouble.nan_poses;
    } else if (!reach.contains(X.p.head<2>()) || X.p.z() < -options.escape_distance || X.p.z() > options.escape_distance) {
      if (state.trouble.first.empty()) {
        state.trouble.first = what + " was flung out of the world (to " + std::to_string(X.p.x()) + ", " + std::to_string(X.p.y()) + ", " +
                              std::to_string(X.p.z()) + ") at t = " + std::to_string(state.time.seconds()) + " s";
      }
      ++state.trouble.escaped;
    }
  };
  for (std::size_t i = 0; i < state.dynamics.size(); ++i) check(state.dynamics[i].X_WB, world.dynamics[i].name);
  for (std::size_t r = 0; r < state.robots.size(); ++r) check(state.robots[r].base.X_WB, "robot '" + world.robots[r].name + "'");
}

}  // namespace rescuesim
