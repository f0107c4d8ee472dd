// Smoke and dust in the camera images against the optics: a surface seen through a medium of
// optical depth τ keeps e^−τ of its contrast (colour in visible light, thermal in the long-wave
// band where smoke is nearly clear), an optically thick medium shows only its own airlight, and
// the depth camera loses its return where e^−2τ falls below 5 %. Optical depths come from
// world/media.h, the lidar's exact ray clipping.

#include <gtest/gtest.h>

#include <cmath>

#include "render/fog_volumes.h"
#include "render_support.h"
#include "core/rng.h"
#include "world/media.h"

namespace rescuesim {
namespace {

using render_test::at;
using render_test::camera;

/// A smoke (or dust) slab from x = 2 to 4 m, 4 m wide and 3 m high.
MediumSpec slab(double density, MediumSpec::Kind kind = MediumSpec::Kind::smoke) {
  MediumSpec m;
  m.kind = kind;
  m.name = "slab";
  m.outline = {{2, -2}, {4, -2}, {4, 2}, {2, 2}};
  m.density = density;
  m.height = 3.0;
  return m;
}

/// A 293 K world with a wall of albedo `grey` (sRGB) across x = 6, a 310 K block (a stand-in
/// for a victim) 1 m wide in front of it at x = 5, and `media`.
World smoky_world(double grey, std::vector<MediumSpec> media) {
  WorldSpec s = render_test::floor_spec();
  MaterialSpec wall;
  wall.name = "screen";
  wall.color = {grey, grey, grey};
  wall.texture = "none";
  s.set_material(wall);
  MaterialSpec warm;
  warm.name = "warm";
  warm.temperature = 310.0;
  warm.emissivity = 1.0;
  s.set_material(warm);
  s.walls.push_back(WallSpec{{6.05, -8}, {6.05, 8}, 0.1, 3.0, "screen", {}});
  s.blocks.push_back(BlockSpec{{{5.0, -0.5}, {5.4, -0.5}, {5.4, 0.5}, {5.0, 0.5}}, 1.6, "warm", {}});
  s.media = std::move(media);
  return compile_world(s, {});
}

/// Linear light of an sRGB byte.
double linear(std::uint8_t c) { return srgb_to_linear(c / 255.0); }

/// The visible optical depth of the ray from the camera through pixel (i, j) to `depth` along the axis.
double tau_of_pixel(const CameraView& v, const std::vector<MediumSpec>& media, int i, int j, double depth, SensingBand band) {
  const Pose3 X_WO = v.X_WC * X_BO();
  const Vec3 p = X_WO * unproject(v.k, i, j, depth);
  std::vector<MediumVolume> volumes;
  media_at(media, 0.0, band, volumes);
  std::vector<MediumSegment> segments;
  const Vec3 d = p - v.X_WC.p;
  return optical_depth(volumes, v.X_WC.p, d.normalized(), d.norm(), segments);
}

const CameraView kView = camera({0, 0, 1.0}, 0, 0, 96, 72, 1.0);

TEST(Fog, FogPiecesMatchTheLidarsExactOpticalDepth) {
  // a concave L-shaped dust cloud that grows and drifts, and a smoke slab
  MediumSpec l;
  l.kind = MediumSpec::Kind::dust;
  l.outline = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
  l.density = 0.7;
  l.bottom = 0.2;
  l.height = 1.5;
  l.growth = 0.02;
  l.drift = {0.1, -0.05};
  const std::vector<MediumSpec> media = {l, slab(0.4)};
  const double t = 3.0;
  const std::vector<FogPiece> pieces = fog_pieces(media, t);
  ASSERT_EQ(pieces.size(), 5u);  // the L's four triangles and the slab
  Rng rng(7, "fog");
  for (SensingBand band : {SensingBand::visible, SensingBand::near_infrared, SensingBand::long_wave_infrared}) {
    std::vector<MediumVolume> volumes;
    media_at(media, t, band, volumes);
    std::vector<MediumSegment> segments;
    for (int i = 0; i < 500; ++i) {
      const Vec3 a(rng.uniform(-1, 5), rng.uniform(-2, 4), rng.uniform(0, 2));
      const Vec3 b(rng.uniform(-1, 5), rng.uniform(-2, 4), rng.uniform(0, 2));
      const double expected = optical_depth(volumes, a, (b - a).normalized(), (b - a).norm(), segments);
      const Vec3 tau = fog_optical_depth(pieces, a, b);
      const double got = band == SensingBand::visible ? tau.x() : band == SensingBand::near_infrared ? tau.y() : tau.z();
      ASSERT_NEAR(got, expected, 1e-9 + 1e-9 * expected) << "segment " << i;
    }
  }
}

TEST(Fog, ColourContrastFallsAsExpOfTheOpticalDepth) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  // the same smoke in front of a light and a dark wall: each pixel is C·T + A·(1 − T) with the
  // same transmittance T and airlight A, so the difference of the two images is T times the
  // difference without smoke, pixel by pixel
  // once as an axis-aligned box (the shaders' fast path), once turned by 0.4 rad about its
  // centre (the same path in the box's own frame), once as a trapezoid (the general convex path)
  MediumSpec turned = slab(0.5);
  for (Vec2& p : turned.outline) p = Vec2(3, 0) + Eigen::Rotation2Dd(0.4) * (p - Vec2(3, 0));
  MediumSpec trapezoid = slab(0.5);
  trapezoid.outline[2].x() = 4.6;  // the far side's left corner pushed out: not a rectangle
  // and with a box behind the camera beside the trapezoid: both paths in one program
  MediumSpec behind = slab(2.0);
  for (Vec2& p : behind.outline) p.x() -= 7;
  for (const MediumSpec& medium : {slab(0.5), turned, trapezoid}) {
    std::vector<MediumSpec> media = {medium};
    if (medium.outline[2].x() > 4.5) media.push_back(behind);
    const auto image = [&](double grey, const std::vector<MediumSpec>& m) {
      renderer->load(build_render_scene(smoky_world(grey, m)));
      return renderer->color(kView);
    };
    const ColorImage light_clear = image(0.9, {}), dark_clear = image(0.3, {});
    const ColorImage light = image(0.9, media), dark = image(0.3, media);
    render_test::dump("fog_wall_clear", light_clear);
    render_test::dump(media.size() > 1              ? "fog_wall_smoke_trapezoid"
                      : medium.outline[0].y() == -2 ? "fog_wall_smoke"
                                                    : "fog_wall_smoke_turned",
                      light);
    int checked = 0;
    for (int j = 28; j < 44; j += 3) {
      for (int i = 4; i < 92; i += 5) {
        if (i > 38 && i < 58) continue;  // the block
        const std::size_t k = 3 * at(kView.k.width, i, j);
        const double clear = linear(light_clear.rgb[k]) - linear(dark_clear.rgb[k]);
        const double smoke = linear(light.rgb[k]) - linear(dark.rgb[k]);
        ASSERT_GT(clear, 0.1);
        // the wall's plane x = 6 at this pixel: depth along the axis 6 m
        const double expected = std::exp(-tau_of_pixel(kView, media, i, j, 6.0, SensingBand::visible));
        EXPECT_NEAR(smoke / clear, expected, 0.02 + 0.05 * expected) << "pixel " << i << ", " << j;
        ++checked;
      }
    }
    EXPECT_GT(checked, 60);
  }
}

TEST(Fog, ThickSmokeShowsOnlyItsAirlightAndDustIsBrighter) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  for (Quality q : {Quality::low, Quality::medium, Quality::high}) {
    SCOPED_TRACE(quality_name(q));
    renderer->set_quality(q);
    // visible optical depth 16 in front of the wall: T = 1e-7. Wall and sky read alike: the light
    // the smoke scatters towards the camera. Dust scatters 0.9 of what it stops, smoke 0.3.
    MediumSpec tall = slab(8.0);
    tall.height = 40.0;
    const CameraView up = camera({0, 0, 1.0}, 0, -0.25, 96, 72, 1.0);  // the top rows see the sky
    renderer->load(build_render_scene(smoky_world(0.9, {tall})));
    const ColorImage smoke = renderer->color(up);
    render_test::dump(std::string("fog_thick_smoke_") + quality_name(q), smoke);
    const double wall = linear(smoke.rgb[3 * at(96, 10, 60)]), sky = linear(smoke.rgb[3 * at(96, 10, 2)]);
    EXPECT_NEAR(wall, sky, 0.01);
    tall.kind = MediumSpec::Kind::dust;
    tall.density = 8.0;  // the same visible depth
    renderer->load(build_render_scene(smoky_world(0.3, {tall})));
    const ColorImage dust = renderer->color(up);
    render_test::dump(std::string("fog_thick_dust_") + quality_name(q), dust);
    const double dust_wall = linear(dust.rgb[3 * at(96, 10, 60)]);
    EXPECT_NEAR(dust_wall / wall, 3.0, 0.15);
    EXPECT_NEAR(linear(dust.rgb[3 * at(96, 10, 2)]), dust_wall, 0.01);
  }
}

