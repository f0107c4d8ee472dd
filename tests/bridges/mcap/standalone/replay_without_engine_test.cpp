// Record and replay with no physics engine, no ray scene and no importer: this program links
// rs_mcap and rs_robots (the built-in robot's description) and nothing that steps a world or
// reads a file. Its world is drawn in code and compiled by `world`; a ReplayHost stands in for
// the simulation while recording (known scans published by hand), then McapPlayer plays the
// file back onto a fresh host's Bus, handed the same world. The checks `replay_links_no_engine`
// and `replay_links_no_importer` (tests/checks) read this binary's dynamic section and fail if
// Bullet's dynamics or collision libraries or Embree, or a parser of the importers (tinyxml2,
// yaml-cpp, urdfdom, assimp, sdformat), were linked in.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bridges/mcap/mcap_bridge.h"
#include "bridges/mcap/mcap_player.h"
#include "bridges/mcap/replay_host.h"
#include "robots/rescue_robot.h"
#include "support/command.h"
#include "world/world.h"

namespace rescuesim {
namespace {

TEST(ReplayWithoutEngine, ScansRecordedOnAReplayHostComeBackExactly) {
  const auto dir = testing::temp_dir("replay-without-engine");
  WorldSpec spec;
  spec.name = "hand";
  spec.materials = default_materials();
  spec.robots.push_back(RobotPlacement{});
  const std::uint64_t seed = 7;
  const World world = compile_world(spec, builtin_models());

  // record: five scans at 10 Hz whose ranges are 1 m + k cm (k = scan number)
  McapOptions o;
  o.path = dir / "hand.mcap";
  {
    ReplayHost host(world, seed);
    const TopicId scan = host.bus().advertise("/scan", "sensor_msgs/LaserScan", 10);
    McapRecorder recorder(o);
    recorder.start(host);
    for (int k = 0; k < 5; ++k) {
      msg::LaserScan m;
      m.header.stamp = SimTime::from_ms(100 * (k + 1));
      m.header.frame_id = "laser";
      m.angle_min = -1.0f;
      m.angle_max = 1.0f;
      m.angle_increment = 0.5f;
      m.range_min = 0.1f;
      m.range_max = 30.0f;
      m.ranges.assign(5, 1.0f + 0.01f * static_cast<float>(k));
      host.set_time(m.header.stamp);
      host.bus().publish(scan, m);
    }
    recorder.stop();
    EXPECT_EQ(recorder.stats().sent, 5u);
  }

  // replay: the same five scans, in order, with the host clock at each one's log time
  McapPlayer player(o.path, [&](const mcap::McapReader&) { return ReplayWorld{world, seed}; });
  EXPECT_EQ(player.world().robots.size(), 1u);
  BridgeHost& host = player.host();
  ASSERT_NE(host.bus().find("/scan"), kNoTopic);
  std::vector<float> first_ranges;
  std::vector<std::int64_t> clocks;
  host.bus().subscribe("/scan", [&](const Topic&, const msg::Message& m) {
    const auto& scan = std::get<msg::LaserScan>(m);
    ASSERT_EQ(scan.ranges.size(), 5u);
    first_ranges.push_back(scan.ranges[0]);
    clocks.push_back(host.time().ns);
  });
  const PlayResult r = player.play(1000.0);
  EXPECT_EQ(r.messages, 5u);
  ASSERT_EQ(first_ranges.size(), 5u);
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(first_ranges[k], 1.0f + 0.01f * static_cast<float>(k));
    EXPECT_EQ(clocks[k], 100'000'000LL * (k + 1));
  }
}

}  // namespace
}  // namespace rescuesim
