// Darkness and lamps against the lighting model: with no ambient light and no sun nothing is
// visible but what a lamp lights; a spot lamp lights a wall in front of it to albedo × I / d² ×
// its range window inside its core, nothing outside its cone's edge; lamps follow their links
// and leave the scene when switched off.

#include <gtest/gtest.h>

#include <cmath>

#include "render_support.h"

namespace rescuesim {
namespace {

using render_test::at;
using render_test::camera;

/// A dark world (ambient 0, no sun) with a matte wall across x = 4 of albedo 0.9 (sRGB).
World dark_world(double ambient_light) {
  WorldSpec s = render_test::floor_spec();
  s.ambient_light = ambient_light;
  s.sun = false;
  MaterialSpec wall;
  wall.name = "screen";
  wall.color = {0.9, 0.9, 0.9};
  wall.texture = "none";
  wall.roughness = 1.0;
  s.set_material(wall);
  s.walls.push_back(WallSpec{{4.05, -8}, {4.05, 8}, 0.1, 3.0, "screen", {}});
  return compile_world(s, {});
}

/// A lamp at the camera, 1 m up, shining east: intensity 16 (1 at the wall, 4 m away), a core of
/// 0.2 rad and an edge at 0.3 rad, fading out at 12 m.
RenderLight lamp() {
  RenderLight l;
  l.directional = false;
  l.spot = true;
  l.position = {0, 0, 1};
  l.direction = {1, 0, 0};
  l.color = {16, 16, 16};
  l.cone = 0.3;
  l.inner_cone = 0.2;
  l.range = 12;
  l.casts_shadows = false;
  return l;
}

double linear(const ColorImage& img, int x, int y) { return srgb_to_linear(img.rgb[3 * at(img.width, x, y)] / 255.0); }

/// The column of the centre row that looks `angle` rad to the left of the axis.
int column_at(const CameraView& v, double angle) { return static_cast<int>(std::lround(v.k.cx - v.k.fx * std::tan(angle))); }

TEST(Darkness, NoAmbientLightAndNoSunIsBlack) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  renderer->load(build_render_scene(dark_world(0.0)));
  for (Quality q : {Quality::low, Quality::medium, Quality::high}) {
    renderer->set_quality(q);
    const ColorImage img = renderer->color(camera({0, 0, 1}, 0, 0, 64, 48, 1.2));
    for (std::uint8_t v : img.rgb) ASSERT_EQ(v, 0) << quality_name(q);
  }
  // a tenth of the daylight: dim, not black
  renderer->load(build_render_scene(dark_world(0.1)));
  renderer->set_quality(Quality::low);
  const ColorImage dim = renderer->color(camera({0, 0, 1}, 0, 0, 64, 48, 1.2));
  EXPECT_GT(render_test::grey(dim, 32, 20), 10.0);
}

TEST(Darkness, ALampLightsItsConeAndNothingOutside) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  RenderScene scene = build_render_scene(dark_world(0.0));
  scene.lights.push_back(lamp());
  const CameraView view = camera({0, 0, 1}, 0, 0, 160, 120, 1.2);
  // radiance at the wall straight ahead: 16 / 4² = 1 times the window (1 − (4/12)⁴)² = 0.9755;
  // the wall's linear albedo srgb_to_linear(0.9) = 0.787, facing the lamp (cos 1); its highlight
  // (4 % reflectance, roughness 1) adds under 2 %
  const double albedo = srgb_to_linear(0.9);
  const double window = std::pow(1 - std::pow(4.0 / 12.0, 4), 2);
  for (Quality q : {Quality::low, Quality::medium, Quality::high}) {
    SCOPED_TRACE(quality_name(q));
    renderer->set_quality(q);
    renderer->load(scene);
    const ColorImage img = renderer->color(view);
    render_test::dump(std::string("lamp_cone_") + quality_name(q), img);
    const int row = 60;
    EXPECT_NEAR(linear(img, 80, row), albedo * window, 0.03);
    // 0.15 rad off the axis: inside the core; a point of the wall farther (4 / cos) and tilted
    // (cos): 1/d² · cos = cos³ / 16 · 16
    const double a = 0.15, c = std::cos(a);
    const double d2 = 16 / (c * c), x = d2 / 144;
    EXPECT_NEAR(linear(img, column_at(view, a), row), albedo * c * c * c * (1 - x * x) * (1 - x * x), 0.03);
    // outside the edge (0.3 rad) on both sides, and above and below: black
    for (double off : {0.33, 0.45, -0.33, -0.45}) {
      EXPECT_EQ(render_test::grey(img, column_at(view, off), row), 0.0) << off;
    }
    EXPECT_EQ(render_test::grey(img, 80, 5), 0.0);
    EXPECT_EQ(render_test::grey(img, 80, 115), 0.0);
    // between core and edge the light fades: dimmer than the core, brighter than nothing
    const double edge = linear(img, column_at(view, 0.25), row);
    EXPECT_GT(edge, 0.02);
    EXPECT_LT(edge, 0.8 * albedo * std::pow(std::cos(0.25), 3));
  }
}

TEST(Darkness, LampsFollowTheirLinkAndLeaveWhenOff) {
  RenderScene scene;
  RenderLamp l;
  l.robot = RobotIndex(0);
  l.link = 1;
  l.X_LF = Pose3::from_rpy({0.1, 0, 0}, 0, 0, 0);
  l.light = lamp();
  scene.lamps.push_back(l);
  State s;
  s.robots.resize(1);
  // link 1 at (2, 3, 0.5) turned 90° to the left: the lamp 0.1 m ahead of it shines north
  s.robots[0].X_WL = {Pose3::from_rpy({0, 0, 0}, 0, 0, 0), Pose3::from_rpy({2, 3, 0.5}, 0, 0, M_PI / 2)};
  update_render_scene(scene, s);
  EXPECT_TRUE(scene.lights.empty());  // lights off
  s.robots[0].lights_on = true;
  update_render_scene(scene, s);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_TRUE(scene.lights[0].position.isApprox(Vec3(2, 3.1, 0.5), 1e-12));
  EXPECT_TRUE(scene.lights[0].direction.isApprox(Vec3(0, 1, 0), 1e-12));
  EXPECT_TRUE(scene.lights[0].spot);
  s.robots[0].lights_on = false;
  update_render_scene(scene, s);
  EXPECT_TRUE(scene.lights.empty());
}

}  // namespace
}  // namespace rescuesim