// The sky is fogged only where a medium stands in front of it (the pass is cut to the media's
// projection): a tall slab on the left half of the view veils the sky there and leaves the sky on
// the right exactly as in clear air; a slab behind the camera changes no pixel.
TEST(Fog, TheSkyIsFoggedWhereAMediumIsInFrontOfItAndNowhereElse) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  const CameraView up = camera({0, 0, 1.0}, 0, -0.25, 96, 72, 1.0);  // the top rows see the sky
  renderer->load(build_render_scene(smoky_world(0.9, {})));
  const ColorImage clear = renderer->color(up);
  MediumSpec left = slab(1.0);
  left.outline = {{2, 0.5}, {4, 0.5}, {4, 6}, {2, 6}};  // y > 0.5 m: left of the view's centre line
  left.height = 40.0;
  renderer->load(build_render_scene(smoky_world(0.9, {left})));
  const ColorImage veiled = renderer->color(up);
  render_test::dump("fog_sky_left", veiled);
  // the sky's top row: left columns through 2 m of smoke at 1 /m differ; right columns are untouched
  int changed_left = 0, changed_right = 0;
  // (a sky ray crosses the slab where it is 0.5 m left of the centre line 4 m out: columns left
  // of 48 - 87.9 px x 0.125 = 37)
  for (int i = 0; i < 96; ++i) {
    const bool differs = veiled.rgb[3 * at(96, i, 1)] != clear.rgb[3 * at(96, i, 1)];
    if (i < 34) changed_left += differs;
    if (i >= 48) changed_right += differs;
  }
  EXPECT_EQ(changed_left, 34);
  EXPECT_EQ(changed_right, 0);
  // behind the camera: no medium in view, so every camera takes its clear program and its image
  // is the clear world's to the bit (and costs what it costs there)
  MediumSpec behind = slab(1.0);
  behind.outline = {{-4, -2}, {-2, -2}, {-2, 2}, {-4, 2}};
  renderer->load(build_render_scene(smoky_world(0.9, {})));
  const DepthImage clear_depth = renderer->depth(up);
  const ThermalImage clear_thermal = renderer->thermal(up, 0.0);
  renderer->load(build_render_scene(smoky_world(0.9, {behind})));
  const ColorImage same = renderer->color(up);
  ASSERT_EQ(same.rgb.size(), clear.rgb.size());
  int off = 0;
  for (std::size_t k = 0; k < same.rgb.size(); ++k) off += same.rgb[k] != clear.rgb[k];
  EXPECT_EQ(off, 0);
  const DepthImage same_depth = renderer->depth(up);
  ASSERT_EQ(same_depth.z.size(), clear_depth.z.size());
  for (std::size_t k = 0; k < same_depth.z.size(); ++k) {
    ASSERT_TRUE(same_depth.z[k] == clear_depth.z[k] || (std::isinf(same_depth.z[k]) && std::isinf(clear_depth.z[k]))) << k;
  }
  EXPECT_EQ(renderer->thermal(up, 0.0).kelvin, clear_thermal.kelvin);
}

