// Thermal images against the radiometric model e·T + (1 − e)·T_ambient: a 310 K box in front of
// an ambient wall, before and after the Gaussian blur, a uniform surface, and emissivity < 1.

#include <gtest/gtest.h>

#include "render_support.h"

namespace rescuesim {
namespace {

using render_test::at;
using render_test::camera;

/// A 293 K world: a wall 3 m ahead (west face at x = 3) and a 1.4 m wide, 2 m high block of
/// `material` standing 2 m ahead, seen from 1 m up at the origin.
World hot_box_world(double temperature, double emissivity) {
  WorldSpec s = render_test::floor_spec();
  MaterialSpec hot;
  hot.name = "hot";
  hot.temperature = temperature;
  hot.emissivity = emissivity;
  s.set_material(hot);
  s.walls.push_back(WallSpec{{3.05, -8}, {3.05, 8}, 0.1, 3.0, "wall", {}});
  s.blocks.push_back(BlockSpec{{{2.0, -0.7}, {2.4, -0.7}, {2.4, 0.7}, {2.0, 0.7}}, 2.0, "hot", {}});
  return compile_world(s, {});
}

const CameraView kView = camera({0, 0, 1.0}, 0, 0, 160, 120, 1.2);

/// Minimum and maximum over a square of half-size r pixels around the image centre.
std::pair<float, float> centre_range(const ThermalImage& img, int r) {
  float lo = 1e9f, hi = -1e9f;
  for (int y = img.height / 2 - r; y < img.height / 2 + r; ++y) {
    for (int x = img.width / 2 - r; x < img.width / 2 + r; ++x) {
      lo = std::min(lo, img.kelvin[at(img.width, x, y)]);
      hi = std::max(hi, img.kelvin[at(img.width, x, y)]);
    }
  }
  return {lo, hi};
}

TEST(Thermal, WarmBoxInFrontOfAnAmbientWall) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  renderer->load(build_render_scene(hot_box_world(310.0, 1.0)));
  // fx = 80 / tan(0.6) ≈ 117 px: the box spans ±0.7 m at 2 m, ±41 px around the centre, and from
  // 1 m below to 1 m above the lens, ±58 px
  const ThermalImage sharp = renderer->thermal(kView, 0.0);
  render_test::dump("thermal_box_sharp", sharp, 290, 312);
  const auto [lo, hi] = centre_range(sharp, 25);
  EXPECT_NEAR(lo, 310.0, 0.1);
  EXPECT_NEAR(hi, 310.0, 0.1);
  // left and right of the box: the wall, an ambient 293 K surface (emissivity 0.92 changes nothing at ambient)
  EXPECT_NEAR(sharp.kelvin[at(160, 10, 60)], 293.0, 0.1);
  EXPECT_NEAR(sharp.kelvin[at(160, 150, 60)], 293.0, 0.1);

  // blurred with sigma 2 px: the centre of an 82 px box keeps (nearly) its temperature
  const ThermalImage blurred = renderer->thermal(kView, 2.0);
  render_test::dump("thermal_box_blur2", blurred, 290, 312);
  EXPECT_GT(blurred.kelvin[at(160, 80, 60)], 293.0 + (310.0 - 293.0) * 0.9);
  // and the edge is smeared: a pixel just outside the box now reads warmer than the wall
  int edge = 0;
  while (edge < 80 && sharp.kelvin[at(160, edge, 60)] < 300) ++edge;
  ASSERT_GT(edge, 5);
  EXPECT_GT(blurred.kelvin[at(160, edge - 1, 60)], 294.0);
  EXPECT_LT(blurred.kelvin[at(160, edge, 60)], 309.0);
}

TEST(Thermal, UniformSurfaceReadsItsTemperature) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  renderer->load(build_render_scene(hot_box_world(310.0, 1.0)));
  // close to the box: it fills the view
  const CameraView close = camera({1.5, 0, 0.7}, 0, 0, 64, 48, 0.8);
  for (double sigma : {0.0, 1.5, 4.0}) {
    for (float k : renderer->thermal(close, sigma).kelvin) ASSERT_NEAR(k, 310.0, 0.1) << "sigma " << sigma;
  }
  // nothing in view: the ambient temperature
  for (float k : renderer->thermal(camera({0, 0, 1}, 0, -M_PI / 2, 32, 24, 1.0), 1.0).kelvin) ASSERT_NEAR(k, 293.0, 1e-3);
}

TEST(Thermal, EmissivityBelowOnePullsTowardsAmbient) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  renderer->load(build_render_scene(hot_box_world(310.0, 0.5)));
  const auto [lo, hi] = centre_range(renderer->thermal(kView, 0.0), 20);
  // 0.5 · 310 + 0.5 · 293 = 301.5 K
  EXPECT_NEAR(lo, 301.5, 0.1);
  EXPECT_NEAR(hi, 301.5, 0.1);
}

TEST(Thermal, VictimSkinIsWarmerThanClothes) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  WorldSpec s = render_test::floor_spec();
  VictimSpec v;
  v.pose = {2.0, 0.0, M_PI / 2};
  s.victims.push_back(v);
  renderer->load(build_render_scene(compile_world(s, {})));
  // from above: every victim pixel lies between the clothes' and the skin's apparent temperatures
  const ThermalImage img = renderer->thermal(camera({2.0, 0.0, 2.5}, 0, M_PI / 2, 120, 90, 1.2), 0.0);
  render_test::dump("thermal_victim", img, 290, 310);
  const double skin = 0.98 * 307.15 + 0.02 * 293.0, clothes = 0.95 * 301.15 + 0.05 * 293.0;
  float hottest = 0;
  for (float k : img.kelvin) hottest = std::max(hottest, k);
  EXPECT_NEAR(hottest, skin, 0.05);
  int clothed = 0;
  for (float k : img.kelvin) clothed += std::abs(k - clothes) < 0.05 ? 1 : 0;
  EXPECT_GT(clothed, 100);
}

}  // namespace
}  // namespace rescuesim
