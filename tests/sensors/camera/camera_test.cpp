// Camera sensors end to end through EGL on Mesa: a depth camera 2 m from a wall, its point
// cloud, 16-bit millimetres, thermal counts and victims as warm blobs, CameraInfo, distortion.

#include "sensors/camera/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "sensors/ray_sensor_world.h"
#include "support/require_gl.h"

namespace rescuesim {
namespace {

using testing::box_robot;
using testing::compile_with;
using testing::empty_spec;
using testing::wall_facing_west;

/// A camera on a box robot at the origin looking east (+x), level, at `height` above base_link.
SensorSpec camera(SensorSpec::Type type, int w, int h, double hfov_deg) {
  SensorSpec s;
  s.name = "cam";
  s.type = type;
  s.link = "base_link";
  s.X_LS = Pose3{Vec3(0.2, 0, 0.3), Quat::Identity()};
  s.rate = 10;
  s.frame_id = "cam_optical";
  s.camera.width = w;
  s.camera.height = h;
  s.camera.hfov = hfov_deg * M_PI / 180;
  s.camera.min_range = 0.1;
  s.camera.max_range = 10;
  s.camera.blur_sigma = 0;
  return s;
}

struct Scene {
  World world;
  State state;
  std::unique_ptr<Renderer> renderer;
  std::string gl_problem;  ///< why there is no renderer (the EGL call that failed), or empty
};

/// A world with a wall whose face is 2.0 m in front of the camera (camera at x = 0.2).
Scene wall_scene(const SensorSpec& cam, WorldSpec spec = empty_spec()) {
  spec.walls.push_back(wall_facing_west(2.2));
  RobotPlacement p;
  p.model = "box_bot";
  spec.robots.push_back(p);
  Scene s{compile_with(spec, box_robot({cam})), {}, nullptr, {}};
  s.state = initial_state(s.world);
  try {
    s.renderer = Renderer::create_headless(Quality::low);
  } catch (const Error& e) {
    s.gl_problem = e.what();
    return s;
  }
  RenderScene rs = build_render_scene(s.world);
  s.renderer->load(rs);
  update_render_scene(rs, s.state);
  s.renderer->update(rs);
  return s;
}

#define NEED_GL(scene) RS_GL_OR_SKIP((scene).renderer != nullptr, (scene).gl_problem)

float depth_at(const msg::Image& m, int x, int y) {
  float z;
  std::memcpy(&z, &m.data[(static_cast<std::size_t>(y) * m.width + static_cast<std::size_t>(x)) * 4], 4);
  return z;
}

TEST(CameraDepth, WallTwoMetresAwayReadsTwoMetres) {
  const SensorSpec cam = camera(SensorSpec::Type::depth_camera, 160, 120, 60);
  Scene s = wall_scene(cam);
  NEED_GL(s);
  Rng rng(1, "t");
  const msg::Image m =
      depth_message(s.renderer->depth(camera_view(s.world, s.state, RobotIndex(0), cam)), cam, {SimTime{}, "cam_optical"}, rng);
  EXPECT_EQ(m.encoding, "32FC1");
  // the wall is a plane 2.000 m along the optical axis: every pixel of the centre region reads it
  for (int y = 30; y < 90; y += 3) {
    for (int x = 40; x < 120; x += 3) ASSERT_NEAR(depth_at(m, x, y), 2.0, 0.002) << x << "," << y;
  }
}

TEST(CameraDepth, PointCloudLiesOnTheWallPlane) {
  const SensorSpec cam = camera(SensorSpec::Type::depth_camera, 80, 60, 60);
  Scene s = wall_scene(cam);
  NEED_GL(s);
  Rng rng(1, "t");
  const msg::Image depth = depth_message(s.renderer->depth(camera_view(s.world, s.state, RobotIndex(0), cam)), cam, {}, rng);
  const msg::PointCloud2 pc = depth_cloud(depth, cam);
  ASSERT_EQ(pc.width * pc.height, 80u * 60u);
  int on_plane = 0;
  for (std::size_t i = 0; i < pc.width * pc.height; ++i) {
    float p[3];
    std::memcpy(p, &pc.data[i * 12], 12);
    if (!std::isfinite(p[2])) continue;
    // optical frame: the wall is the plane z = 2 (floor pixels are nearer)
    if (std::abs(p[2] - 2.0f) < 0.002f) ++on_plane;
  }
  EXPECT_GT(on_plane, 80 * 60 / 3);
}

TEST(CameraDepth, MillimetresAndOutOfRange) {
  SensorSpec cam = camera(SensorSpec::Type::depth_camera, 80, 60, 60);
  cam.camera.depth_encoding = "16UC1";
  Scene s = wall_scene(cam);
  NEED_GL(s);
  Rng rng(1, "t");
  const msg::Image mm = depth_message(s.renderer->depth(camera_view(s.world, s.state, RobotIndex(0), cam)), cam, {}, rng);
  std::uint16_t v;
  std::memcpy(&v, &mm.data[(30 * 80 + 40) * 2], 2);
  EXPECT_NEAR(v, 2000, 2);
  // the same wall beyond max_range is no data: 0 in 16UC1
  cam.camera.max_range = 1.5;
  const msg::Image none = depth_message(s.renderer->depth(camera_view(s.world, s.state, RobotIndex(0), cam)), cam, {}, rng);
  std::memcpy(&v, &none.data[(30 * 80 + 40) * 2], 2);
  EXPECT_EQ(v, 0);
}

TEST(CameraDepth, QuadraticNoiseGrowsWithDistance) {
  SensorSpec cam = camera(SensorSpec::Type::depth_camera, 160, 120, 60);
  cam.camera.depth_noise_quadratic = 0.005;  // sigma = 0.005 * 2^2 = 2 cm at 2 m
  Scene s = wall_scene(cam);
  NEED_GL(s);
  Rng rng(3, "t");
  const msg::Image m = depth_message(s.renderer->depth(camera_view(s.world, s.state, RobotIndex(0), cam)), cam, {}, rng);
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int y = 30; y < 90; ++y) {
    for (int x = 40; x < 120; ++x) {
      const double e = depth_at(m, x, y) - 2.0;
      sum += e;
      sum2 += e * e;
      ++n;
    }
  }
  EXPECT_NEAR(std::sqrt(sum2 / n - (sum / n) * (sum / n)), 0.02, 0.001);
}

TEST(CameraThermal, UniformSurfaceDecodesWithinATenthOfAKelvin) {
  SensorSpec cam = camera(SensorSpec::Type::thermal_camera, 80, 60, 50);
  WorldSpec spec = empty_spec();
  MaterialSpec warm = *spec.find_material("wall");
  warm.name = "warm";
  warm.temperature = 305.0;
  warm.emissivity = 1.0;
  spec.set_material(warm);
  Scene s = [&] {
    spec.walls.push_back(wall_facing_west(2.2));
    spec.walls.back().material = "warm";
    spec.walls.back().height = 3.0;
    RobotPlacement p;
    p.model = "box_bot";
    spec.robots.push_back(p);
    Scene out{compile_with(spec, box_robot({cam})), {}, nullptr, {}};
    out.state = initial_state(out.world);
    try {
      out.renderer = Renderer::create_headless(Quality::low);
      RenderScene rs = build_render_scene(out.world);
      out.renderer->load(rs);
      update_render_scene(rs, out.state);
      out.renderer->update(rs);
    } catch (const Error& e) {
      out.gl_problem = e.what();
    }
    return out;
  }();
  NEED_GL(s);
  Rng rng(1, "t");
  const msg::Image m = thermal_mono16(s.renderer->thermal(camera_view(s.world, s.state, RobotIndex(0), cam), 0), cam, {}, rng);
  EXPECT_EQ(m.encoding, "mono16");
  std::uint16_t c;
  std::memcpy(&c, &m.data[(20 * 80 + 40) * 2], 2);  // above the horizon: the wall
  EXPECT_NEAR(kelvin_of_count(c), 305.0, 0.1);
  const msg::Image m8 = thermal_mono8(m, cam);
  // 305 K in the 288.15..313.15 K window: (305 - 288.15) / 25 * 255 = 171.9
  EXPECT_NEAR(m8.data[20 * 80 + 40], 172, 1);
}

TEST(CameraThermal, VictimIsHotterThanTheWallAndFoundWhenVisible) {
  SensorSpec cam = camera(SensorSpec::Type::thermal_camera, 160, 120, 57);
  cam.X_LS = Pose3::from_rpy(Vec3(0.2, 0, 0.6), 0, 0.5, 0);  // looking down at the floor ahead
  cam.camera.blur_sigma = 1.5;
  WorldSpec spec = empty_spec();
  VictimSpec v;
  v.name = "anna";
  v.pose = {1.5, 0, M_PI / 2};
  v.length = 1.2;
  v.width = 0.4;
  spec.victims.push_back(v);
  Scene s = wall_scene(cam, spec);
  NEED_GL(s);
  const CameraView view = camera_view(s.world, s.state, RobotIndex(0), cam);
  Rng rng(1, "t");
  const msg::Image m = thermal_mono16(s.renderer->thermal(view, cam.camera.blur_sigma), cam, {}, rng);
  // the victim's torso projects into the image; after the blur it is still well above the wall
  const Vec2 uv =
      project(view.k, (view.X_WC * X_BO()).inverse() * s.world.statics[static_cast<std::size_t>(s.world.victims[0].parts[1])].X_WO.p);
  std::uint16_t body, wall;
  std::memcpy(&body, &m.data[(static_cast<std::size_t>(std::lround(uv.y())) * 160 + static_cast<std::size_t>(std::lround(uv.x()))) * 2], 2);
  std::memcpy(&wall, &m.data[(5 * 160 + 80) * 2], 2);
  // clothes at 301.15 K against a wall at ambient 293.15 K: 8 K, most of it left after sigma 1.5 px
  EXPECT_GT(kelvin_of_count(body) - kelvin_of_count(wall), 0.8 * 8.0);
  EXPECT_NEAR(kelvin_of_count(wall), 293.15, 0.3);
  EXPECT_EQ(victims_in_thermal_image(s.world, view, cam, m, 4.0), std::vector<int>{0});
}

TEST(CameraThermal, VictimBehindAWallIsNotFound) {
  SensorSpec cam = camera(SensorSpec::Type::thermal_camera, 160, 120, 57);
  WorldSpec spec = empty_spec();
  VictimSpec v;
  v.pose = {3.5, 0, M_PI / 2};  // beyond the wall at x = 2.2
  spec.victims.push_back(v);
  Scene s = wall_scene(cam, spec);
  NEED_GL(s);
  const CameraView view = camera_view(s.world, s.state, RobotIndex(0), cam);
  Rng rng(1, "t");
  const msg::Image m = thermal_mono16(s.renderer->thermal(view, 1.5), cam, {}, rng);
  EXPECT_TRUE(victims_in_thermal_image(s.world, view, cam, m, 4.0).empty());
}

TEST(CameraInfo, KAndPFollowTheIntrinsics) {
  const SensorSpec cam = camera(SensorSpec::Type::color_camera, 640, 480, 90);
  const msg::CameraInfo ci = camera_info(cam, {SimTime{5}, "cam_optical"});
  // hfov 90 degrees over 640 px: fx = 320 / tan(45) = 320; square pixels; centre at (320, 240)
  EXPECT_NEAR(ci.k[0], 320.0, 1e-9);
  EXPECT_NEAR(ci.k[4], 320.0, 1e-9);
  EXPECT_NEAR(ci.k[2], 320.0, 1e-9);
  EXPECT_NEAR(ci.k[5], 240.0, 1e-9);
  EXPECT_EQ(ci.p[0], ci.k[0]);
  EXPECT_EQ(ci.p[10], 1.0);
  // a point 1 m right of the axis at 2 m: u = 320 * 1/2 + 320 = 480
  const Intrinsics k = camera_intrinsics(cam.camera);
  EXPECT_NEAR(project(k, Vec3(1, 0, 2)).x(), 480.0, 1e-9);
  EXPECT_EQ(ci.d.size(), 5u);
}

TEST(CameraColor, DistortionKeepsTheCentreAndNoiseIsRepeatable) {
  SensorSpec cam = camera(SensorSpec::Type::color_camera, 160, 120, 60);
  Scene s = wall_scene(cam);
  NEED_GL(s);
  const ColorImage img = s.renderer->color(camera_view(s.world, s.state, RobotIndex(0), cam));
  Rng a(1, "t");
  cam.camera.distortion = {-0.2, 0.05, 0, 0, 0};
  const msg::Image d = color_message(img, cam, {}, a);
  // the principal point does not move under radial distortion
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(d.data[(60 * 160 + 80) * 3 + c], img.rgb[(60 * 160 + 80) * 3 + c], 2);
  // pixel noise: different from the clean image, identical for the same stream
  cam.camera.noise.stddev = 0.02;
  Rng r1(7, "noise"), r2(7, "noise");
  const msg::Image n1 = color_message(img, cam, {}, r1), n2 = color_message(img, cam, {}, r2);
  EXPECT_NE(n1.data, d.data);
  EXPECT_EQ(n1.data, n2.data);
}

}  // namespace
}  // namespace rescuesim

