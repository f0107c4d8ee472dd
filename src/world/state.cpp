#include "world/state.h"

#include <cstring>

namespace rescuesim {

namespace {

/// FNV-1a over the bytes of plain values.
struct Hasher {
  std::uint64_t h = 0xcbf29ce484222325ull;
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= c[i];
      h *= 0x100000001b3ull;
    }
  }
  void operator()(double v) {
    if (v == 0) v = 0;  // +0 and -0 hash alike
    bytes(&v, sizeof v);
  }
  void operator()(std::int64_t v) { bytes(&v, sizeof v); }
  void operator()(std::uint64_t v) { bytes(&v, sizeof v); }
  void operator()(int v) { bytes(&v, sizeof v); }
  void operator()(const std::string& s) {
    (*this)(static_cast<std::uint64_t>(s.size()));
    bytes(s.data(), s.size());
  }
  void operator()(const Vec3& v) {
    for (int i = 0; i < 3; ++i) (*this)(v[i]);
  }
  void operator()(const Pose3& p) {
    (*this)(p.p);
    (*this)(p.q.w());
    (*this)(p.q.x());
    (*this)(p.q.y());
    (*this)(p.q.z());
  }
  void operator()(const BodyState& b) {
    (*this)(b.X_WB);
    (*this)(b.v_WB);
    (*this)(b.w_WB);
  }
  void operator()(const std::vector<double>& v) {
    for (double x : v) (*this)(x);
  }
};

}  // namespace

std::uint64_t state_hash(const State& s) {
  Hasher h;
  h(s.time.ns);
  h(s.step);
  for (const auto& b : s.dynamics) h(b);
  for (const auto& r : s.robots) {
    h(r.base);
    h(r.prev_v_WB);
    for (const auto& X : r.X_WL) h(X);
    h(r.q);
    h(r.qd);
    h(r.effort);
    h(r.cmd_linear);
    h(r.cmd_angular);
    h(r.cmd_time.ns);
    h(r.drive_v);
    h(r.drive_w);
    h(r.yaw_rate_integral);
    h(r.joint_target);
    h(r.head_target);
    h(r.odom.x);
    h(r.odom.y);
    h(r.odom.yaw);
    h(r.odom_v);
    h(r.odom_w);
    for (const auto& t : r.touching) h(t);
    h(r.collisions);
    h(r.distance);
  }
  for (const auto& v : s.victims) {
    h(v.first_seen.ns);
    h(v.seen_by);
  }
  for (const auto& sl : s.sensors) {
    h(sl.next_due.ns);
    h(sl.rng.state());
    h(sl.rng.stream());
    h(sl.count);
    h(sl.last_sample.ns);
    for (const auto& m : sl.memory) h(m);
  }
  h(s.trouble.nan_poses);
  h(s.trouble.escaped);
  return h.h;
}

}  // namespace rescuesim
