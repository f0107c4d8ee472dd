// The outbound queue policy every bridge shares: per-topic bounds, a byte budget, per-topic
// sequence numbers, drop counts, lossless waiting, and topics that appear late.

#include "bridges/common/outbox.h"

#include <gtest/gtest.h>

#include <thread>

namespace rescuesim {
namespace {

using namespace std::chrono_literals;

Bus::SharedMessage clock_at(std::int64_t ns) { return std::make_shared<const msg::Message>(msg::Clock{SimTime{ns}}); }

Bus::SharedMessage image(std::uint32_t width, std::uint32_t height) {
  msg::Image i;
  i.width = width;
  i.height = height;
  i.data.assign(std::size_t{width} * height * 3, 1);
  return std::make_shared<const msg::Message>(std::move(i));
}

constexpr TopicId kClock{0};
constexpr TopicId kImage{1};

TEST(Outbox, ABurstOfClockMessagesNeverPushesOutAnImage) {
  Outbox box({.per_topic = 64, .byte_budget = 1 << 20});
  const auto img = image(320, 240);  // 230 400 bytes + 256
  box.push(kImage, SimTime{0}, img, Outbox::approx_bytes(*img));
  for (int i = 1; i <= 10000; ++i) box.push(kClock, SimTime{i}, clock_at(i), 256);
  // /clock keeps its newest 64 (10 000 - 64 = 9 936 dropped), the image is still there
  const OutboxStats s = box.stats();
  EXPECT_EQ(s.pushed, 10001u);
  EXPECT_EQ(s.dropped, 9936u);
  EXPECT_EQ(box.dropped(kClock), 9936u);
  EXPECT_EQ(box.dropped(kImage), 0u);
  EXPECT_EQ(s.queued, 65u);
  EXPECT_EQ(s.queued_bytes, 64u * 256 + 230656);
  // the first round takes one of each: the oldest kept /clock (seq 9 937) and the image (seq 1)
  std::vector<OutboxItem> out;
  ASSERT_TRUE(box.take_round(out, 0ms));
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].topic, kClock);
  EXPECT_EQ(out[0].seq, 9937u);
  EXPECT_EQ(out[0].at.ns, 9937);
  EXPECT_EQ(out[1].topic, kImage);
  EXPECT_EQ(out[1].seq, 1u);
  EXPECT_EQ(out[1].message.get(), img.get());  // shared, not copied
}

TEST(Outbox, TheByteBudgetDropsOlderMessagesOfTheSameTopicFirst) {
  // budget 1 000 bytes: two 400-byte images fit, a third pushes out the first
  Outbox box({.per_topic = 10, .byte_budget = 1000});
  EXPECT_TRUE(box.push(kImage, SimTime{1}, image(1, 1), 400));
  EXPECT_TRUE(box.push(kImage, SimTime{2}, image(1, 1), 400));
  EXPECT_FALSE(box.push(kImage, SimTime{3}, image(1, 1), 400));
  EXPECT_EQ(box.stats().queued_bytes, 800u);
  EXPECT_EQ(box.dropped(kImage), 1u);
  // a 300-byte clock does not fit beside 800 bytes of images, and may not push them out
  EXPECT_FALSE(box.push(kClock, SimTime{4}, clock_at(4), 300));
  EXPECT_EQ(box.dropped(kClock), 1u);
  EXPECT_EQ(box.dropped(kImage), 1u);
  // a 200-byte one does (800 + 200 = 1 000)
  EXPECT_TRUE(box.push(kClock, SimTime{5}, clock_at(5), 200));
  EXPECT_EQ(box.stats().queued, 3u);
  EXPECT_EQ(box.stats().dropped, 2u);
  // what is left: images 2 and 3, clock seq 2 (seq counts the dropped one too)
  std::vector<OutboxItem> out;
  box.take_round(out, 0ms);
  box.take_round(out, 0ms);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].topic, kClock);
  EXPECT_EQ(out[0].seq, 2u);
  EXPECT_EQ(out[1].at.ns, 2);
  EXPECT_EQ(out[2].at.ns, 3);
  EXPECT_EQ(box.stats().queued_bytes, 0u);
}

TEST(Outbox, TopicsAdvertisedLateGetAQueueOnTheirFirstMessage) {
  Outbox box;
  box.push(TopicId{7}, SimTime{1}, clock_at(1), 256);
  std::vector<OutboxItem> out;
  ASSERT_TRUE(box.take_round(out, 0ms));
  EXPECT_EQ(out.at(0).topic, TopicId{7});
  EXPECT_EQ(out.at(0).seq, 1u);
}

TEST(Outbox, LosslessPushWaitsForRoomAndDropsNothing) {
  Outbox box({.per_topic = 2, .byte_budget = 0, .lossless = true});
  std::thread producer([&] {
    for (int i = 1; i <= 100; ++i) box.push(kClock, SimTime{i}, clock_at(i), 256);
    box.close();
  });
  std::vector<OutboxItem> out;
  while (!box.drained()) box.take_round(out, 10ms);
  producer.join();
  ASSERT_EQ(out.size(), 100u);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(out[static_cast<std::size_t>(i)].seq, static_cast<std::uint32_t>(i + 1));
  EXPECT_EQ(box.stats().dropped, 0u);
}

TEST(Outbox, CloseWakesTheSenderAndLaterPushesAreCountedAsDropped) {
  Outbox box;
  std::vector<OutboxItem> out;
  std::thread sender([&] { EXPECT_FALSE(box.take_round(out, 1h)); });
  box.close();
  sender.join();
  EXPECT_FALSE(box.push(kClock, SimTime{1}, clock_at(1), 256));
  EXPECT_EQ(box.stats().dropped, 1u);
  EXPECT_TRUE(box.drained());
}

}  // namespace
}  // namespace rescuesim
