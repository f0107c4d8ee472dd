// Bad input at the Renderer's boundary is rejected with messages naming the call and the field.

#include <gtest/gtest.h>

#include "render_support.h"

namespace rescuesim {
namespace {

using render_test::camera;

/// Runs `f`, expecting an Error whose text contains every one of `parts`.
template <class F>
void expect_error(F&& f, std::initializer_list<const char*> parts) {
  try {
    f();
    ADD_FAILURE() << "no Error thrown";
  } catch (const Error& e) {
    for (const char* p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
}

TEST(Validation, UnknownQualityIsRejected) {
  expect_error([] { Renderer::create_headless(static_cast<Quality>(7)); }, {"Renderer::create_headless", "unknown quality 7"});
  expect_error([] { quality_name(static_cast<Quality>(-1)); }, {"unknown quality -1"});
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  expect_error([&] { renderer->set_quality(static_cast<Quality>(3)); }, {"Renderer::set_quality", "unknown quality 3"});
  EXPECT_EQ(renderer->quality(), Quality::low);
}

TEST(Validation, BadViewsAreRejected) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  // before any scene
  expect_error([&] { renderer->color(camera({0, 0, 1}, 0, 0, 32, 24, 1.0)); }, {"Renderer::color", "no scene loaded"});
  renderer->load(build_render_scene(compile_world(render_test::floor_spec(), {})));

  CameraView zero = camera({0, 0, 1}, 0, 0, 32, 24, 1.0);
  zero.k.width = 0;
  expect_error([&] { renderer->color(zero); }, {"Renderer::color", "view size 0x24 px is outside [1, 8192]"});
  CameraView huge = camera({0, 0, 1}, 0, 0, 32, 24, 1.0);
  huge.k.height = 9000;
  expect_error([&] { renderer->depth(huge); }, {"Renderer::depth", "view size"});

  CameraView wide = camera({0, 0, 1}, 0, 0, 32, 24, 1.0);
  wide.k.fx = -5;
  expect_error([&] { renderer->thermal(wide, 1.0); }, {"Renderer::thermal", "focal lengths"});

  CameraView clip = camera({0, 0, 1}, 0, 0, 32, 24, 1.0);
  clip.near_clip = 2.0;
  clip.far_clip = 1.0;
  expect_error([&] { renderer->depth(clip); }, {"0 < near < far"});
  clip.near_clip = 0.0;
  clip.far_clip = 10;
  expect_error([&] { renderer->depth(clip); }, {"0 < near < far"});
  clip.near_clip = 0.1;
  clip.far_clip = INFINITY;
  expect_error([&] { renderer->depth(clip); }, {"finite"});

  CameraView pose = camera({0, 0, 1}, 0, 0, 32, 24, 1.0);
  pose.X_WC.p.x() = NAN;
  expect_error([&] { renderer->color(pose); }, {"camera pose X_WC"});

  expect_error([&] { renderer->thermal(camera({0, 0, 1}, 0, 0, 32, 24, 1.0), -1.0); }, {"Renderer::thermal", "blur sigma -1 px"});
  expect_error([] { Intrinsics::from_hfov(64, 48, 3.5); }, {"Intrinsics::from_hfov", "outside (0, pi)"});
}

TEST(Validation, UpdateNeedsTheLoadedLayout) {
  RS_RENDERER_OR_SKIP(renderer, Quality::low);
  RenderScene scene = build_render_scene(compile_world(render_test::floor_spec(), {}));
  renderer->load(scene);
  scene.items.push_back(scene.items.front());
  expect_error([&] { renderer->update(scene); }, {"Renderer::update", "2 items but the loaded one has 1"});
  EXPECT_NE(renderer->device().find("via EGL"), std::string::npos) << renderer->device();
}

}  // namespace
}  // namespace rescuesim
