// The recorder while robots are spawned and deleted (Simulation::add_robot, remove_robot): a
// spawned robot's topics get their channels (and schemas) when their first message comes, a
// deleted robot's topics simply stop, and one of that name spawned again records on the same
// channels. Counts by hand from the laser's 10 Hz schedule (tests/sim/spawn_test.cpp).

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "bridges/mcap/mcap_bridge.h"
#include "mcap_test_support.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

/// The built-in robot as SpawnEntity makes it, with a description so it offers robot_description.
RobotInstance spawned_p3at() {
  RobotSpec spec = rescue_robot();
  spec.description = R"(<robot name="p3at"><link name="base_link"/></robot>)";
  RobotInstance r = place_robot("p3at", spec, Pose3{Vec3(3, 3, 0), Quat::Identity()});
  r.spawned = true;
  r.ns = "p3at";
  return r;
}

TEST(McapSpawn, ASpawnedRobotIsRecordedOnItsOwnChannelsUntilItIsDeleted) {
  const auto file = testing::temp_dir("mcap-spawn") / "run.mcap";
  Simulation sim(compile_world(testing::room_spec(), builtin_models()), SimOptions{});
  McapOptions o;
  o.path = file;
  McapRecorder recorder(o);
  recorder.start(sim);
  sim.step_until(SimTime::from_seconds(1.0));
  ASSERT_EQ(sim.add_robot(spawned_p3at()), RobotIndex(1));
  sim.step_until(SimTime::from_seconds(2.0));
  sim.remove_robot(RobotIndex(1));
  sim.step_until(SimTime::from_seconds(2.5));
  ASSERT_EQ(sim.add_robot(spawned_p3at()), RobotIndex(1));
  sim.step_until(SimTime::from_seconds(3.0));
  recorder.stop();
  EXPECT_EQ(recorder.recording().dropped, 0u);
  EXPECT_TRUE(recorder.recording().error.empty()) << recorder.recording().error;

  mcap::McapReader r(file);
  std::map<std::string, std::uint64_t> counts;
  std::vector<std::uint64_t> p3at_scans;
  r.read_messages([&](const mcap::Channel& c, const mcap::MessageView& m) {
    ++counts[c.topic];
    if (c.topic == "/p3at/scan") p3at_scans.push_back(m.log_time);
    return true;
  });
  // its laser is due at once (sampled after the next step, 5 ms on), then on the 0.1 s grid
  // from the spawn: 1.005, 1.1, ..., 2.0 s (11 scans) until it is deleted at 2 s; spawned again
  // at 2.5 s: 2.505, 2.6, ..., 3.0 s (6)
  ASSERT_EQ(p3at_scans.size(), 17u);
  EXPECT_EQ(p3at_scans[0], 1'005'000'000u);
  EXPECT_EQ(p3at_scans[1], 1'100'000'000u);
  EXPECT_EQ(p3at_scans[10], 2'000'000'000u);
  EXPECT_EQ(p3at_scans[11], 2'505'000'000u);
  EXPECT_EQ(p3at_scans[16], 3'000'000'000u);
  EXPECT_EQ(counts["/p3at/robot_description"], 2u);  // latched, once per spawn
  EXPECT_EQ(counts["/scan"], 31u);                    // the scenario's robot, 0 to 3 s, untouched
  // one channel per topic, spawned twice or not; the spawned robot's with their schemas
  std::map<std::string, int> channels;
  for (const auto& [id, c] : r.channels()) {
    ++channels[c.topic];
    if (c.topic == "/p3at/scan") {
      ASSERT_TRUE(r.schemas().count(c.schema_id));
      EXPECT_EQ(r.schemas().at(c.schema_id).name, "sensor_msgs/msg/LaserScan");
    }
  }
  for (const auto& [topic, n] : channels) EXPECT_EQ(n, 1) << topic;
  // nothing lost: the file has exactly what the Bus carried
  std::uint64_t total = 0;
  for (const Topic& t : sim.bus().topics()) {
    EXPECT_EQ(counts.count(t.name) ? counts.at(t.name) : 0u, sim.bus().count(t.id)) << t.name;
    total += sim.bus().count(t.id);
  }
  ASSERT_TRUE(r.statistics());
  EXPECT_EQ(r.statistics()->message_count, total);
}

}  // namespace
}  // namespace rescuesim
