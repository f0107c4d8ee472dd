// Mesh textures: an OBJ panel (tests/render/data/textured_panel) whose .mtl names an 8 x 8 PNG
// of four coloured quadrants is drawn with that image at its texture coordinates — each quadrant
// where the file puts it (top-left red, top-right green, bottom-left blue, bottom-right yellow),
// so neither axis is mirrored — while the same mesh without its image is one grey.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "import/mesh/mesh.h"
#include "render_support.h"

namespace rescuesim {
namespace {

using render_test::camera;

const std::string kPanel = RESCUESIM_SOURCE_DIR "/tests/render/data/textured_panel/panel.obj";

/// The floor with the panel (x = 0, y in [-1, 1], z in [0, 2], facing -x) as a static solid.
World panel_world(bool with_image) {
  const LoadedMesh loaded = load_mesh(kPanel);
  WorldSpec spec = render_test::floor_spec();
  SolidSpec s;
  s.name = "panel";
  s.geometry = Geometry::triangles(loaded.mesh);
  if (with_image) s.geometry.image = loaded.image;
  spec.solids.push_back(std::move(s));
  return compile_world(spec, {});
}

/// Mean colour of a square of pixels around (x, y).
Vec3 mean_rgb(const ColorImage& img, int x, int y, int half = 6) {
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (int v = y - half; v <= y + half; ++v) {
    for (int u = x - half; u <= x + half; ++u) {
      const std::size_t i = 3 * render_test::at(img.width, u, v);
      sum += Vec3(img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]);
      ++n;
    }
  }
  return sum / n;
}

TEST(Texture, TheLoaderFindsTheImageAndEveryCornersCoordinates) {
  const LoadedMesh m = load_mesh(kPanel);
  EXPECT_EQ(m.texture, "quadrants.png");
  ASSERT_NE(m.image, nullptr);
  EXPECT_NE(m.image->file.find("textured_panel/quadrants.png"), std::string::npos) << m.image->file;
  // the quad is two triangles; every corner has the (u, v) of its vertex: u = (1 - y) / 2, v = z / 2
  ASSERT_EQ(m.mesh.triangles.size(), 2u);
  ASSERT_EQ(m.image->corner_uvs.size(), 2u);
  for (std::size_t t = 0; t < 2; ++t) {
    for (int c = 0; c < 3; ++c) {
      const Vec3& p = m.mesh.vertices[static_cast<std::size_t>(m.mesh.triangles[t][static_cast<std::size_t>(c)])];
      const Vec2& uv = m.image->corner_uvs[t][static_cast<std::size_t>(c)];
      EXPECT_NEAR(uv.x(), (1 - p.y()) / 2, 1e-6);
      EXPECT_NEAR(uv.y(), p.z() / 2, 1e-6);
    }
  }
}

TEST(Texture, EachQuadrantOfTheImageIsDrawnWhereTheFilePutsIt) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  // 3 m in front of the panel, at its middle height, looking at it (+x): 2 atan(1/2) across
  // is 3 m there, so the panel's 2 m span the middle 160 of 240 px, x = 40..200 and y = 40..200
  const CameraView view = camera({-3, 0, 1}, 0, 0, 240, 240, 2 * std::atan(0.5));
  renderer->load(build_render_scene(panel_world(true)));
  const ColorImage img = renderer->color(view);
  render_test::dump("texture_panel", img);
  // quadrant centres: 40 px in from each corner of the panel's square
  const Vec3 top_left = mean_rgb(img, 80, 80), top_right = mean_rgb(img, 160, 80);
  const Vec3 bottom_left = mean_rgb(img, 80, 160), bottom_right = mean_rgb(img, 160, 160);
  const auto dominant = [](const Vec3& c, int channel) {
    for (int k = 0; k < 3; ++k) {
      if (k != channel && c[channel] < c[k] + 40) return false;
    }
    return true;
  };
  EXPECT_TRUE(dominant(top_left, 0)) << "top-left should be red: " << top_left.transpose();
  EXPECT_TRUE(dominant(top_right, 1)) << "top-right should be green: " << top_right.transpose();
  EXPECT_TRUE(dominant(bottom_left, 2)) << "bottom-left should be blue: " << bottom_left.transpose();
  // yellow: red and green both well above blue
  EXPECT_GT(bottom_right.x(), bottom_right.z() + 40) << bottom_right.transpose();
  EXPECT_GT(bottom_right.y(), bottom_right.z() + 40) << bottom_right.transpose();

  // without its image the same panel is one colour: the four places differ by little
  renderer->load(build_render_scene(panel_world(false)));
  const ColorImage plain = renderer->color(view);
  const Vec3 a = mean_rgb(plain, 80, 80, 12), b = mean_rgb(plain, 160, 160, 12);
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 30) << a.transpose() << " vs " << b.transpose();
}

}  // namespace
}  // namespace rescuesim
