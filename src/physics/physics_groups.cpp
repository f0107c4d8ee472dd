// Groups: the bodies spread over independent Bullet worlds, bodies that could touch in the next
// step always in one, and the worlds stepped side by side on the worker threads.

#include <algorithm>

#include "core/parallel.h"
#include "physics/physics_impl.h"

namespace rescuesim {

using namespace physics_detail;

int Physics::Impl::group_count(int requested, int robots) {
  if (requested > 0) return requested;
  if (robots < 8) return 1;
  return std::clamp(robots / 8, 2, 32);
}

void Physics::Impl::attach_robot(std::size_t r, int g) {
  RobotBody& b = robots[r];
  btMultiBodyDynamicsWorld& w = groups[static_cast<std::size_t>(g)]->dynamics;
  w.addMultiBody(b.mb);
  for (btMultiBodyLinkCollider* c : b.colliders) {
    if (c) w.addCollisionObject(c, btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
  }
  for (btMultiBodyConstraint* c : b.constraints) w.addMultiBodyConstraint(c);
  robot_group[r] = g;
}

void Physics::Impl::detach_robot(std::size_t r) {
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

void Physics::Impl::attach_rubble(std::size_t i, int g) {
  groups[static_cast<std::size_t>(g)]->dynamics.addRigidBody(rubble[i].get());
  rubble_group[i] = g;
}

void Physics::Impl::detach_rubble(std::size_t i) {
  if (rubble_group[i] < 0) return;
  groups[static_cast<std::size_t>(rubble_group[i])]->dynamics.removeRigidBody(rubble[i].get());
  rubble_group[i] = -1;
}

std::pair<std::vector<int>, std::vector<int>> Physics::Impl::grouping() const {
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
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return box[a].lo.x() < box[b].lo.x() || (box[a].lo.x() == box[b].lo.x() && a < b); });
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

void Physics::Impl::regroup() {
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

void Physics::Impl::step_groups(State& state) {
  std::vector<std::vector<std::size_t>> members(groups.size());
  for (std::size_t r = 0; r < robots.size(); ++r) members[static_cast<std::size_t>(robot_group[r])].push_back(r);
  // each group on a thread of its own: they share nothing Bullet writes to, and each robot's
  // targets and read-back touch only its own multibody and its own RobotState
  parallel_for(groups.size(), [&](std::size_t g) {
    for (std::size_t r : members[g]) apply_targets(world.robots[r].spec, robots[r], state.robots[r]);
    groups[g]->dynamics.stepSimulation(btScalar(options.dt), 0, btScalar(options.dt));
    for (std::size_t r : members[g]) read_robot(world.robots[r].spec, robots[r], state.robots[r]);
    read_contacts(g, members[g], state);
  });
}

}  // namespace rescuesim
