// Depth images against planes worked out by hand: a wall square to the optical axis 2 m away,
// a wall turned 30° about the vertical, and a view with nothing in it.

#include <gtest/gtest.h>

#include <cmath>

#include "render_support.h"

namespace rescuesim {
namespace {

using render_test::at;
using render_test::camera;

/// A 2.5 m high, 10 cm thick, 12 m long wall whose camera-side face is the plane n·p = d
/// through (2, 0) with unit normal n = (cos a, sin a) (camera at the origin).
WorldSpec wall_world(double a) {
  WorldSpec s = render_test::floor_spec();
  const Vec2 n(std::cos(a), std::sin(a)), t(-std::sin(a), std::cos(a));
  const Vec2 centre = Vec2(2, 0) + 0.05 * n;
  s.walls.push_back(WallSpec{centre - 6 * t, centre + 6 * t, 0.1, 2.5, "wall", {}});
  return s;
}

TEST(Depth, WallSquareToTheAxisReadsTwoMetres) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  renderer->load(build_render_scene(compile_world(wall_world(0), {})));
  const CameraView view = camera({0, 0, 1.0}, 0, 0, 320, 240, 1.2);
  const DepthImage img = renderer->depth(view);
  render_test::dump("depth_wall", img, 4.0);
  ASSERT_EQ(img.width, 320);
  ASSERT_EQ(img.height, 240);
  // the centre half of the image sees only the wall (rows 60..180 reach 0.5 m below and above the lens)
  double worst = 0;
  for (int y = img.height / 4; y < 3 * img.height / 4; ++y) {
    for (int x = img.width / 4; x < 3 * img.width / 4; ++x) worst = std::max(worst, std::abs(img.z[at(img.width, x, y)] - 2.0));
  }
  EXPECT_LT(worst, 0.002);
}

TEST(Depth, WallTurnedThirtyDegreesFollowsThePlanarField) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  const double a = M_PI / 6;
  renderer->load(build_render_scene(compile_world(wall_world(a), {})));
  const CameraView view = camera({0, 0, 1.0}, 0, 0, 320, 240, 1.2);
  const DepthImage img = renderer->depth(view);
  render_test::dump("depth_tilted", img, 4.0);
  // the ray of column u has optical x/z = (u − cx)/fx, i.e. world y = −(u − cx)/fx · z; on the
  // plane cos(a)·z + sin(a)·y = 2·cos(a):  z(u) = 2 / (1 − tan(a)·(u − cx)/fx)
  double worst = 0;
  for (int y = img.height / 4; y < 3 * img.height / 4; ++y) {
    for (int x = img.width / 4; x < 3 * img.width / 4; ++x) {
      const double expected = 2.0 / (1.0 - std::tan(a) * (x - view.k.cx) / view.k.fx);
      worst = std::max(worst, std::abs(img.z[at(img.width, x, y)] - expected));
    }
  }
  EXPECT_LT(worst, 0.003);
}

TEST(Depth, NothingInViewIsInfinite) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  renderer->load(build_render_scene(compile_world(wall_world(0), {})));
  // looking straight up: only sky
  const DepthImage up = renderer->depth(camera({0, 0, 1.0}, 0, -M_PI / 2, 64, 48, 1.2));
  for (float z : up.z) ASSERT_TRUE(std::isinf(z) && z > 0);
  // the wall lies beyond a 1.5 m far plane: nothing within far reads +inf as well
  const DepthImage short_range = renderer->depth(camera({0, 0, 1.0}, 0, 0, 64, 48, 0.5, 0.05, 1.5));
  for (float z : short_range.z) ASSERT_TRUE(std::isinf(z));
}

TEST(Depth, HiddenRobotAndMovedRubble) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  WorldSpec spec = wall_world(0);
  spec.rubble.push_back(RubbleSpec{RubbleSpec::Shape::box, {1.0, 0.0, 0.0}, {0.2, 0.2, 0.2}, 1.0, "rubble", {}});
  const World world = compile_world(spec, {});
  RenderScene scene = build_render_scene(world);
  renderer->load(scene);
  const CameraView view = camera({0, 0, 0.1}, 0, 0, 64, 48, 0.8);
  // the box's near face is 0.9 m away on the axis
  EXPECT_NEAR(renderer->depth(view).z[at(64, 32, 24)], 0.9, 0.002);
  // moved 0.5 m further away by a State
  State s;
  s.dynamics.push_back({Pose3{Vec3(1.5, 0, 0.1), Quat::Identity()}});
  update_render_scene(scene, s);
  renderer->update(scene);
  EXPECT_NEAR(renderer->depth(view).z[at(64, 32, 24)], 1.4, 0.002);
  // a State without the rubble does not fit this scene
  EXPECT_THROW(update_render_scene(scene, State{}), Error);
}

}  // namespace
}  // namespace rescuesim
