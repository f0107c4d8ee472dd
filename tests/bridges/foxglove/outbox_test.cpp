// The Foxglove bridge queues for its serialiser thread under the Outbox policy the ROS bridges
// share (bridges/common/outbox.h): a bounded queue per topic, so a burst of small messages on
// one topic pushes out only older messages of that topic, never an image waiting on another,
// and a byte budget over all topics that a message meets by pushing out older messages of its
// own topic, or is dropped itself.
//
// The bridge runs in this process on a Simulation nobody steps (this thread publishes, as the
// simulation thread would); the reference client (outbox_client.js) subscribes. While the
// serialiser thread is held between rounds (FoxgloveBridge::pause_serialiser), this thread
// publishes, so what the outbox holds and drops is computed by hand, then the serialiser is let
// go and the client reports what reached it.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <functional>
#include <set>
#include <thread>

#include "bridges/common/outbox.h"
#include "bridges/foxglove/bridge_impl.h"
#include "bridges/foxglove/server_rig.h"
#include "core/local_ports.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"

namespace rescuesim {
namespace {

using json = nlohmann::json;

/// The rgb8 images published on /big and /big2: 320 x 240, every byte the image's marker.
constexpr std::uint32_t kWidth = 320, kHeight = 240;
constexpr std::size_t kImageData = std::size_t{kWidth} * kHeight * 3;  // 230 400 bytes
/// What the outbox counts for them, and for a PoseStamped (Outbox::approx_bytes: 256 + data).
constexpr std::size_t kImageBytes = 256 + kImageData;
constexpr std::size_t kSmallBytes = 256;

json last_json(const std::string& out) {
  const auto end = out.find_last_not_of('\n');
  const auto start = out.rfind('\n', end);
  const std::size_t from = start == std::string::npos ? 0 : start + 1;
  return json::parse(out.substr(from, end + 1 - from));
}

/// A one-robot room with /burst, /probe (PoseStamped), /big and /big2 (Image) advertised.
struct Rig {
  Simulation sim;
  TopicId burst, probe, big, big2;

  static World room() { return testing::one_wall_room(); }
  Rig()
      : sim(room()),
        burst(sim.bus().advertise("/burst", "geometry_msgs/PoseStamped")),
        probe(sim.bus().advertise("/probe", "geometry_msgs/PoseStamped")),
        big(sim.bus().advertise("/big", "sensor_msgs/Image")),
        big2(sim.bus().advertise("/big2", "sensor_msgs/Image")) {}