TEST(Fog, ThermalSeesTheVictimThroughSmokeThatHidesItFromColour) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  // visible optical depth 1.5 × 2 = 3: the colour contrast falls to e^−3 = 5 %; long-wave 0.05
  // of it, 0.15: the thermal contrast keeps e^−0.15 = 86 %
  const std::vector<MediumSpec> media = {slab(1.5)};
  const auto contrast = [&](const std::vector<MediumSpec>& m) {
    renderer->load(build_render_scene(smoky_world(0.9, m)));
    const ColorImage c = renderer->color(kView);
    const ThermalImage t = renderer->thermal(kView, 0.0);
    const int block = 48, wall = 20, row = 36;
    return std::tuple{std::abs(render_test::grey(c, block, row) - render_test::grey(c, wall, row)),
                      t.kelvin[at(96, block, row)] - t.kelvin[at(96, wall, row)], t.kelvin[at(96, block, row)], c, t};
  };
  const auto [colour_clear, thermal_clear, block_clear, c0, t0] = contrast({});
  const auto [colour_smoke, thermal_smoke, block_smoke, c1, t1] = contrast(media);
  render_test::dump("fog_victim_colour_clear", c0);
  render_test::dump("fog_victim_colour_smoke", c1);
  render_test::dump("fog_victim_thermal_smoke", t1, 290, 312);
  EXPECT_NEAR(thermal_clear, 17.0, 0.1);
  const double tau_lw = tau_of_pixel(kView, media, 48, 36, 5.0, SensingBand::long_wave_infrared);
  EXPECT_NEAR(tau_lw, 0.15, 0.01);
  EXPECT_NEAR(block_smoke, 293.0 + 17.0 * std::exp(-tau_lw), 0.05);
  EXPECT_GT(thermal_smoke / thermal_clear, 0.8);
  // a lamp switched on recompiles the colour programs: the smoke stays in every camera
  RenderScene scene = build_render_scene(smoky_world(0.9, media));
  RenderLamp lamp;
  lamp.robot = RobotIndex(0);
  lamp.link = 0;
  lamp.light.directional = false;
  lamp.light.spot = true;
  lamp.light.cone = 0.4;
  lamp.light.inner_cone = 0.3;
  lamp.light.color = {4, 4, 4};
  scene.lamps.push_back(lamp);
  renderer->load(scene);
  const double colour_before = render_test::grey(renderer->color(kView), 20, 36);
  State s;
  s.robots.resize(1);
  s.robots[0].X_WL = {Pose3::from_rpy({0.5, 0, 1}, 0, 0, 0)};
  s.robots[0].lights_on = true;
  update_render_scene(scene, s);
  ASSERT_EQ(scene.lights.size(), scene.world_lights + 1);
  renderer->update(scene);
  EXPECT_NEAR(renderer->thermal(kView, 0.0).kelvin[at(96, 48, 36)], block_smoke, 1e-3);
  // the lamp lights the wall through the smoke a little, and the smoke still hides it mostly
  const double colour_lit = render_test::grey(renderer->color(kView), 20, 36);
  EXPECT_GE(colour_lit, colour_before);
  EXPECT_LT(std::abs(colour_lit - colour_before), 0.5 * colour_clear);
  EXPECT_GT(colour_clear, 40.0);                  // grey levels
  EXPECT_LT(colour_smoke / colour_clear, 0.15);   // e^-3 in linear light; a little more in sRGB
}

