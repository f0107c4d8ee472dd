// Colour images of a small maze: not blank, textured where the floor and walls are, the same on
// every render, close to a committed reference rendering; shadows at medium quality.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "import/maze/maze.h"
#include "render_support.h"

namespace rescuesim {
namespace {

using render_test::camera;
using render_test::grey;
using render_test::mean_gradient;

/// A 3 × 3 maze of 1.5 m cells (seed 7) with two rubble pieces and no robot.
WorldSpec small_maze_spec() {
  MazeOptions o;
  o.cols = 3;
  o.rows = 3;
  o.seed = 7;
  o.rubble = 2;
  WorldSpec spec = maze_to_world(generate_maze(o));
  spec.robots.clear();
  return spec;
}

/// From the south-west cell, 0.6 m up, looking north-east and slightly down: the bottom quarter
/// of the image is floor, the upper middle a wall 1.5 m away.
CameraView maze_view() { return camera({0.4, 0.3, 0.6}, 0.6, 0.25, 320, 240, 1.3); }

const char* const kReference = RESCUESIM_SOURCE_DIR "/tests/render/data/maze_low_320x240.png";

TEST(Color, MazeImageIsNotBlank) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  renderer->load(build_render_scene(compile_world(small_maze_spec(), {})));
  const ColorImage img = renderer->color(maze_view());
  render_test::dump("color_maze_low", img);
  ASSERT_EQ(img.rgb.size(), 320u * 240u * 3u);
  double mean = 0, sq = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      mean += grey(img, x, y);
      sq += grey(img, x, y) * grey(img, x, y);
    }
  }
  const double n = img.width * img.height;
  mean /= n;
  EXPECT_GT(sq / n - mean * mean, 200.0);  // a standard deviation above 14 grey levels
}

TEST(Color, FloorAndWallsHaveTexture) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  WorldSpec spec = small_maze_spec();
  renderer->load(build_render_scene(compile_world(spec, {})));
  const ColorImage textured = renderer->color(maze_view());
  // the same scene with plain materials: what lighting and geometry alone give
  spec.materials = default_materials();
  for (auto& m : spec.materials) m.texture = "none";
  renderer->load(build_render_scene(compile_world(spec, {})));
  const ColorImage plain = renderer->color(maze_view());
  render_test::dump("color_maze_plain", plain);
  // floor (bottom quarter) and wall (upper middle): plain shading changes by well under a grey
  // level per pixel there, while 0.5 m tiles with grout, mottling and concrete pores change it by
  // more; vision code (corners, optical flow) needs that texture
  const double floor_textured = mean_gradient(textured, 0, 180, 320, 240), floor_plain = mean_gradient(plain, 0, 180, 320, 240);
  const double wall_textured = mean_gradient(textured, 120, 40, 185, 100), wall_plain = mean_gradient(plain, 120, 40, 185, 100);
  EXPECT_LT(floor_plain, 0.5);
  EXPECT_LT(wall_plain, 0.5);
  EXPECT_GT(floor_textured, 1.0);
  EXPECT_GT(wall_textured, 1.0);
  EXPECT_GT(floor_textured, 3 * floor_plain);
  EXPECT_GT(wall_textured, 3 * wall_plain);
}

TEST(Color, RendersAreDeterministicAndMatchTheReference) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  renderer->load(build_render_scene(compile_world(small_maze_spec(), {})));
  const ColorImage a = renderer->color(maze_view());
  const ColorImage b = renderer->color(maze_view());
  EXPECT_EQ(a.rgb, b.rgb);
  // regenerate with RESCUESIM_UPDATE_RENDER_REFERENCE=1 after a deliberate change of the looks
  if (std::getenv("RESCUESIM_UPDATE_RENDER_REFERENCE") != nullptr) render_test::to_canvas(a).write_png(kReference);
  std::ifstream in(kReference, std::ios::binary);
  ASSERT_TRUE(in) << kReference;
  std::stringstream bytes;
  bytes << in.rdbuf();
  const Canvas ref = decode_png(bytes.str());
  ASSERT_EQ(ref.width(), a.width);
  ASSERT_EQ(ref.height(), a.height);
  // another Mesa may round differently, and rasterise edges a little differently: allow a few
  // grey levels on average
  double diff = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) diff += std::abs(static_cast<int>(a.rgb[i]) - static_cast<int>(ref.pixels()[i]));
  EXPECT_LT(diff / static_cast<double>(a.rgb.size()), 3.0);
}

/// Mean grey of a 7 × 7 patch around the pixel where a world point lands.
double patch_at(const ColorImage& img, const CameraView& view, const Vec3& p_W) {
  const Vec2 uv = project(view.k, (view.X_WC * X_BO()).inverse() * p_W);
  double sum = 0;
  for (int dy = -3; dy <= 3; ++dy) {
    for (int dx = -3; dx <= 3; ++dx) sum += grey(img, static_cast<int>(uv.x()) + dx, static_cast<int>(uv.y()) + dy);
  }
  return sum / 49;
}

TEST(Color, MediumQualityCastsShadows) {
  WorldSpec spec = render_test::floor_spec();
  // a 1.5 m pillar; the default sun travels along (−0.35, 0.45, −1), so its shadow falls towards
  // −x, +y: the top's shadow lands 0.53 m west and 0.68 m north of the footprint
  spec.blocks.push_back(BlockSpec{{{0, 0}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}}, 1.5, "obstacle", {}});
  const RenderScene scene = build_render_scene(compile_world(spec, {}));
  const CameraView view = camera({0.2, 0.2, 5.0}, 0, M_PI / 2, 320, 240, 1.2);
  const Vec3 in_shadow(-0.25, 0.9, 0), in_sun(1.6, -0.8, 0);
  ColorImage images[2];
  for (Quality q : {Quality::low, Quality::medium}) {
    RS_RENDERER_OR_SKIP(renderer, q);
    renderer->load(scene);
    images[static_cast<int>(q)] = renderer->color(view);
    render_test::dump(std::string("color_shadow_") + quality_name(q), images[static_cast<int>(q)]);
  }
  const double shadow_ratio = patch_at(images[1], view, in_shadow) / patch_at(images[0], view, in_shadow);
  const double sun_ratio = patch_at(images[1], view, in_sun) / patch_at(images[0], view, in_sun);
  EXPECT_LT(shadow_ratio, 0.75);
  EXPECT_NEAR(sun_ratio, 1.0, 0.1);
}

}  // namespace
}  // namespace rescuesim