  void pose(TopicId topic, double x) {
    msg::PoseStamped p;
    p.header = {sim.time(), "map"};
    p.pose.p = Vec3(x, 0, 0);
    sim.bus().publish(topic, p);
  }
  void image(TopicId topic, std::uint8_t marker) {
    msg::Image m;
    m.header = {sim.time(), "camera"};
    m.width = kWidth;
    m.height = kHeight;
    m.encoding = "rgb8";
    m.step = kWidth * 3;
    m.data.assign(kImageData, marker);
    sim.bus().publish(topic, m);
  }
};

/// What one run through the bridge gave.
struct Outcome {
  std::uint64_t dropped_while_held = 0;  ///< BridgeStats::dropped added by `publish`, before the serialiser ran again
  std::uint64_t dropped_in_all = 0;      ///< ... and once the client had everything (adds the per-client queues' drops)
  json client;                           ///< outbox_client.js's report
};

/// Starts the bridge with `options`, connects outbox_client.js (waiting for /burst numbered
/// `last_x` and the /big image marked `last_marker`), holds the serialiser, runs `publish`,
/// lets the serialiser go and waits for the client.
Outcome run_through_bridge(Rig& rig, FoxgloveOptions options, double last_x, int last_marker, const std::function<void()>& publish) {
  Outcome o;
  options.port = free_local_port();
  EXPECT_GT(options.port, 0);
  foxglove::FoxgloveBridge bridge(options);
  bridge.start(rig.sim);
  testing::CommandResult r;
  std::atomic<bool> done = false;
  std::jthread client([&] {
    r = testing::node_script("outbox_client.js", "ws://127.0.0.1:" + std::to_string(options.port) + " " + std::to_string(last_x) + " " +
                                                     std::to_string(last_marker));
    done = true;
  });
  // the client subscribes to /probe last: once a probe went out, its other subscriptions are in.
  // Probes published before it subscribed are not queued; one probe a second after that (the
  // serialiser sends one within milliseconds) leaves at most a few queued, on their own topic.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (bridge.stats().sent == 0 && !done && std::chrono::steady_clock::now() < deadline) {
    rig.pose(rig.probe, 0);
    const auto next = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    while (bridge.stats().sent == 0 && !done && std::chrono::steady_clock::now() < next) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  EXPECT_GT(bridge.stats().sent, 0u) << "the client never subscribed";

  bridge.pause_serialiser();
  const std::uint64_t before = bridge.stats().dropped;
  publish();
  o.dropped_while_held = bridge.stats().dropped - before;
  bridge.resume_serialiser();

  client.join();
  o.dropped_in_all = bridge.stats().dropped - before;
  bridge.stop();
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  o.client = r.out.empty() ? json::object() : last_json(r.out);
  return o;
}

std::multiset<double> bursts(const json& client) {
  std::multiset<double> s;
  for (const auto& x : client["bursts"]) s.insert(x.get<double>());
  return s;
}

class FoxgloveOutbox : public testing::NodeClientTest {};

TEST_F(FoxgloveOutbox, ABurstOnOneTopicPushesOutOnlyItsOwnOlderMessagesNeverAnImage) {
  Rig rig;
  FoxgloveOptions options;
  options.bridge_queue = 4;  // per topic
  // one image, then 100 small messages on /burst: /burst keeps its newest 4 (97..100) and drops
  // 96; the image on /big stays queued and goes out. (One queue of 4 for everything, as before
  // the Outbox, would have pushed the image out with the burst's fifth message.)
  const Outcome o = run_through_bridge(rig, options, 100, 1, [&] {
    rig.image(rig.big, 1);
    for (int i = 1; i <= 100; ++i) rig.pose(rig.burst, i);
  });
  EXPECT_EQ(o.dropped_while_held, 96u);
  EXPECT_EQ(o.dropped_in_all, 96u);  // and none in the client's own queue (5 messages, 0.2 MiB)
  EXPECT_TRUE(o.client["errors"].empty()) << o.client;
  EXPECT_EQ(bursts(o.client), (std::multiset<double>{97, 98, 99, 100})) << o.client["bursts"];
  ASSERT_EQ(o.client["images"].size(), 1u) << o.client["images"];
  const json& image = o.client["images"][0];
  EXPECT_EQ(image["topic"], "/big");
  EXPECT_EQ(image["marker"], 1);
  EXPECT_EQ(image["bytes"], kImageData);
  EXPECT_TRUE(image["uniform"].get<bool>());
}

TEST_F(FoxgloveOutbox, TheByteBudgetIsMetByDroppingTheSameTopicsOlderMessagesOrTheNewOne) {
  Rig rig;
  FoxgloveOptions options;
  options.bridge_queue = 4;  // per topic
  // room for two images and 8 small messages (at most 4 of them probes still queued)
  options.bridge_queue_bytes = 2 * kImageBytes + 8 * kSmallBytes;
  // /big: images 1 and 2 fit, image 3 does not: it pushes out image 1 (1 dropped)
  // /burst: 10 small messages, 4 kept (7..10; 6 dropped), within the budget beside two images
  // /big2: an image with no older one of its own to push out: it is dropped (1 dropped)
  const Outcome o = run_through_bridge(rig, options, 10, 3, [&] {
    for (std::uint8_t marker : {1, 2, 3}) rig.image(rig.big, marker);
    for (int i = 1; i <= 10; ++i) rig.pose(rig.burst, i);
    rig.image(rig.big2, 9);
  });
  EXPECT_EQ(o.dropped_while_held, 1u + 6u + 1u);
  EXPECT_EQ(o.dropped_in_all, 8u);
  EXPECT_TRUE(o.client["errors"].empty()) << o.client;
  EXPECT_EQ(bursts(o.client), (std::multiset<double>{7, 8, 9, 10})) << o.client["bursts"];
  ASSERT_EQ(o.client["images"].size(), 2u) << o.client["images"];
  std::multiset<int> markers;
  for (const auto& image : o.client["images"]) {
    EXPECT_EQ(image["topic"], "/big") << image;
    EXPECT_EQ(image["bytes"], kImageData);
    EXPECT_TRUE(image["uniform"].get<bool>());
    markers.insert(image["marker"].get<int>());
  }
  EXPECT_EQ(markers, (std::multiset<int>{2, 3}));
}

}  // namespace
}  // namespace rescuesim
