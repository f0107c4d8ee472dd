#include "core/bounded_queue.h"

#include <gtest/gtest.h>

#include <thread>

namespace rescuesim {
namespace {

using namespace std::chrono_literals;

TEST(BoundedQueue, PushDropsTheOldestWhenFull) {
  BoundedQueue<int> q(3);
  EXPECT_TRUE(q.push(1));
  EXPECT_TRUE(q.push(2));
  EXPECT_TRUE(q.push(3));
  // the fourth and fifth push out 1 and 2
  EXPECT_FALSE(q.push(4));
  EXPECT_FALSE(q.push(5));
  EXPECT_EQ(q.size(), 3u);
  EXPECT_EQ(q.dropped(), 2u);
  EXPECT_EQ(q.pop(0ms), 3);
  EXPECT_EQ(q.pop(0ms), 4);
  EXPECT_EQ(q.pop(0ms), 5);
  EXPECT_EQ(q.pop(0ms), std::nullopt);
}

TEST(BoundedQueue, ZeroCapacityHoldsOne) {
  BoundedQueue<int> q(0);
  EXPECT_EQ(q.capacity(), 1u);
  q.push(1);
  q.push(2);
  EXPECT_EQ(q.try_pop(), 2);
  EXPECT_EQ(q.dropped(), 1u);
}

TEST(BoundedQueue, PushWaitWaitsForRoomAndDropsNothing) {
  BoundedQueue<int> q(2);
  q.push_wait(1);
  q.push_wait(2);
  // the producer waits while the queue is full; once 1 is taken, 3 goes in behind 2
  std::thread producer([&] { EXPECT_TRUE(q.push_wait(3)); });
  EXPECT_EQ(q.pop(1s), 1);
  producer.join();
  EXPECT_EQ(q.pop(0ms), 2);
  EXPECT_EQ(q.pop(0ms), 3);
  EXPECT_EQ(q.dropped(), 0u);
}

TEST(BoundedQueue, CloseWakesAWaitingPushWaitWhichDiscardsItsItem) {
  BoundedQueue<int> q(1);
  q.push(1);
  bool result = true;
  std::thread producer([&] { result = q.push_wait(2); });
  q.close();
  producer.join();
  EXPECT_FALSE(result);
  // what was queued before close can still be taken, then the queue reports empty
  EXPECT_EQ(q.pop(0ms), 1);
  EXPECT_EQ(q.pop(1h), std::nullopt);  // closed and drained: returns at once, not after an hour
}

TEST(BoundedQueue, CloseWakesAWaitingPopAndIgnoresLaterPushes) {
  BoundedQueue<int> q(4);
  std::optional<int> got = 7;
  std::thread consumer([&] { got = q.pop(1h); });
  q.close();
  consumer.join();
  EXPECT_EQ(got, std::nullopt);
  EXPECT_TRUE(q.closed());
  EXPECT_TRUE(q.push(5));  // ignored, and not counted as a drop
  EXPECT_EQ(q.size(), 0u);
  EXPECT_EQ(q.dropped(), 0u);
}

TEST(BoundedQueue, PopTimesOutOnAnEmptyQueue) {
  BoundedQueue<int> q(1);
  EXPECT_EQ(q.pop(1ms), std::nullopt);
  EXPECT_EQ(q.try_pop(), std::nullopt);
}

}  // namespace
}  // namespace rescuesim
