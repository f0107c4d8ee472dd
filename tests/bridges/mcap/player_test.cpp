// Replay: a recording played back into a rebuilt simulation puts the same messages on its Bus,
// in order, paced to the wall clock, with the simulation's clock following; recording the
// replay gives the same message records back.

#include "bridges/mcap/mcap_player.h"

#include <gtest/gtest.h>

#include <map>

#include "bridges/mcap/mcap_bridge.h"
#include "mcap_test_support.h"
#include "robots/rescue_robot.h"
#include "run_record/run_record.h"
#include "session/session.h"

namespace rescuesim {
namespace {

class Player : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = testing::temp_dir("mcap-player");
    const ModelMap models = builtin_models();
    Scenario s = default_scenario(models);
    s.duration = 2.0;
    SessionOptions so;
    so.cameras = false;
    Session session(s, models, so);
    McapOptions o;
    o.path = dir_ / "run.mcap";
    describe_run(o, session.scenario(), session.world_spec(), false, "test");
    McapRecorder recorder(o);
    recorder.start(session.sim());
    session.run();
    recorder.stop();
  }
  static inline std::filesystem::path dir_;
};

TEST_F(Player, RebuildsTheSimulationWithTheRecordedTopics) {
  RecordedRun run;
  McapPlayer player(dir_ / "run.mcap", rebuild_into(run, builtin_models()));
  EXPECT_EQ(run.scenario.seed, 7u);
  EXPECT_EQ(player.world().robots.size(), 1u);
  EXPECT_EQ(player.host().time().ns, 0);
  for (const auto& [id, c] : player.reader().channels()) EXPECT_NE(player.host().bus().find(c.topic), kNoTopic) << c.topic;
  EXPECT_TRUE(player.host().bus().topic(player.host().bus().find("/tf_static")).latched);
}

TEST_F(Player, PublishesEveryMessageInOrderWithTheClockFollowing) {
  RecordedRun run;
  McapPlayer player(dir_ / "run.mcap", rebuild_into(run, builtin_models()));
  ReplayHost& sim = player.host();
  std::map<std::string, std::uint64_t> counts;
  std::vector<msg::LaserScan> scans;
  std::int64_t last = -1;
  bool clock_follows = true;
  sim.bus().subscribe("", [&](const Topic& t, const msg::Message& m) {
    ++counts[t.name];
    if (sim.time().ns < last) clock_follows = false;
    last = sim.time().ns;
    if (const auto* c = std::get_if<msg::Clock>(&m)) clock_follows = clock_follows && c->clock == sim.time();
    if (const auto* s = std::get_if<msg::LaserScan>(&m)) scans.push_back(*s);
  });
  // 2 s of recording at 20x: a tenth of a second of wall time
  const PlayResult r = player.play(20.0);
  EXPECT_EQ(r.messages, 1194u);
  EXPECT_EQ(r.skipped, 0u);
  EXPECT_DOUBLE_EQ(r.duration, 2.0);
  EXPECT_GE(r.wall_time, 0.099);
  EXPECT_LT(r.wall_time, 2.0);
  EXPECT_TRUE(clock_follows);
  EXPECT_EQ(sim.time().ns, 2'000'000'000);
  EXPECT_EQ(counts["/clock"], 401u);
  EXPECT_EQ(counts["/scan"], 21u);
  ASSERT_EQ(scans.size(), 21u);
  EXPECT_EQ(scans[20].header.stamp.ns, 2'000'000'000);
  EXPECT_EQ(scans[20].ranges.size(), 541u);
}

TEST_F(Player, StopsWhenAsked) {
  RecordedRun run;
  McapPlayer player(dir_ / "run.mcap", rebuild_into(run, builtin_models()));
  std::atomic<bool> stop{false};
  std::uint64_t n = 0;
  player.host().bus().subscribe("", [&](const Topic&, const msg::Message&) {
    if (++n == 100) stop = true;
  });
  const PlayResult r = player.play(1000.0, &stop);
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.messages, 100u);
}

TEST_F(Player, RecordingAReplayGivesTheSameMessages) {
  RecordedRun run;
  McapPlayer player(dir_ / "run.mcap", rebuild_into(run, builtin_models()));
  McapOptions o;
  o.path = dir_ / "replayed.mcap";
  McapRecorder recorder(o);
  recorder.start(player.host());
  player.play(1000.0);
  recorder.stop();
  mcap::McapReader a(dir_ / "run.mcap"), b(dir_ / "replayed.mcap");
  EXPECT_EQ(testing::all_messages(a), testing::all_messages(b));
}

TEST_F(Player, TheReplayHostHasNoSimulationAndDiscardsCommands) {
  // the player and its ReplayHost alone: a Bus, the recorded world and a clock, no physics
  RecordedRun run;
  McapPlayer player(dir_ / "run.mcap", rebuild_into(run, builtin_models()));
  BridgeHost& host = player.host();
  EXPECT_EQ(host.time().ns, 0);
  EXPECT_EQ(host.world().robots.size(), 1u);
  EXPECT_EQ(host.topic_name(RobotIndex(0), "cmd_vel"), "/cmd_vel");  // one robot: no namespace
  EXPECT_EQ(host.frame_name(RobotIndex(0), "base_link"), "base_link");
  EXPECT_EQ(host.seed(), 7u);
  // the state is the world's start: one record per rubble body and victim, none found
  EXPECT_EQ(host.state().dynamics.size(), host.world().dynamics.size());
  ASSERT_EQ(host.state().victims.size(), host.world().victims.size());
  for (const VictimState& v : host.state().victims) EXPECT_EQ(v.first_seen.ns, -1);
  // commands are taken (a bridge counts them received) and discarded: nothing is simulated
  msg::Twist t;
  t.linear.x() = 0.5;
  EXPECT_TRUE(host.command_velocity(RobotIndex(0), t));
  EXPECT_TRUE(host.command_head(RobotIndex(0), {0, 0, 0, 0}));
  EXPECT_EQ(player.host().discarded(), 2u);
  // the clock is the log time of the message being published
  std::int64_t clock_at_last_scan = -1;
  host.bus().subscribe("/scan", [&](const Topic&, const msg::Message&) { clock_at_last_scan = host.time().ns; });
  player.play(1000.0);
  EXPECT_EQ(clock_at_last_scan, 2'000'000'000);
}

TEST(PlayerBadInput, ForeignMcapIsNotARescuesimRecording) {
  const auto dir = testing::temp_dir("mcap-foreign");
  {
    mcap::McapWriter w(std::make_unique<mcap::FileSink>(dir / "foreign.mcap"));
    w.add_channel(w.add_schema("std_msgs/msg/String", "ros2msg", "string data"), "/chatter", "cdr");
  }
  try {
    RecordedRun run;
    McapPlayer player(dir / "foreign.mcap", rebuild_into(run, builtin_models()));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("foreign.mcap: not a rescuesim recording"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rescuesim
