// RadioNetwork against link budgets worked by hand: WSS through walls, a cut link that never
// delivers, SubT capacity, multi-hop through a robot and through a dropped relay, widest-path
// routing, bad input, and the same links at 1 and 2 ray-tracing threads.

#include "radio/radio_network.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"
#include "radio_test_worlds.h"

namespace rescuesim {
namespace {

using radio_test::walls_across_x;
using ::testing::HasSubstr;

/// SubT without shadowing and with n = 4: P = −20 − 40·log10 d, linked up to 10^1.75 = 56.2 m.
RadioModel short_subt() {
  RadioModel m = radio_model("subt");
  m.subt.sigma_db = 0;
  m.subt.n = 4;
  return m;
}

std::vector<std::uint8_t> payload(std::size_t n) { return std::vector<std::uint8_t>(n, 0xab); }

TEST(RadioNetworkWss, ReceivedPowerThroughWallsMatchesTheFormula) {
  // radios 10 m apart at 0.5 m height; walls between them at x = 1.5, 2.5, ...
  // P = −49.67 − 10·log10(10/2) − min(walls, 5)·6.325 = −56.6597 − 6.325·min(walls, 5)
  struct Case {
    std::vector<double> wall_x;
    int walls_counted;
    double expected_dbm;
  };
  const std::vector<Case> cases = {
      {{}, 0, -56.6597},
      {{5}, 1, -62.9847},
      {{2.5, 5, 7.5}, 3, -75.6347},
      {{1.5, 2.5, 3.5, 4.5, 5.5, 6.5, 7.5}, 5, -88.2847},  // 7 walls, counted up to 5
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(::testing::Message() << c.wall_x.size() << " walls");
    const World world = walls_across_x(c.wall_x);
    const RayScene scene(world);
    const WallCounter walls(scene, world);
    RadioNetwork net(radio_model("wss"), 1);
    const RadioNodeIndex a = net.add_node("robot1", RadioNodeKind::robot, {0, 0, 0.5});
    const RadioNodeIndex b = net.add_node("robot2", RadioNodeKind::robot, {10, 0, 0.5});
    net.update(&walls);
    const RadioLink& l = net.link(a, b);
    EXPECT_NEAR(l.distance_m, 10.0, 1e-12);
    EXPECT_EQ(l.walls, c.walls_counted);
    EXPECT_NEAR(l.rssi_dbm, c.expected_dbm, 0.01);
    EXPECT_NEAR(l.margin_db, c.expected_dbm + 93.0, 0.01);
    EXPECT_TRUE(l.connected);
    EXPECT_EQ(net.link(b, a).rssi_dbm, l.rssi_dbm);
  }
}

TEST(RadioNetworkWss, DatagramAcrossACutLinkNeverArrives) {
  // 60 m through 5 walls: −49.67 − 10·log10(60/2) − 5·6.325 = −49.67 − 14.7712 − 31.625
  // = −96.0662 dBm < −93: no link (margin −3.07 dB)
  const World world = walls_across_x({10, 20, 30, 40, 50}, -2, 62);
  const RayScene scene(world);
  const WallCounter walls(scene, world);
  RadioNetwork net(radio_model("wss"), 1);
  const RadioNodeIndex a = net.add_node("robot1", RadioNodeKind::robot, {0, 0, 0.5});
  const RadioNodeIndex b = net.add_node("base", RadioNodeKind::base, {60, 0, 0.5});
  net.update(&walls);
  EXPECT_EQ(net.link(a, b).walls, 5);
  EXPECT_NEAR(net.link(a, b).rssi_dbm, -96.0662, 0.01);
  EXPECT_NEAR(net.link(a, b).margin_db, -3.0662, 0.01);
  EXPECT_FALSE(net.link(a, b).connected);
  EXPECT_FALSE(net.status(a).hops_to_base.has_value());
  for (int k = 0; k < 50; ++k) {
    ASSERT_TRUE(net.send(a, b, payload(100)).accepted);
    ASSERT_TRUE(net.send(a, kRadioBroadcast, payload(10)).accepted);
    net.update(&walls);
    net.deliver(0.1);
  }
  EXPECT_TRUE(net.inbox(b).empty());
  EXPECT_EQ(net.status(b).bytes_received, 0u);
  EXPECT_EQ(net.status(a).datagrams_dropped, 100u);
  EXPECT_EQ(net.status(a).bytes_dropped, 50u * 110u);
  EXPECT_EQ(net.dropped(RadioDropReason::no_route), 100u);
  // without the walls the same 60 m link holds (−64.44 dBm)
  RadioNetwork open(radio_model("wss"), 1);
  open.add_node("robot1", RadioNodeKind::robot, {0, 0, 0.5});
  open.add_node("base", RadioNodeKind::base, {60, 0, 0.5});
  open.update();
  EXPECT_NEAR(open.link(RadioNodeIndex(0), RadioNodeIndex(1)).rssi_dbm, -64.4412, 0.01);
  EXPECT_EQ(open.status(RadioNodeIndex(0)).hops_to_base, 1);
}

TEST(RadioNetworkSubt, ShadowingIsTheSameForTheSameSeedAndDiffersForAnother) {
  auto rssi_series = [](std::uint64_t seed) {
    RadioNetwork net(radio_model("subt"), seed);  // σ = 10 dB
    net.add_node("robot1", RadioNodeKind::robot, {0, 0, 0.5});
    net.add_node("robot2", RadioNodeKind::robot, {30, 0, 0.5});
    std::vector<double> out;
    for (int k = 0; k < 5; ++k) {
      net.update();
      out.push_back(net.link(RadioNodeIndex(0), RadioNodeIndex(1)).rssi_dbm);
      // mean 20 − 40 − 15·log10 30 = −42.1568 dBm plus this update's draw
      EXPECT_NEAR(net.link(RadioNodeIndex(0), RadioNodeIndex(1)).rssi_dbm - net.link(RadioNodeIndex(0), RadioNodeIndex(1)).shadowing_db,
                  -42.1568, 0.01);
      EXPECT_EQ(net.link(RadioNodeIndex(0), RadioNodeIndex(1)).shadowing_db,
                link_shadowing_db(net.model(), seed, "robot2", "robot1", net.update_count()));
    }
    return out;
  };
  const std::vector<double> a = rssi_series(5);
  EXPECT_EQ(a, rssi_series(5));
  const std::vector<double> b = rssi_series(6);
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_NE(a[k], b[k]) << "update " << k;
  EXPECT_NE(a[0], a[1]);  // redrawn at each update
}

TEST(RadioNetworkSubt, CapacityDeliversOneMegabitPerSecondAndDropsTheRest) {
  // 250 datagrams of 1000 bytes (2 Mbit) sent over one second, 25 per 0.1 s; the 1 Mbit/s
  // radio carries 125000 bytes per second: 125 arrive, 125 are dropped
  RadioNetwork net(short_subt(), 1);
  const RadioNodeIndex a = net.add_node("robot1", RadioNodeKind::robot, {0, 0, 0.5});
  const RadioNodeIndex b = net.add_node("base", RadioNodeKind::base, {10, 0, 0.5});
  net.update();
  for (int step = 0; step < 10; ++step) {
    for (int k = 0; k < 25; ++k) ASSERT_TRUE(net.send(a, b, payload(1000)).accepted);
    net.deliver(0.1);
  }
  EXPECT_EQ(net.inbox(b).size(), 125u);
  EXPECT_EQ(net.status(b).bytes_received, 125000u);
  EXPECT_EQ(net.status(a).bytes_sent, 250000u);
  EXPECT_EQ(net.status(a).bytes_dropped, 125000u);
  EXPECT_EQ(net.dropped(RadioDropReason::capacity), 125u);
  // the next second has room again: 125 more arrive
  for (int step = 0; step < 10; ++step) {
    for (int k = 0; k < 25; ++k) net.send(a, b, payload(1000));
    net.deliver(0.1);
  }
  EXPECT_EQ(net.inbox(b).size(), 250u);
  // ideal and wss radios have no capacity limit
  RadioNetwork free(radio_model("ideal"), 1);
  free.add_node("robot1", RadioNodeKind::robot, {0, 0, 0.5});
  free.add_node("base", RadioNodeKind::base, {10, 0, 0.5});
  free.update();
  for (int k = 0; k < 250; ++k) free.send(RadioNodeIndex(0), RadioNodeIndex(1), payload(1000));
  free.deliver(0.1);
  EXPECT_EQ(free.inbox(RadioNodeIndex(1)).size(), 250u);
}

TEST(RadioNetworkRouting, DatagramGoesThroughTheRobotBetween) {
  // A(0), B(40), C(80): A–B and B–C are 40 m: −20 − 40·log10 40 = −84.082 dBm (margin 5.92 dB);
  // A–C is 80 m: −20 − 40·log10 80 = −96.124 dBm, no link
  RadioNetwork net(short_subt(), 1);
  const RadioNodeIndex a = net.add_node("A", RadioNodeKind::robot, {0, 0, 0.5});
  const RadioNodeIndex b = net.add_node("B", RadioNodeKind::robot, {40, 0, 0.5});
  const RadioNodeIndex c = net.add_node("C", RadioNodeKind::robot, {80, 0, 0.5});
  net.update();
  EXPECT_NEAR(net.link(a, b).rssi_dbm, -84.0824, 0.01);
  EXPECT_NEAR(net.link(a, b).margin_db, 5.9176, 0.01);
  EXPECT_FALSE(net.link(a, c).connected);
  ASSERT_TRUE(net.send(a, c, {1, 2, 3}).accepted);
  net.deliver(0.1);
  const std::vector<Datagram> got = net.take_inbox(c);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].hops(), 2);
  EXPECT_EQ(got[0].path, (std::vector<RadioNodeIndex>{a, b, c}));
  EXPECT_EQ(got[0].bytes, (std::vector<std::uint8_t>{1, 2, 3}));
  EXPECT_EQ(net.status(b).bytes_forwarded, 3u);
  EXPECT_TRUE(net.inbox(b).empty());
  EXPECT_TRUE(net.inbox(c).empty());  // taken
  // a broadcast from A is one hop: B hears it, C does not
  ASSERT_TRUE(net.send(a, kRadioBroadcast, {9}).accepted);
  net.deliver(0.1);
  EXPECT_EQ(net.inbox(b).size(), 1u);
  EXPECT_TRUE(net.inbox(c).empty());
  // status of A: one neighbour, B, at −84.08 dBm
  const RadioStatus s = net.status(a);
  ASSERT_EQ(s.neighbours.size(), 1u);
  EXPECT_EQ(s.neighbours[0].node, b);
  EXPECT_NEAR(s.neighbours[0].rssi_dbm, -84.0824, 0.01);
}