TEST(Fog, DepthCameraLosesItsReturnBelowFivePercent) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  // pixel (20, 36) looks 27.5 px off the axis at f = 48 / tan 0.7 = 57.03 px, so its ray crosses
  // the 2 m slab over 2 · hypot(1, 27.5 / 57.03) = 2.2205 m; two-way e^−2·σ·2.2205: σ = 0.5 keeps
  // 10.9 % (valid), σ = 1 keeps 1.2 % (lost); the 5 % edge is at σ = ln(20) / 4.441 = 0.6746:
  // σ = 0.62 keeps 6.4 % (valid), σ = 0.72 keeps 4.1 % (lost)
  const CameraView v = camera({0, 0, 1.0}, 0, 0, 96, 72, 1.4);
  for (double sigma : {0.0, 0.5, 0.62, 0.72, 1.0}) {
    renderer->load(build_render_scene(smoky_world(0.9, {slab(sigma)})));
    const DepthImage d = renderer->depth(v);
    render_test::dump("fog_depth_" + std::to_string(sigma), d, 8);
    const float centre = d.z[at(96, 20, 36)];  // the wall, through the slab
    if (sigma < 0.6746) {
      EXPECT_NEAR(centre, 6.0, 0.01) << sigma;
    } else {
      EXPECT_TRUE(std::isnan(centre)) << centre;
    }
    // past the slab's side (|y| > 2 at x = 6: the image's edge, 1.4 rad wide) the wall stays valid
    EXPECT_NEAR(d.z[at(96, 1, 36)], 6.0, 0.01);
    // the floor in front of the slab, seen below: valid
    EXPECT_TRUE(std::isfinite(d.z[at(96, 20, 71)]));
  }
}

}  // namespace
}  // namespace rescuesim
