// State's one field list: the hash sees every field (each perturbed in turn changes it), the
// part hashes point at the part that changed, and the kinematic start state by hand.

#include "world/state.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "world/world.h"

namespace rescuesim {
namespace {

/// A state with at least one element in every sequence, so every field of the list exists.
State full_state() {
  State s;
  s.time = SimTime::from_seconds(1.5);
  s.step = 300;
  s.dynamics.push_back(BodyState{Pose3{Vec3(1, 2, 0.1), Quat::Identity()}});
  RobotState r;
  r.X_WL = {Pose3{}, Pose3{Vec3(0.2, 0, 0.1), Quat::Identity()}};
  r.q = {0, 0.5};
  r.qd = {0, 0.1};
  r.effort = {0, 2};
  r.joint_target = {0, 0.5};
  r.brake_q = {0, 0.25};
  r.head_target = {0.5};
  r.touching = {"wall_1"};
  s.robots.push_back(r);
  s.victims.push_back(VictimState{SimTime::from_seconds(1), "robot", {SimTime::from_seconds(1)}});
  SensorSlot slot;
  slot.rng = Rng(7, "imu");
  s.sensors.push_back(slot);
  return s;
}

/// Changes one leaf so that it differs from before.
struct Change {
  void operator()(SimTime& t) { t.ns += 1; }
  void operator()(std::int64_t& v) { v += 1; }
  void operator()(std::uint64_t& v) { v += 1; }
  void operator()(int& v) { v += 1; }
  void operator()(double& v) { v += 0.5; }
  void operator()(bool& v) { v = !v; }
  void operator()(BodyState::Sleep& v) { v = v == BodyState::Sleep::asleep ? BodyState::Sleep::awake : BodyState::Sleep::asleep; }
  void operator()(Vec3& v) { v.z() += 0.5; }
  void operator()(Pose3& X) { X.p.y() += 0.5; }
  void operator()(Pose2& X) { X.yaw += 0.5; }
  void operator()(Rng& r) { r.next_u32(); }
  void operator()(std::string& s) { s += "x"; }
  void operator()(std::vector<double>& v) { v.back() += 0.5; }
  void operator()(std::vector<Pose3>& v) { v.back().p.x() += 0.5; }
  void operator()(std::vector<std::string>& v) { v.back() += "x"; }
  void operator()(std::vector<SimTime>& v) { v.push_back(SimTime{3}); }
};

/// Walks the field list, naming each leaf and sequence; changes the one numbered `target`
/// (sequences count too: changing one means appending an element).
struct Perturber {
  int target = -1;
  int seen = 0;
  std::string changed;
  std::vector<std::string> path;