TEST(RadioNetworkRouting, WidestPathBeatsFewerHopsAndTiesGoToFewerHops) {
  // A(0) and C(50) link directly with margin 90 − 87.959 = 2.04 dB; through B(25) each link is
  // 25 m: −20 − 40·log10 25 = −75.918 dBm, margin 14.08 dB: the route takes B
  RadioNetwork net(short_subt(), 1);
  net.add_node("A", RadioNodeKind::robot, {0, 0, 0.5});
  net.add_node("B", RadioNodeKind::robot, {25, 0, 0.5});
  net.add_node("C", RadioNodeKind::base, {50, 0, 0.5});
  net.update();
  EXPECT_NEAR(net.link(RadioNodeIndex(0), RadioNodeIndex(2)).margin_db, 2.0412, 0.01);
  EXPECT_NEAR(net.link(RadioNodeIndex(0), RadioNodeIndex(1)).margin_db, 14.0824, 0.01);
  EXPECT_EQ(net.route(RadioNodeIndex(0), RadioNodeIndex(2)),
            (std::vector<RadioNodeIndex>{RadioNodeIndex(0), RadioNodeIndex(1), RadioNodeIndex(2)}));
  EXPECT_EQ(net.status(RadioNodeIndex(0)).hops_to_base, 2);
  EXPECT_EQ(net.status(RadioNodeIndex(2)).hops_to_base, 0);  // the base itself
  // ideal: every link is infinitely strong, so the tie goes to the direct link
  RadioNetwork ideal(radio_model("ideal"), 1);
  ideal.add_node("A", RadioNodeKind::robot, {0, 0, 0.5});
  ideal.add_node("B", RadioNodeKind::robot, {25, 0, 0.5});
  ideal.add_node("C", RadioNodeKind::base, {5000, 0, 0.5});
  ideal.update();
  EXPECT_EQ(ideal.route(RadioNodeIndex(0), RadioNodeIndex(2)), (std::vector<RadioNodeIndex>{RadioNodeIndex(0), RadioNodeIndex(2)}));
}

