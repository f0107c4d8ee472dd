// The recorder on a real run: what a 2 s lockstep run of the default scenario leaves in the
// file (counts computed from the sensor rates), its timestamps and sequences, determinism, and
// the lossless and bounded queue policies.

#include "bridges/mcap/mcap_bridge.h"

#include <gtest/gtest.h>

#include <map>

#include "mcap_test_support.h"
#include "msgs/serialize.h"
#include "robots/rescue_robot.h"
#include "run_record/run_record.h"
#include "session/session.h"
#include "sim/simulation.h"
#include "sim/slider_robot.h"

namespace rescuesim {
namespace {

/// Runs the default scenario (no cameras) for `seconds` with a recorder; returns the Bus counts.
std::map<std::string, std::uint64_t> record_run(const std::filesystem::path& file, double seconds = 2.0, std::uint64_t seed = 7,
                                                McapOptions o = {}, McapRecordingStats* stats = nullptr) {
  const ModelMap models = builtin_models();
  Scenario s = default_scenario(models);
  s.duration = seconds;
  s.seed = seed;
  if (s.maze) s.maze->seed = seed;
  SessionOptions so;
  so.cameras = false;
  Session session(s, models, so);
  o.path = file;
  const bool lossless = o.lossless;  // describe_run picks it from the scenario's mode; the tests choose
  describe_run(o, session.scenario(), session.world_spec(), false, "test");
  o.lossless = lossless;
  McapRecorder recorder(o);
  recorder.start(session.sim());
  const RunResult r = session.run();
  recorder.stop();
  if (stats) *stats = recorder.recording();
  std::map<std::string, std::uint64_t> counts(r.message_counts.begin(), r.message_counts.end());
  return counts;
}

std::map<std::string, std::uint64_t> counts_by_topic(const std::vector<testing::ReadMessage>& messages) {
  std::map<std::string, std::uint64_t> n;
  for (const auto& m : messages) ++n[m.topic];
  return n;
}

class Recorder : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = testing::temp_dir("mcap-recorder");
    bus_counts_ = record_run(dir_ / "run.mcap");
  }
  static inline std::filesystem::path dir_;
  static inline std::map<std::string, std::uint64_t> bus_counts_;
};

