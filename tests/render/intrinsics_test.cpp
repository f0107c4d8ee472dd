// A rendered point lands where project() says: the centroid of a small sphere's pixels matches
// the projection of its centre, on and off the optical axis, at two image sizes.

#include <gtest/gtest.h>

#include "render_support.h"

namespace rescuesim {
namespace {

using render_test::at;
using render_test::camera;

/// A scene with one 16 cm sphere at p_W and nothing else.
RenderScene sphere_scene(const Vec3& p_W) {
  RenderScene s;
  s.meshes.push_back(render_mesh_of(Geometry::sphere(0.08)));
  s.materials.push_back(RenderMaterial{});
  RenderItem item;
  item.X_WI = Pose3{p_W, Quat::Identity()};
  s.items.push_back(item);
  return s;
}

TEST(Intrinsics, SphereCentroidMatchesProjection) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  const CameraView base = camera({0.3, -0.2, 1.1}, 0.4, 0.1, 320, 240, 1.1);
  const Pose3 X_WO = base.X_WC * X_BO();
  for (const Vec3& p_O : {Vec3(0, 0, 2.0), Vec3(0.5, -0.3, 2.5), Vec3(-0.7, 0.45, 1.8)}) {
    for (int width : {320, 97}) {
      CameraView view = base;
      view.k = Intrinsics::from_hfov(width, width * 3 / 4, 1.1);
      renderer->load(sphere_scene(X_WO * p_O));
      const DepthImage img = renderer->depth(view);
      double su = 0, sv = 0, n = 0;
      for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
          if (std::isfinite(img.z[at(img.width, x, y)])) {
            su += x;
            sv += y;
            n += 1;
          }
        }
      }
      ASSERT_GT(n, 3) << "sphere not seen at " << p_O.transpose();
      const Vec2 expected = project(view.k, p_O);
      // pixel coverage quantises the disc: a quarter pixel is plenty for a disc of ≥ 2 px radius
      EXPECT_NEAR(su / n, expected.x(), 0.25) << width << " px, p_O " << p_O.transpose();
      EXPECT_NEAR(sv / n, expected.y(), 0.25) << width << " px, p_O " << p_O.transpose();
    }
  }
}

}  // namespace
}  // namespace rescuesim