TEST(RadioNetworkRelays, ADroppedRelayRestoresContactWithTheBase) {
  // base at 0, robot at 80 m: −96.12 dBm, out of contact; a relay at 40 m makes two 40 m hops
  RadioNetworkOptions options;
  options.relays_per_robot = 1;
  RadioNetwork net(short_subt(), 1, options);
  const RadioNodeIndex base = net.add_node("base", RadioNodeKind::base, {0, 0, 0.5});
  const RadioNodeIndex robot = net.add_node("robot1", RadioNodeKind::robot, {80, 0, 0.5});
  net.update();
  EXPECT_FALSE(net.status(robot).hops_to_base.has_value());
  EXPECT_EQ(net.relays_left(robot), 1);
  const RelayResult relay = net.add_relay(robot, {40, 0, 0.5});
  ASSERT_TRUE(relay.ok()) << relay.reason;
  EXPECT_EQ(net.node(relay.node).id, "robot1/relay_1");
  EXPECT_EQ(net.node(relay.node).owner, robot);
  EXPECT_EQ(net.relays_left(robot), 0);
  net.update();
  EXPECT_EQ(net.status(robot).hops_to_base, 2);
  EXPECT_EQ(net.status(relay.node).hops_to_base, 1);
  ASSERT_TRUE(net.send(robot, base, payload(8)).accepted);
  net.deliver(0.1);
  ASSERT_EQ(net.inbox(base).size(), 1u);
  EXPECT_EQ(net.inbox(base)[0].path, (std::vector<RadioNodeIndex>{robot, relay.node, base}));
  // the budget is enforced, and only robots drop relays
  const RelayResult more = net.add_relay(robot, {60, 0, 0.5});
  EXPECT_FALSE(more.ok());
  EXPECT_THAT(more.reason, HasSubstr("no relays left (budget 1)"));
  EXPECT_THAT(net.add_relay(base, {1, 0, 0.5}).reason, HasSubstr("not a robot"));
}

