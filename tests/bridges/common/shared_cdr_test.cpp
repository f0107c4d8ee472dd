// One CDR encoding of a large message for every bridge (bridges/common/shared_cdr.h): the same
// bytes object for every bridge that asks while the message lives, byte for byte what to_cdr
// writes, forgotten when the message goes; small messages are encoded afresh and not kept.

#include "bridges/common/shared_cdr.h"

#include <gtest/gtest.h>

#include <thread>

#include "msgs/serialize.h"

namespace rescuesim {
namespace {

Bus::SharedMessage image(std::uint32_t width, std::uint32_t height) {
  msg::Image i;
  i.header.stamp = SimTime::from_ms(100);
  i.header.frame_id = "camera_optical_frame";
  i.width = width;
  i.height = height;
  i.encoding = "rgb8";
  i.step = width * 3;
  i.data.resize(std::size_t{width} * height * 3);
  for (std::size_t k = 0; k < i.data.size(); ++k) i.data[k] = static_cast<std::uint8_t>(k * 7);
  return std::make_shared<const msg::Message>(std::move(i));
}

TEST(SharedCdr, ALargeMessageIsEncodedOnceForEveryBridgeWhileItLives) {
  {
    const Bus::SharedMessage img = image(640, 480);  // 921 600 bytes of pixels
    const SharedBytes first = shared_cdr(img);
    const SharedBytes second = shared_cdr(img);
    EXPECT_EQ(first.get(), second.get());  // the same bytes object: encoded once
    std::vector<std::uint8_t> expected;
    msg::to_cdr(*img, expected);
    EXPECT_EQ(*first, expected);
    // 4 encapsulation + 4 sec + 4 nanosec + (4 + 21) frame_id + 3 pad + 4 height + 4 width
    // + (4 + 5) encoding + 1 is_bigendian + 2 pad + 4 step + 4 length + 921 600 pixels
    EXPECT_EQ(first->size(), 4u + 8 + 25 + 3 + 8 + 9 + 1 + 2 + 4 + 4 + 921600);
    EXPECT_EQ(shared_cdr_entries(), 1u);
    // another message, even of equal content, has bytes of its own
    const Bus::SharedMessage other = image(640, 480);
    EXPECT_NE(shared_cdr(other).get(), first.get());
    EXPECT_EQ(shared_cdr_entries(), 2u);
  }
  // both messages gone: nothing kept
  EXPECT_EQ(shared_cdr_entries(), 0u);
}

TEST(SharedCdr, ASmallMessageIsEncodedAfreshAndNotKept) {
  msg::LaserScan scan;
  scan.ranges.assign(10, 1.5f);
  const auto m = std::make_shared<const msg::Message>(scan);
  const SharedBytes a = shared_cdr(m), b = shared_cdr(m);
  EXPECT_NE(a.get(), b.get());
  EXPECT_EQ(*a, *b);
  EXPECT_EQ(shared_cdr_entries(), 0u);
}

TEST(SharedCdr, BridgesAskingAtOnceGetTheSameBytes) {
  const Bus::SharedMessage img = image(320, 240);
  std::vector<SharedBytes> got(3);
  std::vector<std::thread> bridges;
  for (std::size_t k = 0; k < got.size(); ++k) bridges.emplace_back([&, k] { got[k] = shared_cdr(img); });
  for (auto& t : bridges) t.join();
  // two may have encoded at the same moment, but what they hand on is equal, and one is kept
  for (const SharedBytes& g : got) EXPECT_EQ(*g, *got[0]);
  EXPECT_EQ(shared_cdr_entries(), 1u);
  EXPECT_EQ(shared_cdr(img).get(), shared_cdr(img).get());
}

}  // namespace
}  // namespace rescuesim