TEST_F(Recorder, EveryTopicWithTheCountItsRateGives) {
  mcap::McapReader r(dir_ / "run.mcap");
  const auto counts = counts_by_topic(testing::all_messages(r));
  // 2 s at dt 5 ms: 400 steps, and every stream also publishes at t = 0, so a rate of f Hz
  // gives 2 f + 1 messages (the last at exactly t = 2 s)
  EXPECT_EQ(counts.at("/clock"), 401u);        // every step
  EXPECT_EQ(counts.at("/scan"), 21u);          // 10 Hz
  EXPECT_EQ(counts.at("/sonar/front_left"), 21u);
  EXPECT_EQ(counts.at("/imu/data"), 201u);     // 100 Hz
  EXPECT_EQ(counts.at("/odom"), 101u);         // 50 Hz
  EXPECT_EQ(counts.at("/ground_truth/pose"), 101u);
  EXPECT_EQ(counts.at("/joint_states"), 41u);  // 20 Hz
  EXPECT_EQ(counts.at("/bumper"), 41u);
  EXPECT_EQ(counts.at("/tf"), 202u);           // odom -> base_link with odometry (50 Hz) + joints (50 Hz)
  EXPECT_EQ(counts.at("/tf_static"), 1u);
  // nothing lost: the file has exactly what the Bus carried
  for (const auto& [topic, n] : bus_counts_) EXPECT_EQ(counts.count(topic) ? counts.at(topic) : 0u, n) << topic;
  ASSERT_TRUE(r.statistics());
  EXPECT_EQ(r.statistics()->message_count, 1194u);
  EXPECT_EQ(r.statistics()->message_end_time, 2'000'000'000u);
}

TEST_F(Recorder, Ros2ProfileSchemasAndChannels) {
  mcap::McapReader r(dir_ / "run.mcap");
  EXPECT_EQ(r.header().profile, "ros2");
  EXPECT_EQ(r.header().library, "rescuesim test");
  for (const auto& [id, c] : r.channels()) {
    EXPECT_EQ(c.message_encoding, "cdr") << c.topic;
    const mcap::Schema& s = r.schemas().at(c.schema_id);
    EXPECT_EQ(s.encoding, "ros2msg");
    const msg::TypeSupport* t = msg::find_type(s.name);
    ASSERT_NE(t, nullptr) << s.name;
    EXPECT_EQ(s.name, t->ros2_name);
    EXPECT_EQ(std::string(s.data.begin(), s.data.end()), t->ros2_definition);
    ASSERT_EQ(c.metadata.size(), 1u);
    EXPECT_EQ(c.metadata[0].first, "offered_qos_profiles");
    EXPECT_EQ(c.metadata[0].second.find("durability: 1") != std::string::npos, c.topic == "/tf_static") << c.topic;
  }
  const auto scan = std::find_if(r.channels().begin(), r.channels().end(), [](const auto& c) { return c.second.topic == "/scan"; });
  ASSERT_NE(scan, r.channels().end());
  EXPECT_EQ(r.schemas().at(scan->second.schema_id).name, "sensor_msgs/msg/LaserScan");
  // every zstd chunk indexed
  EXPECT_EQ(r.chunk_indexes().size(), r.chunk_count());
  for (const auto& ci : r.chunk_indexes()) EXPECT_EQ(ci.compression, "zstd");
}

TEST_F(Recorder, TimesAndSequences) {
  mcap::McapReader r(dir_ / "run.mcap");
  std::map<std::string, std::uint32_t> last_sequence;
  std::uint64_t last_log = 0;
  int scans = 0;
  r.read_messages([&](const mcap::Channel& c, const mcap::MessageView& m) {
    EXPECT_GE(m.log_time, last_log);  // written in log-time order
    last_log = m.log_time;
    EXPECT_EQ(m.sequence, ++last_sequence[c.topic]) << c.topic;  // per channel, from 1, no gaps
    const msg::Message decoded = msg::from_cdr(*msg::find_type(r.schemas().at(c.schema_id).name), m.data);
    const std::int64_t stamp = msg::stamp_of(decoded).ns;
    EXPECT_EQ(m.publish_time, stamp > 0 ? static_cast<std::uint64_t>(stamp) : m.log_time) << c.topic;
    if (c.topic == "/scan") {
      // the laser samples at 0, 0.1, ... 2.0 s of sim time and publishes at once
      EXPECT_EQ(m.log_time, static_cast<std::uint64_t>(scans) * 100'000'000u);
      EXPECT_EQ(m.publish_time, m.log_time);
      const auto& scan = std::get<msg::LaserScan>(decoded);
      EXPECT_EQ(scan.ranges.size(), 541u);
      EXPECT_EQ(scan.header.frame_id, "laser");
      ++scans;
    }
    return true;
  });
  EXPECT_EQ(scans, 21);
}

TEST_F(Recorder, DescribesTheRun) {
  mcap::McapReader r(dir_ / "run.mcap");
  const mcap::Metadata* md = r.find_metadata("rescuesim");
  ASSERT_NE(md, nullptr);
  const std::map<std::string, std::string> kv(md->entries.begin(), md->entries.end());
  EXPECT_EQ(kv.at("seed"), "7");
  EXPECT_EQ(kv.at("scenario"), "default");
  EXPECT_EQ(kv.at("version"), "test");
  EXPECT_EQ(kv.at("mode"), "lockstep");
  EXPECT_EQ(kv.at("duration_s"), "2");
  EXPECT_EQ(kv.at("physics_dt_s"), "0.005");
  EXPECT_EQ(kv.at("cameras"), "off");
  ASSERT_NE(r.find_attachment("world.svg"), nullptr);
  ASSERT_NE(r.find_attachment("scenario.yaml"), nullptr);
  const auto& yaml = r.find_attachment("scenario.yaml")->data;
  EXPECT_NE(std::string(yaml.begin(), yaml.end()).find("name: default"), std::string::npos);
  const mcap::Metadata* end = r.find_metadata("rescuesim.recording");
  ASSERT_NE(end, nullptr);
  EXPECT_EQ(end->entries[0], (std::pair<std::string, std::string>{"messages", "1194"}));
  EXPECT_EQ(end->entries[1], (std::pair<std::string, std::string>{"dropped", "0"}));
  // finished files take their name only when complete
  EXPECT_FALSE(std::filesystem::exists(dir_ / "run.mcap.part"));
}

TEST_F(Recorder, SameSeedGivesIdenticalFiles) {
  record_run(dir_ / "again.mcap");
  mcap::McapReader a(dir_ / "run.mcap"), b(dir_ / "again.mcap");
  EXPECT_EQ(testing::all_messages(a), testing::all_messages(b));
  // nothing in the file depends on the wall clock, so the whole files agree
  EXPECT_EQ(testing::read_bytes(dir_ / "run.mcap"), testing::read_bytes(dir_ / "again.mcap"));
}

TEST_F(Recorder, LosslessWithATinyQueueBlocksInsteadOfDropping) {
  // a queue of one message: the simulation thread waits for the recorder at nearly every message
  McapOptions o;
  o.queue_size = 1;
  o.lossless = true;
  McapRecordingStats st;
  record_run(dir_ / "tiny.mcap", 2.0, 7, o, &st);
  EXPECT_EQ(st.dropped, 0u);
  mcap::McapReader a(dir_ / "run.mcap"), b(dir_ / "tiny.mcap");
  EXPECT_EQ(testing::all_messages(a), testing::all_messages(b));
}

TEST_F(Recorder, BoundedModeCountsWhatItDrops) {
  // realtime policy with a two-message queue: whatever is dropped is counted, and sequence
  // numbers (given on the simulation thread) leave gaps exactly where messages are missing
  McapOptions o;
  o.queue_size = 2;
  o.lossless = false;
  McapRecordingStats st;
  const auto bus = record_run(dir_ / "bounded.mcap", 2.0, 7, o, &st);
  mcap::McapReader r(dir_ / "bounded.mcap");
  std::uint64_t published = 0;
  for (const auto& [topic, n] : bus) published += n;
  EXPECT_EQ(st.writer.messages + st.dropped, published);
  std::map<std::string, std::uint32_t> last;
  std::uint64_t gaps = 0;
  r.read_messages([&](const mcap::Channel& c, const mcap::MessageView& m) {
    gaps += m.sequence - last[c.topic] - 1;
    last[c.topic] = m.sequence;
    return true;
  });
  for (const auto& [topic, n] : bus) gaps += n - last[topic];
  EXPECT_EQ(gaps, st.dropped);
  const mcap::Metadata* end = r.find_metadata("rescuesim.recording");
  ASSERT_NE(end, nullptr);
  EXPECT_EQ(end->entries[1].second, std::to_string(st.dropped));
}

TEST(RecorderDescription, ARobotsDescriptionIsALatchedStringChannel) {
  Simulation sim(testing::slider_world());
  const auto dir = testing::temp_dir("mcap-description");
  McapOptions o;
  o.path = dir / "run.mcap";
  McapRecorder recorder(o);
  recorder.start(sim);
  sim.step_until(SimTime::from_seconds(0.5));
  recorder.stop();
  mcap::McapReader r(o.path);
  const auto c =
      std::find_if(r.channels().begin(), r.channels().end(), [](const auto& c) { return c.second.topic == "/robot_description"; });
  ASSERT_NE(c, r.channels().end());
  const mcap::Schema& schema = r.schemas().at(c->second.schema_id);
  EXPECT_EQ(schema.name, "std_msgs/msg/String");
  EXPECT_EQ(schema.encoding, "ros2msg");
  EXPECT_EQ(std::string(schema.data.begin(), schema.data.end()), "string data\n");
  ASSERT_EQ(c->second.metadata.size(), 1u);
  EXPECT_NE(c->second.metadata[0].second.find("durability: 1"), std::string::npos);  // transient local, like /tf_static
  std::vector<std::string> texts;
  r.read_messages([&](const mcap::Channel& ch, const mcap::MessageView& m) {
    if (ch.topic == "/robot_description") {
      texts.push_back(std::get<msg::String>(msg::from_cdr(*msg::find_type("std_msgs/String"), m.data)).data);
    }
    return true;
  });
  ASSERT_EQ(texts.size(), 1u);
  EXPECT_EQ(texts[0], testing::kSliderDescription);
}

TEST(RecorderFile, UnwritablePathIsAnErrorNamingIt) {
  const ModelMap models = builtin_models();
  Scenario s = default_scenario(models);
  SessionOptions so;
  so.cameras = false;
  Session session(s, models, so);
  const auto dir = testing::temp_dir("mcap-unwritable");
  testing::write_text(dir / "file", "x");
  McapOptions o;
  o.path = dir / "file" / "sub" / "run.mcap";  // a folder that cannot exist under a file
  McapRecorder recorder(o);
  try {
    recorder.start(session.sim());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("run.mcap"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rescuesim