TEST(RadioNetworkBadInput, NaNPositionIsNotConnectedAndDoesNotCrash) {
  const World world = walls_across_x({5});
  const RayScene scene(world);
  const WallCounter walls(scene, world);
  RadioNetwork net(radio_model("wss"), 1);
  const RadioNodeIndex a = net.add_node("robot1", RadioNodeKind::robot, {0, 0, 0.5});
  const RadioNodeIndex b = net.add_node("base", RadioNodeKind::base, {std::nan(""), 0, 0.5});
  net.update(&walls);
  EXPECT_FALSE(net.link(a, b).connected);
  EXPECT_TRUE(std::isnan(net.link(a, b).distance_m));
  EXPECT_FALSE(net.status(a).hops_to_base.has_value());
  EXPECT_TRUE(net.status(b).neighbours.empty());
  ASSERT_TRUE(net.send(a, b, payload(4)).accepted);
  net.deliver(0.1);
  EXPECT_TRUE(net.inbox(b).empty());
  EXPECT_EQ(net.dropped(RadioDropReason::no_route), 1u);
  // moved back to a real position, the link returns: 10 m through 1 wall = −62.98 dBm
  const std::vector<Vec3> positions = {{0, 0, 0.5}, {10, 0, 0.5}};
  net.update(positions, &walls);
  EXPECT_NEAR(net.link(a, b).rssi_dbm, -62.9847, 0.01);
  EXPECT_EQ(net.status(a).hops_to_base, 1);
  // a relay at a NaN position is refused
  EXPECT_THAT(net.add_relay(a, {0, std::nan(""), 0}).reason, HasSubstr("not finite"));
  // wrong number of positions, bad dt
  EXPECT_THROW(net.update(std::vector<Vec3>{{0, 0, 0}}, &walls), Error);
  EXPECT_THROW(net.deliver(std::nan("")), Error);
  EXPECT_THROW(net.deliver(-0.1), Error);
}

