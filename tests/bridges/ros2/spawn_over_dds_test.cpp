// Robots spawned and deleted while the ROS 2 bridge runs, seen from a second DDS participant:
// the spawned robot's topics get writers at once (its latched description reaches a late
// joiner, its odometry is in its namespace), its cmd_vel drives it, and when it is deleted its
// writers and readers leave the wire while a robot spawned after it, now one index lower, is
// still driven by its own cmd_vel.

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "bridges/ros2/dds_loopback.h"
#include "bridges/ros2/dds_participant.h"
#include "bridges/ros2/ros2_bridge.h"
#include "msgs/serialize.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "support/dds_domain.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using ros2::DdsParticipant;
using Clock = std::chrono::steady_clock;

RobotInstance spawned_robot(const std::string& name, double x, double y) {
  RobotInstance r = place_robot(name, rescue_robot(), Pose3{Vec3(x, y, 0), Quat::Identity()});
  r.spawned = true;
  r.ns = name;
  return r;
}

template <class T>
std::vector<T> take_all(DdsParticipant& p, int reader, const char* type) {
  std::vector<T> out;
  p.take(reader, [&](std::span<const std::uint8_t> bytes) { out.push_back(std::get<T>(msg::from_cdr(*msg::find_type(type), bytes))); });
  return out;
}

/// Steps `sim` in 50 ms slices until `done` or 20 s of wall time; false on timeout.
template <class F>
bool step_until(Simulation& sim, F done) {
  const auto give_up = Clock::now() + std::chrono::seconds(20);
  while (Clock::now() < give_up) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    sim.step_until(sim.time() + SimTime::from_ms(50));
  }
  return done();
}

TEST(Ros2Spawn, ASpawnedRobotIsOnTheWireDrivenAndGoneWhenDeleted) {
  testing::pin_cyclone_to_loopback();
  const int domain = testing::leased_dds_domain();
  Simulation sim(compile_world(testing::room_spec(20.0, {0, 0, 0}), builtin_models()));
  Ros2Options o;
  o.domain_id = domain;
  auto bridge = make_ros2_bridge(o);
  bridge->start(sim);
  sim.step_until(SimTime::from_seconds(0.5));
  const RobotIndex a = sim.add_robot(spawned_robot("a", 3, -3));
  const RobotIndex b = sim.add_robot(spawned_robot("b", 3, 3));
  ASSERT_EQ(a, RobotIndex(1));
  ASSERT_EQ(b, RobotIndex(2));

  DdsParticipant ros(domain, ros2::participant_user_data());
  const int odom_a = ros.create_reader("rt/a/odom", "nav_msgs::msg::dds_::Odometry_", {});
  const int odom_b = ros.create_reader("rt/b/odom", "nav_msgs::msg::dds_::Odometry_", {});
  const int cmd_b = ros.create_writer("rt/b/cmd_vel", "geometry_msgs::msg::dds_::Twist_", {});
  // the bridge made writers and readers for both at once: they match
  ASSERT_TRUE(step_until(
      sim, [&] { return ros.matched_writers(odom_a) > 0 && ros.matched_writers(odom_b) > 0 && ros.matched_readers(cmd_b) > 0; }));
  std::vector<msg::Odometry> odoms;
  ASSERT_TRUE(step_until(sim, [&] {
    for (auto& m : take_all<msg::Odometry>(ros, odom_a, "nav_msgs/Odometry")) odoms.push_back(m);
    return !odoms.empty();
  }));
  EXPECT_EQ(odoms.back().header.frame_id, "a/odom");
  EXPECT_EQ(odoms.back().child_frame_id, "a/base_link");

  // a is deleted: its writer leaves the wire; b moves down to index 1 and its cmd_vel still drives it
  sim.remove_robot(a);
  ASSERT_EQ(sim.world().robots[1].name, "b");
  EXPECT_TRUE(step_until(sim, [&] { return ros.matched_writers(odom_a) == 0; })) << "the bridge kept a's odometry writer";
  msg::Twist forward;
  forward.linear.x() = 0.4;
  std::vector<std::uint8_t> cmd;
  msg::to_cdr(forward, cmd);
  const double x0 = sim.state().robots[1].base.X_WB.p.x();
  const SimTime since = sim.time();
  ASSERT_TRUE(step_until(sim, [&] {
    std::string error;
    EXPECT_TRUE(ros.write(cmd_b, cmd, &error)) << error;
    return sim.time() - since > SimTime::from_seconds(2.0);
  }));
  bridge->stop();
  // about 2 s at 0.4 m/s, less the speed-up and the first command's way over the wire
  const double moved = sim.state().robots[1].base.X_WB.p.x() - x0;
  EXPECT_GT(moved, 0.4);
  EXPECT_LT(moved, 0.4 * 2.2);
  EXPECT_NEAR(sim.state().robots[0].base.X_WB.p.x(), 0.0, 0.01);  // the scenario's robot was not driven
}

}  // namespace
}  // namespace rescuesim
