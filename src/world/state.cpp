#include "world/state.h"

#include <algorithm>

#include "world/world.h"

namespace rescuesim {

namespace {

/// FNV-1a over the bytes of every leaf that `visit_fields` hands it.
struct Hasher {
  std::uint64_t h = 0xcbf29ce484222325ull;
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= c[i];
      h *= 0x100000001b3ull;
    }
  }
  void value(double v) {
    if (v == 0) v = 0;  // +0 and -0 hash alike
    bytes(&v, sizeof v);
  }
  void value(std::int64_t v) { bytes(&v, sizeof v); }
  void value(std::uint64_t v) { bytes(&v, sizeof v); }
  void value(int v) { bytes(&v, sizeof v); }
  void value(bool v) { value(v ? 1 : 0); }
  void value(BodyState::Sleep v) { value(static_cast<int>(v)); }
  void value(SimTime t) { value(t.ns); }
  void value(const std::string& s) {
    value(static_cast<std::uint64_t>(s.size()));
    bytes(s.data(), s.size());
  }
  void value(const Vec3& v) {
    for (int i = 0; i < 3; ++i) value(v[i]);
  }
  void value(const Pose3& p) {
    value(p.p);
    value(p.q.w());
    value(p.q.x());
    value(p.q.y());
    value(p.q.z());
  }
  void value(const Pose2& p) {
    value(p.x);
    value(p.y);
    value(p.yaw);
  }
  void value(const Rng& r) {
    value(r.state());
    value(r.stream());
    // the spare normal deviate is private: the next normal of a copy returns it when there is one
    Rng copy = r;
    value(copy.normal());
  }
  template <class T>
  void value(const std::vector<T>& v) {
    value(static_cast<std::uint64_t>(v.size()));
    for (const auto& x : v) value(x);
  }

  // the visitor interface of visit_fields
  template <class T>
  void operator()(const char*, const T& leaf) {
    value(leaf);
  }
  template <class F>
  void group(const char*, F&& f) {
    f(*this);
  }
  template <class E, class F>
  void items(const char*, const std::vector<E>& v, F&& f) {
    value(static_cast<std::uint64_t>(v.size()));
    for (const auto& e : v) f(*this, e);
  }
};

/// Hashes each leaf into the part named by the first two levels of its path.
struct PartHasher {
  std::vector<std::string> path;
  std::vector<std::pair<std::string, Hasher>> parts;

  Hasher& part(const char* leaf) {
    std::string name = path.empty() ? leaf : path[0];
    if (path.size() > 1) name += "." + path[1];
    if (parts.empty() || parts.back().first != name) parts.emplace_back(name, Hasher{});
    return parts.back().second;
  }
  template <class T>
  void operator()(const char* name, const T& leaf) {
    part(name).value(leaf);
  }
  template <class F>
  void group(const char* name, F&& f) {
    path.emplace_back(name);
    f(*this);
    path.pop_back();
  }
  template <class E, class F>
  void items(const char* name, const std::vector<E>& v, F&& f) {
    // the count belongs to the part of the whole sequence
    path.emplace_back(name);
    part(name).value(static_cast<std::uint64_t>(v.size()));
    path.pop_back();
    for (std::size_t i = 0; i < v.size(); ++i) {
      path.push_back(std::string(name) + "[" + std::to_string(i) + "]");
      f(*this, v[i]);
      path.pop_back();
    }
  }
};

}  // namespace

State initial_state(const World& world) {
  State s;
  s.dynamics.reserve(world.dynamics.size());
  for (const auto& d : world.dynamics) s.dynamics.push_back(BodyState{d.X_WO});
  for (const auto& r : world.robots) {
    const RobotSpec& spec = r.spec;
    RobotState rs;
    const std::vector<double> q0 = initial_positions(spec);
    for (const Pose3& X_BL : link_poses(spec, q0)) rs.X_WL.push_back(r.X_W_start * X_BL);
    rs.base.X_WB = rs.X_WL.front();
    rs.q = q0;
    rs.qd.assign(spec.joints.size(), 0.0);
    rs.effort.assign(spec.joints.size(), 0.0);
    // position-controlled joints and the head hold where they start
    rs.joint_target.assign(spec.joints.size(), 0.0);
    for (std::size_t j = 0; j < spec.joints.size(); ++j) {
      if (spec.joints[j].control == JointSpec::Control::position) rs.joint_target[j] = spec.joints[j].initial;
    }
    for (const auto& name : spec.head_joints)
      rs.head_target.push_back(spec.joints[static_cast<std::size_t>(spec.joint_index(name))].initial);
    rs.lights_on = spec.lights_on && !spec.lights.empty();
    s.robots.push_back(std::move(rs));
  }
  s.victims.assign(world.victims.size(), VictimState{});
  return s;
}

std::uint64_t state_hash(const State& s) {
  Hasher h;
  visit_fields(s, h);
  return h.h;
}

std::vector<std::pair<std::string, std::uint64_t>> state_part_hashes(const State& s) {
  PartHasher p;
  visit_fields(s, p);
  std::vector<std::pair<std::string, std::uint64_t>> out;
  for (const auto& [name, h] : p.parts) out.emplace_back(name, h.h);
  return out;
}

}  // namespace rescuesim