namespace rescuesim {
namespace {

/// A w × h colour image of one sRGB grey level.
ColorImage uniform_image(int w, int h, std::uint8_t grey) {
  ColorImage img;
  img.width = w;
  img.height = h;
  img.rgb.assign(static_cast<std::size_t>(w * h * 3), grey);
  return img;
}

TEST(ColorCamera, AutoExposureBringsTheMeanToMidGreyWithinItsGainAndNoiseGrowsWithTheGain) {
  SensorSpec cam;
  cam.type = SensorSpec::Type::color_camera;
  cam.camera.auto_exposure = true;
  cam.camera.max_gain = 16;
  Rng rng(1, "ae");
  const auto linear_of = [](std::uint8_t v) { return srgb_to_linear(v / 255.0); };
  // a dim scene, linear 0.045 (sRGB 60): gain 0.18 / 0.045 = 4, brought to linear 0.18 (sRGB 118)
  const std::uint8_t dim = 60;
  const double gain = 0.18 / linear_of(dim);
  ASSERT_LT(gain, 16);
  const msg::Image m = color_message(uniform_image(40, 30, dim), cam, {}, rng);
  for (std::uint8_t v : m.data) ASSERT_NEAR(linear_of(v), 0.18, 0.003);
  // a dark one, linear 0.0012 (sRGB 5): the gain stops at 16, linear 0.019 (sRGB 37)
  const std::uint8_t dark = 5;
  const msg::Image d = color_message(uniform_image(40, 30, dark), cam, {}, rng);
  const auto expected = static_cast<std::uint8_t>(std::lround(255 * linear_to_srgb(16 * linear_of(dark))));
  for (std::uint8_t v : d.data) ASSERT_EQ(v, expected);
  // read noise of 0.5 % at unit gain: 16 times that at gain 16, in 8-bit counts (0.005 × 16 × 255 = 20)
  cam.camera.noise.stddev = 0.005;
  const msg::Image n = color_message(uniform_image(100, 100, dark), cam, {}, rng);
  double sum = 0, sum2 = 0;
  for (std::uint8_t v : n.data) {
    sum += v;
    sum2 += static_cast<double>(v) * v;
  }
  const double count = static_cast<double>(n.data.size()), mean = sum / count;
  EXPECT_NEAR(std::sqrt(sum2 / count - mean * mean), 0.005 * 16 * 255, 1.0);
  // in a bright scene the gain drops below one, and the noise stays the sensor's own
  const msg::Image b = color_message(uniform_image(100, 100, 230), cam, {}, rng);
  sum = sum2 = 0;
  for (std::uint8_t v : b.data) {
    sum += v;
    sum2 += static_cast<double>(v) * v;
  }
  EXPECT_NEAR(sum / count, 255 * linear_to_srgb(0.18), 1.0);
  EXPECT_NEAR(std::sqrt(sum2 / count - (sum / count) * (sum / count)), 0.005 * 255, 0.2);
}

}  // namespace
}  // namespace rescuesim
