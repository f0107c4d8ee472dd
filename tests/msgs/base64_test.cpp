// Base64 against RFC 4648's test vectors (section 10), both ways, and text that is not base64.

#include "msgs/base64.h"

#include <gtest/gtest.h>

namespace rescuesim::msg {
namespace {

std::vector<std::uint8_t> bytes(std::string_view s) { return {s.begin(), s.end()}; }

TEST(Base64, Rfc4648Vectors) {
  const std::pair<const char*, const char*> vectors[] = {{"", ""},         {"f", "Zg=="},         {"fo", "Zm8="},    {"foo", "Zm9v"},
                                                         {"foob", "Zm9vYg=="}, {"fooba", "Zm9vYmE="}, {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : vectors) {
    std::string out;
    const auto b = bytes(plain);
    append_base64(out, b.data(), b.size());
    EXPECT_EQ(out, encoded) << plain;
    const auto back = decode_base64(encoded);
    ASSERT_TRUE(back) << encoded;
    EXPECT_EQ(*back, b) << encoded;
  }
}

TEST(Base64, EveryByteValueRoundTrips) {
  std::vector<std::uint8_t> all(256);
  for (int i = 0; i < 256; ++i) all[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(i);
  std::string text;
  append_base64(text, all.data(), all.size());
  EXPECT_EQ(text.size(), 344u);  // 4 * ceil(256 / 3)
  EXPECT_EQ(decode_base64(text), all);
}

TEST(Base64, TextThatIsNotBase64IsRefused) {
  for (const char* bad : {"Zg=", "Zg", "Z===", "Zm9v!A==", "Zg==Zg==", "Zm=v", "Zm9 v", "=AAA"}) {
    EXPECT_FALSE(decode_base64(bad)) << bad;
  }
}

}  // namespace
}  // namespace rescuesim::msg
