// Camera message decoders against their encoders: an image made into a message with
// color_message, depth_message or thermal_mono16 (no noise) and decoded again gives the same
// pixels; other encodings and short data are refused by name.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "core/rng.h"
#include "sensors/camera/camera.h"

namespace rescuesim {
namespace {

/// A noiseless, undistorted camera of the given kind and size.
SensorSpec plain_camera(SensorSpec::Type type, int w, int h) {
  SensorSpec s;
  s.name = "cam";
  s.type = type;
  s.camera.width = w;
  s.camera.height = h;
  s.camera.min_range = 0.5;
  s.camera.max_range = 4.0;
  return s;
}

TEST(CameraDecode, ColourRoundTripKeepsEveryPixel) {
  ColorImage img;
  img.width = 3;
  img.height = 2;
  for (int i = 0; i < 18; ++i) img.rgb.push_back(static_cast<std::uint8_t>(i * 14));
  Rng rng(1, "cam");
  const msg::Image m = color_message(img, plain_camera(SensorSpec::Type::color_camera, 3, 2), {}, rng);
  const ColorImage back = color_image_of(m);
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.rgb, img.rgb);
}

TEST(CameraDecode, Bgr8AndPaddedRowsAreHonoured) {
  // one row of two pixels, red then blue, in bgr8 with two bytes of padding per row
  msg::Image m;
  m.width = 2;
  m.height = 1;
  m.encoding = "bgr8";
  m.step = 8;
  m.data = {0, 0, 255, 255, 0, 0, 7, 7};
  const ColorImage img = color_image_of(m);
  EXPECT_EQ(img.rgb, (std::vector<std::uint8_t>{255, 0, 0, 0, 0, 255}));
}

TEST(CameraDecode, DepthMetresRoundTripWithNoReturnAsInfinity) {
  DepthImage img;
  img.width = 2;
  img.height = 2;
  // in range, in range, nearer than min_range (0.5 m), no return
  img.z = {1.5f, 3.25f, 0.2f, std::numeric_limits<float>::infinity()};
  Rng rng(1, "cam");
  const DepthImage back = depth_image_of(depth_message(img, plain_camera(SensorSpec::Type::depth_camera, 2, 2), {}, rng));
  ASSERT_EQ(back.z.size(), 4u);
  EXPECT_EQ(back.z[0], 1.5f);
  EXPECT_EQ(back.z[1], 3.25f);
  EXPECT_TRUE(std::isinf(back.z[2]));
  EXPECT_TRUE(std::isinf(back.z[3]));
}

TEST(CameraDecode, DepthMillimetresRoundTripToTheMillimetre) {
  SensorSpec spec = plain_camera(SensorSpec::Type::depth_camera, 2, 1);
  spec.camera.depth_encoding = "16UC1";
  DepthImage img;
  img.width = 2;
  img.height = 1;
  img.z = {1.2344f, 5.0f};  // 1234 mm; beyond max_range (4 m) → 0 → no data
  Rng rng(1, "cam");
  const msg::Image m = depth_message(img, spec, {}, rng);
  ASSERT_EQ(m.encoding, "16UC1");
  const DepthImage back = depth_image_of(m);
  EXPECT_FLOAT_EQ(back.z[0], 1.234f);
  EXPECT_TRUE(std::isinf(back.z[1]));
}

TEST(CameraDecode, ThermalRoundTripToAHundredthOfAKelvin) {
  ThermalImage img;
  img.width = 2;
  img.height = 1;
  img.kelvin = {300.0f, 293.15f};  // 30000 and 29315 counts
  Rng rng(1, "cam");
  const ThermalImage back = thermal_image_of(thermal_mono16(img, plain_camera(SensorSpec::Type::thermal_camera, 2, 1), {}, rng));
  EXPECT_NEAR(back.kelvin[0], 300.0, 1e-4);
  EXPECT_NEAR(back.kelvin[1], 293.15, 1e-4);
}

TEST(CameraDecode, BigEndianMono16IsSwapped) {
  msg::Image m;
  m.width = 1;
  m.height = 1;
  m.encoding = "mono16";
  m.is_bigendian = 1;
  m.step = 2;
  m.data = {0x75, 0x30};  // 0x7530 = 30000 counts = 300 K
  EXPECT_NEAR(thermal_image_of(m).kelvin[0], 300.0, 1e-4);
}

TEST(CameraDecode, UnknownEncodingAndShortDataAreRefusedByName) {
  msg::Image m;
  m.width = 2;
  m.height = 2;
  m.encoding = "yuv422";
  m.step = 4;
  m.data.resize(8);
  try {
    color_image_of(m);
    FAIL() << "yuv422 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("color_image_of"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'yuv422'"), std::string::npos) << e.what();
  }
  m.encoding = "mono16";
  m.data.resize(6);  // 2 rows of 4 bytes need 8
  try {
    thermal_image_of(m);
    FAIL() << "short data was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("thermal_image_of"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("4 bytes per row and 2 rows"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rescuesim