TEST(RadioNetworkBadInput, OversizedAndMisaddressedDatagramsAreRejectedWithAReason) {
  RadioNetwork net(radio_model("ideal"), 1);
  const RadioNodeIndex a = net.add_node("robot1", RadioNodeKind::robot, {0, 0, 0.5});
  const RadioNodeIndex b = net.add_node("base", RadioNodeKind::base, {5, 0, 0.5});
  net.update();
  const SendResult big = net.send(a, b, payload(65537));
  EXPECT_FALSE(big.accepted);
  EXPECT_THAT(big.reason, HasSubstr("65537 bytes exceeds the 65536-byte limit"));
  EXPECT_TRUE(net.send(a, b, payload(65536)).accepted);
  EXPECT_THAT(net.send(a, RadioNodeIndex(7), payload(1)).reason, HasSubstr("unknown destination node 7"));
  EXPECT_THAT(net.send(RadioNodeIndex(), b, payload(1)).reason, HasSubstr("unknown sender node -1"));  // invalid
  EXPECT_THAT(net.send(a, a, payload(1)).reason, HasSubstr("destination is the sender"));
  EXPECT_EQ(net.status(a).datagrams_sent, 1u);  // only the accepted one
  net.deliver(0.1);
  EXPECT_EQ(net.inbox(b).size(), 1u);
  EXPECT_THROW(net.add_node("base", RadioNodeKind::base, {0, 0, 0}), Error);
  EXPECT_THROW(net.add_node("", RadioNodeKind::robot, {0, 0, 0}), Error);
}

TEST(RadioNetworkBadInput, ImpossibleParametersAreListedWhenTheNetworkIsBuilt) {
  RadioModel m = radio_model("wss");
  m.wss.d0_m = -1;
  m.wss.max_walls = -1;
  try {
    RadioNetwork net(m, 1);
    FAIL() << "no error for impossible parameters";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("radio.wss.d0_m"));
    EXPECT_THAT(e.what(), HasSubstr("radio.wss.max_walls"));
  }
}

/// Ten radios scattered in a world of seven walls, one per metre; all links of one update.
std::vector<RadioLink> ten_radio_links(const WallCounter& walls, int updates) {
  RadioNetwork net(radio_model("wss"), 3);
  for (int i = 0; i < 10; ++i) {
    net.add_node("robot" + std::to_string(i), RadioNodeKind::robot, {0.9 * i, -4.0 + 0.8 * i, 0.3 + 0.05 * i});
  }
  for (int k = 0; k < updates; ++k) net.update(&walls);
  std::vector<RadioLink> out;
  for (RadioNodeIndex a : net.node_indices()) {
    for (RadioNodeIndex b : net.node_indices()) out.push_back(net.link(a, b));
  }
  return out;
}

TEST(RadioNetworkDeterminism, SameLinksAtOneAndTwoRayThreads) {
  const World world = walls_across_x({1.5, 2.5, 3.5, 4.5, 5.5, 6.5, 7.5});
  const RayScene scene(world);
  const WallCounter walls(scene, world);
  set_worker_threads(1);
  const std::vector<RadioLink> one = ten_radio_links(walls, 1);
  set_worker_threads(2);
  const std::vector<RadioLink> two = ten_radio_links(walls, 200);  // 200 updates: also the cost seen in the test time
  set_worker_threads(0);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].walls, two[i].walls) << i;
    EXPECT_EQ(one[i].rssi_dbm, two[i].rssi_dbm) << i;
    EXPECT_EQ(one[i].connected, two[i].connected) << i;
  }
  // node 0 at (0, −4) and node 9 at (8.1, 3.2): the segment crosses all seven walls, counted up to 5
  EXPECT_EQ(one[9].walls, 5);
}

}  // namespace
}  // namespace rescuesim
