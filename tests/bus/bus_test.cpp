// The Bus: delivery order, latched replay, shared messages, typed ids and the lock that
// refuses changes from inside a subscriber callback.

#include "bus/bus.h"

#include <gtest/gtest.h>

#include <string>
#include <type_traits>

#include "core/error.h"

namespace rescuesim {
namespace {

TEST(Bus, SubscribersRunInOrderAndLatchedTopicsReplay) {
  Bus bus;
  const TopicId t = bus.advertise("/x", "rosgraph_msgs/Clock");
  const TopicId l = bus.advertise("/latched", "rosgraph_msgs/Clock", 0, true);
  std::string order;
  bus.subscribe("/x", [&](const Topic&, const msg::Message&) { order += "a"; });
  bus.subscribe("", [&](const Topic&, const msg::Message&) { order += "b"; });
  bus.subscribe("/x", [&](const Topic&, const msg::Message&) { order += "c"; });
  bus.publish(t, msg::Clock{SimTime{5}});
  EXPECT_EQ(order, "abc");
  bus.publish(l, msg::Clock{SimTime{7}});
  SimTime got{-1};
  bus.subscribe("/latched", [&](const Topic&, const msg::Message& m) { got = std::get<msg::Clock>(m).clock; });
  EXPECT_EQ(got.ns, 7);
  EXPECT_EQ(bus.count(t), 1u);
  EXPECT_THROW(bus.advertise("/x", "sensor_msgs/Imu"), Error);
}

TEST(Bus, SharedSubscribersKeepTheOneMessageInOrderWithOthers) {
  Bus bus;
  const TopicId t = bus.advertise("/image", "sensor_msgs/Image");
  const TopicId l = bus.advertise("/latched", "rosgraph_msgs/Clock", 0, true);
  std::string order;
  Bus::SharedMessage kept1, kept2;
  std::size_t plain_size = 0;
  bus.subscribe_shared("/image", [&](const Topic&, const Bus::SharedMessage& m) { order += "s"; kept1 = m; });
  bus.subscribe("/image", [&](const Topic&, const msg::Message& m) { order += "p"; plain_size = std::get<msg::Image>(m).data.size(); });
  bus.subscribe_shared("", [&](const Topic& topic, const Bus::SharedMessage& m) {
    order += "S";
    if (topic.id == t) kept2 = m;
  });
  msg::Image image;
  image.width = 640;
  image.height = 480;
  image.data.assign(640 * 480 * 3, 7);
  const std::uint8_t* pixels = image.data.data();
  bus.publish(t, std::move(image));
  EXPECT_EQ(order, "spS");
  EXPECT_EQ(plain_size, 640u * 480 * 3);
  // both kept the very message published: the pixels were moved, never copied
  ASSERT_TRUE(kept1);
  EXPECT_EQ(kept1.get(), kept2.get());
  EXPECT_EQ(std::get<msg::Image>(*kept1).data.data(), pixels);
  // a latched message replays to a late shared subscriber too
  bus.publish(l, msg::Clock{SimTime{9}});
  SimTime got{-1};
  bus.subscribe_shared("/latched", [&](const Topic&, const Bus::SharedMessage& m) { got = std::get<msg::Clock>(*m).clock; });
  EXPECT_EQ(got.ns, 9);
}


TEST(Bus, TopicIdsAndSubscriptionHandlesAreDistinctTypes) {
  // bus.unsubscribe(topic_id) must not compile; nor may a bare int stand for either
  static_assert(!std::is_invocable_v<decltype(&Bus::unsubscribe), Bus&, TopicId>);
  static_assert(!std::is_invocable_v<decltype(&Bus::unsubscribe), Bus&, int>);
  static_assert(!std::is_invocable_v<decltype(&Bus::publish), Bus&, SubscriptionId, msg::Message>);
  static_assert(!std::is_invocable_v<decltype(&Bus::publish), Bus&, int, msg::Message>);
  Bus bus;
  // topic ids count from 0 in advertising order; handles from 1
  EXPECT_EQ(bus.advertise("/a", "rosgraph_msgs/Clock"), TopicId{0});
  EXPECT_EQ(bus.advertise("/b", "rosgraph_msgs/Clock"), TopicId{1});
  EXPECT_EQ(bus.advertise("/a", "rosgraph_msgs/Clock"), TopicId{0});
  EXPECT_EQ(bus.find("/b"), TopicId{1});
  EXPECT_EQ(bus.find("/c"), kNoTopic);
  EXPECT_EQ(bus.topic(TopicId{1}).name, "/b");
  EXPECT_EQ(bus.subscribe("", [](const Topic&, const msg::Message&) {}), SubscriptionId{1});
  EXPECT_EQ(bus.subscribe_shared("", [](const Topic&, const Bus::SharedMessage&) {}), SubscriptionId{2});
}

TEST(Bus, UnsubscribeStopsDeliveryToThatSubscriberOnly) {
  Bus bus;
  const TopicId t = bus.advertise("/x", "rosgraph_msgs/Clock");
  int a = 0, b = 0;
  const SubscriptionId ha = bus.subscribe("/x", [&](const Topic&, const msg::Message&) { ++a; });
  bus.subscribe("/x", [&](const Topic&, const msg::Message&) { ++b; });
  bus.publish(t, msg::Clock{SimTime{1}});
  bus.unsubscribe(ha);
  bus.unsubscribe(ha);  // a second time: nothing
  bus.publish(t, msg::Clock{SimTime{2}});
  EXPECT_EQ(a, 1);
  EXPECT_EQ(b, 2);
  EXPECT_EQ(bus.count(t), 2u);
}

TEST(Bus, ACallbackMayPublishOnAnotherTopic) {
  Bus bus;
  const TopicId in = bus.advertise("/in", "rosgraph_msgs/Clock");
  const TopicId out = bus.advertise("/out", "rosgraph_msgs/Clock");
  std::string order;
  bus.subscribe("/in", [&](const Topic&, const msg::Message& m) {
    order += "i";
    bus.publish(out, msg::Clock{std::get<msg::Clock>(m).clock + SimTime{1}});
  });
  SimTime got{-1};
  bus.subscribe("/out", [&](const Topic&, const msg::Message& m) {
    order += "o";
    got = std::get<msg::Clock>(m).clock;
  });
  bus.publish(in, msg::Clock{SimTime{4}});
  EXPECT_EQ(order, "io");
  EXPECT_EQ(got.ns, 5);
  // after the nested delivery the Bus is unlocked again
  bus.subscribe("/in", [](const Topic&, const msg::Message&) {});
  EXPECT_EQ(bus.topics().size(), 2u);
}

using BusDeathTest = ::testing::Test;

TEST_F(BusDeathTest, SubscribingFromACallbackIsRefused) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  Bus bus;
  const TopicId t = bus.advertise("/x", "rosgraph_msgs/Clock");
  bus.subscribe("/x", [&](const Topic&, const msg::Message&) { bus.subscribe("/x", [](const Topic&, const msg::Message&) {}); });
  EXPECT_DEATH(bus.publish(t, msg::Clock{SimTime{1}}), "Bus::subscribe: called from inside a subscriber callback");
}

TEST_F(BusDeathTest, UnsubscribingAndAdvertisingFromACallbackAreRefused) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  Bus bus;
  const TopicId t = bus.advertise("/x", "rosgraph_msgs/Clock");
  const TopicId u = bus.advertise("/y", "rosgraph_msgs/Clock");
  SubscriptionId self = kNoSubscription;
  self = bus.subscribe("/x", [&](const Topic&, const msg::Message&) { bus.unsubscribe(self); });
  bus.subscribe("/y", [&](const Topic&, const msg::Message&) { bus.advertise("/z", "rosgraph_msgs/Clock"); });
  EXPECT_DEATH(bus.publish(t, msg::Clock{SimTime{1}}), "Bus::unsubscribe: called from inside a subscriber callback");
  EXPECT_DEATH(bus.publish(u, msg::Clock{SimTime{1}}), "Bus::advertise: called from inside a subscriber callback");
}

TEST_F(BusDeathTest, SubscribingFromALatchedReplayIsRefused) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  Bus bus;
  const TopicId l = bus.advertise("/latched", "rosgraph_msgs/Clock", 0, true);
  bus.publish(l, msg::Clock{SimTime{1}});
  // the newcomer's callback runs inside subscribe (the latched replay): the Bus is locked there too
  EXPECT_DEATH(
      bus.subscribe("/latched", [&](const Topic&, const msg::Message&) { bus.subscribe("", [](const Topic&, const msg::Message&) {}); }),
      "Bus::subscribe: called from inside a subscriber callback");
}

TEST_F(BusDeathTest, UnknownTopicIdsAreRefused) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  Bus bus;
  bus.advertise("/x", "rosgraph_msgs/Clock");
  EXPECT_DEATH(bus.publish(TopicId{1}, msg::Clock{}), "Bus::publish: no topic 1 \\(this Bus has 1\\)");
  EXPECT_DEATH(bus.publish(kNoTopic, msg::Clock{}), "Bus::publish: no topic -1");
  EXPECT_DEATH(bus.count(TopicId{7}), "Bus::count: no topic 7");
}

}  // namespace
}  // namespace rescuesim