  std::string name(const char* leaf) const {
    std::string n;
    for (const auto& p : path) n += p + ".";
    return n + leaf;
  }
  template <class T>
  void operator()(const char* leaf, T& value) {
    if (seen++ == target) {
      Change{}(value);
      changed = name(leaf);
    }
  }
  template <class F>
  void group(const char* g, F&& f) {
    path.emplace_back(g);
    f(*this);
    path.pop_back();
  }
  template <class E, class F>
  void items(const char* seq, std::vector<E>& v, F&& f) {
    const bool grow = seen++ == target;
    for (std::size_t i = 0; i < v.size(); ++i) {
      path.push_back(std::string(seq) + "[" + std::to_string(i) + "]");
      f(*this, v[i]);
      path.pop_back();
    }
    if (grow) {
      v.emplace_back();
      changed = name(seq) + " (one more)";
    }
  }
};

TEST(StateHash, EveryFieldOfTheListChangesTheHash) {
  const State base = full_state();
  const std::uint64_t h0 = state_hash(base);
  Perturber count;
  State probe = base;
  visit_fields(probe, count);
  // 2 top-level leaves, 4 sequences, 5 per body, per robot its base's 5 + 1 + 1 + 3 + 11 + 3 + 3,
  // 3 per victim, 8 per sensor slot, 4 schedule and 3 trouble leaves
  EXPECT_EQ(count.seen, 2 + 4 + 5 + 27 + 3 + 8 + 4 + 3);
  for (int k = 0; k < count.seen; ++k) {
    State s = base;
    Perturber p;
    p.target = k;
    visit_fields(s, p);
    ASSERT_FALSE(p.changed.empty()) << k;
    EXPECT_NE(state_hash(s), h0) << "changing " << p.changed << " does not change state_hash";
  }
}

TEST(StateHash, EqualStatesHashAlikeAndSignedZerosToo) {
  State a = full_state(), b = full_state();
  EXPECT_EQ(state_hash(a), state_hash(b));
  b.robots[0].drive_v = -0.0;  // a's is +0
  EXPECT_EQ(state_hash(a), state_hash(b));
}

TEST(StateHash, AnRngHoldingASpareNormalHashesApartFromOneThatDoesNot) {
  // Marsaglia's method makes two deviates at a time and keeps the second: after one normal()
  // the stream holds a spare, and the next normal() returns it without moving the generator
  State a = full_state(), b = full_state();
  a.sensors[0].rng.normal();
  b.sensors[0].rng = a.sensors[0].rng;
  b.sensors[0].rng.normal();
  ASSERT_EQ(a.sensors[0].rng.state(), b.sensors[0].rng.state());
  ASSERT_FALSE(a.sensors[0].rng == b.sensors[0].rng);
  EXPECT_NE(state_hash(a), state_hash(b));
}

TEST(StateHash, PartsNameWhatChanged) {
  const State base = full_state();
  State s = base;
  s.robots[0].qd[1] += 1;
  const auto before = state_part_hashes(base), after = state_part_hashes(s);
  ASSERT_EQ(before.size(), after.size());
  std::vector<std::string> differ;
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_EQ(before[i].first, after[i].first);
    if (before[i].second != after[i].second) differ.push_back(before[i].first);
  }
  EXPECT_EQ(differ, std::vector<std::string>{"robots[0].joints"});
  // the parts: top-level leaves, each sequence's length, each element, a robot's groups
  std::vector<std::string> names;
  for (const auto& [n, h] : before) names.push_back(n);
  const std::vector<std::string> expected{"time", "step", "dynamics", "dynamics[0]", "robots", "robots[0].base", "robots[0].links",
                                          "robots[0].joints", "robots[0].commands", "robots[0].odometry", "robots[0].contacts",
                                          "victims", "victims[0]", "sensors", "sensors[0]", "schedule", "trouble"};
  EXPECT_EQ(names, expected);
}

TEST(InitialState, PlacesLinksByForwardKinematicsFromTheStartPose) {
  // a base with one arm joint about z, 0.2 m ahead and 0.1 m up, starting at 0.5 rad
  RobotSpec spec;
  spec.model = "arm_bot";
  LinkSpec base, arm;
  base.name = "base_link";
  arm.name = "arm";
  spec.links = {base, arm};
  JointSpec j;
  j.name = "pan";
  j.parent = "base_link";
  j.child = "arm";
  j.X_PJ = Pose3{Vec3(0.2, 0, 0.1), Quat::Identity()};
  j.control = JointSpec::Control::position;
  j.initial = 0.5;
  spec.joints = {j};
  spec.head_joints = {"pan"};
  World w;
  // the robot starts at (1, 2) facing +y
  w.robots.push_back(
      RobotInstance{"robot", spec, Pose3{Vec3(1, 2, 0), Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()))}, false, ""});
  DynamicObject box;
  box.X_WO = Pose3{Vec3(3, 0, 0.1), Quat::Identity()};
  w.dynamics.push_back(box);
  w.victims.resize(2);

  const State s = initial_state(w);
  ASSERT_EQ(s.robots.size(), 1u);
  const RobotState& r = s.robots[0];
  EXPECT_EQ(s.time.ns, 0);
  EXPECT_NEAR((r.base.X_WB.p - Vec3(1, 2, 0)).norm(), 0, 1e-12);
  // arm origin: (1, 2, 0) + Rz(90°)(0.2, 0, 0.1) = (1, 2.2, 0.1); heading 90° + 0.5 rad
  ASSERT_EQ(r.X_WL.size(), 2u);
  EXPECT_NEAR((r.X_WL[1].p - Vec3(1, 2.2, 0.1)).norm(), 0, 1e-12);
  const Vec3 x_axis = r.X_WL[1].q * Vec3::UnitX();
  EXPECT_NEAR(std::atan2(x_axis.y(), x_axis.x()), std::numbers::pi / 2 + 0.5, 1e-12);
  EXPECT_EQ(r.q, (std::vector<double>{0.5}));
  EXPECT_EQ(r.qd, (std::vector<double>{0.0}));
  EXPECT_EQ(r.joint_target, (std::vector<double>{0.5}));
  EXPECT_EQ(r.head_target, (std::vector<double>{0.5}));
  ASSERT_EQ(s.dynamics.size(), 1u);
  EXPECT_EQ(s.dynamics[0].X_WB.p, Vec3(3, 0, 0.1));
  EXPECT_EQ(s.dynamics[0].v_WB, Vec3::Zero());
  EXPECT_EQ(s.victims.size(), 2u);
  EXPECT_TRUE(s.sensors.empty());
  EXPECT_FALSE(s.schedule.started);
}

}  // namespace
}  // namespace rescuesim
