// Two lockstep runs with the same seed record byte-identical files, cameras included (their
// frames are rendered on another thread, which must not show in the file); another seed does not.

#include <gtest/gtest.h>

#include "mcap_test_support.h"

namespace rescuesim {
namespace {

/// Records `args` into dir/name with the rescuesim executable.
testing::CommandResult record(const std::filesystem::path& dir, const std::string& name, const std::string& args) {
  return testing::rescuesim("run -q " + args + " --record '" + (dir / name).string() + "' --out '" + (dir / (name + ".out")).string() +
                            "'");
}

TEST(RecordingDeterminism, SameSeedSameBytesWithCameras) {
  const auto dir = testing::temp_dir("mcap-determinism");
  const auto a = record(dir, "a.mcap", "--duration 1 --seed 3");
  if (a.exit_code != 0 && a.err.find("OpenGL") != std::string::npos) GTEST_SKIP() << "no OpenGL for the cameras: " << a.err;
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(record(dir, "b.mcap", "--duration 1 --seed 3").exit_code, 0);
  const auto bytes = testing::read_bytes(dir / "a.mcap");
  EXPECT_GT(bytes.size(), 5'000'000u);  // 11 frames of each camera
  EXPECT_TRUE(bytes == testing::read_bytes(dir / "b.mcap")) << "the two recordings differ";
  mcap::McapReader r(dir / "a.mcap");
  std::uint64_t images = 0;
  for (const auto& [id, n] : r.statistics()->channel_message_counts) {
    images += r.channels().at(id).topic == "/camera/color/image_raw" ? n : 0;
  }
  EXPECT_GE(images, 10u);
}

TEST(RecordingDeterminism, AnotherSeedGivesOtherMessages) {
  const auto dir = testing::temp_dir("mcap-seeds");
  ASSERT_EQ(record(dir, "a.mcap", "--duration 1 --no-cameras --seed 3").exit_code, 0);
  ASSERT_EQ(record(dir, "b.mcap", "--duration 1 --no-cameras --seed 4").exit_code, 0);
  mcap::McapReader a(dir / "a.mcap"), b(dir / "b.mcap");
  EXPECT_NE(testing::all_messages(a), testing::all_messages(b));
}

}  // namespace
}  // namespace rescuesim
