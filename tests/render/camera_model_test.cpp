// Pinhole maths against numbers worked out by hand: projection and its inverse, the body →
// optical rotation, both OpenGL projection matrices, and the Brown distortion round trip.

#include "render/camera_model.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace rescuesim {
namespace {

TEST(CameraModel, FromHfovGivesSquarePixelsAndTheCentreConvention) {
  // 90° across 640 px: fx = 320 / tan(45°) = 320
  const Intrinsics k = Intrinsics::from_hfov(640, 480, M_PI / 2);
  EXPECT_NEAR(k.fx, 320.0, 1e-9);
  EXPECT_NEAR(k.fy, 320.0, 1e-9);
  EXPECT_DOUBLE_EQ(k.cx, 320.0);
  EXPECT_DOUBLE_EQ(k.cy, 240.0);
  EXPECT_NEAR(k.hfov(), M_PI / 2, 1e-12);
}

TEST(CameraModel, KnownPointProjectsWhereKSays) {
  const Intrinsics k = Intrinsics::from_hfov(640, 480, M_PI / 2);
  // 1 m right, 0.5 m down, 4 m ahead: u = 320·1/4 + 320 = 400, v = 320·0.5/4 + 240 = 280
  const Vec2 uv = project(k, Vec3(1.0, 0.5, 4.0));
  EXPECT_NEAR(uv.x(), 400.0, 1e-9);
  EXPECT_NEAR(uv.y(), 280.0, 1e-9);
  const Vec3 back = unproject(k, uv.x(), uv.y(), 4.0);
  EXPECT_NEAR((back - Vec3(1.0, 0.5, 4.0)).norm(), 0.0, 1e-12);
  // the optical axis lands on the principal point
  const Vec2 c = project(k, Vec3(0, 0, 7));
  EXPECT_DOUBLE_EQ(c.x(), k.cx);
  EXPECT_DOUBLE_EQ(c.y(), k.cy);
}

TEST(CameraModel, BodyToOpticalRotation) {
  const Pose3 X = X_BO();
  // optical z (forward) is body x, optical x (right) is body −y, optical y (down) is body −z
  EXPECT_NEAR((X.q * Vec3::UnitZ() - Vec3::UnitX()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((X.q * Vec3::UnitX() + Vec3::UnitY()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((X.q * Vec3::UnitY() + Vec3::UnitZ()).norm(), 0.0, 1e-12);
  // a point 3 m ahead of the body, 1 m to its left and 0.5 m up: optical (−1, −0.5, 3)
  const Vec3 p_O = X.inverse() * Vec3(3, 1, 0.5);
  EXPECT_NEAR((p_O - Vec3(-1, -0.5, 3)).norm(), 0.0, 1e-12);
}

TEST(CameraModel, GlProjectionMatchesThePixelConvention) {
  const Intrinsics k = Intrinsics::from_hfov(320, 240, 1.2);
  const double n = 0.1, f = 50;
  const Vec3 p_O(0.3, -0.2, 2.5);
  const Vec2 uv = project(k, p_O);
  // classic GL: eye = (x, −y, −z), window x = u + 0.5, window y = h − v − 0.5
  const Eigen::Vector4d clip = gl_projection(k, n, f) * Eigen::Vector4d(p_O.x(), -p_O.y(), -p_O.z(), 1);
  const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
  EXPECT_NEAR((ndc.x() + 1) / 2 * k.width, uv.x() + 0.5, 1e-9);
  EXPECT_NEAR((ndc.y() + 1) / 2 * k.height, k.height - uv.y() - 0.5, 1e-9);
  // near plane at NDC −1, far plane at +1
  const Eigen::Vector4d at_near = gl_projection(k, n, f) * Eigen::Vector4d(0, 0, -n, 1);
  const Eigen::Vector4d at_far = gl_projection(k, n, f) * Eigen::Vector4d(0, 0, -f, 1);
  EXPECT_NEAR(at_near.z() / at_near.w(), -1.0, 1e-12);
  EXPECT_NEAR(at_far.z() / at_far.w(), 1.0, 1e-9);
}

TEST(CameraModel, ReversedZProjectionAndItsInverse) {
  const Intrinsics k = Intrinsics::from_hfov(320, 240, 1.2);
  const double n = 0.05, f = 30;
  const Eigen::Matrix4d P = optical_projection_reversed_z(k, n, f);
  const Vec3 p_O(-0.4, 0.25, 2.0);
  const Eigen::Vector4d clip = P * p_O.homogeneous();
  const Vec2 uv = project(k, p_O);
  // rows top-down: window y = v + 0.5
  EXPECT_NEAR((clip.x() / clip.w() + 1) / 2 * k.width, uv.x() + 0.5, 1e-9);
  EXPECT_NEAR((clip.y() / clip.w() + 1) / 2 * k.height, uv.y() + 0.5, 1e-9);
  const double d = clip.z() / clip.w();
  EXPECT_NEAR(depth_from_reversed_z(d, n, f), 2.0, 1e-12);
  EXPECT_NEAR((P * Vec3(0, 0, n).homogeneous()).z() / n, 1.0, 1e-12);
  EXPECT_NEAR((P * Vec3(0, 0, f).homogeneous()).z(), 0.0, 1e-9);
}

TEST(CameraModel, DistortionRoundTrip) {
  const BrownDistortion d{-0.28, 0.09, -0.01, 0.0012, -0.0008};
  for (double x = -0.6; x <= 0.6; x += 0.15) {
    for (double y = -0.45; y <= 0.45; y += 0.15) {
      const Vec2 p(x, y);
      const Vec2 back = undistort(d, distort(d, p));
      EXPECT_NEAR((back - p).norm(), 0.0, 1e-9) << x << ", " << y;
    }
  }
  // barrel distortion pulls points towards the centre; no distortion is the identity
  EXPECT_LT(distort(d, Vec2(0.5, 0)).x(), 0.5);
  EXPECT_EQ(distort(BrownDistortion{}, Vec2(0.3, -0.2)), Vec2(0.3, -0.2));
}

TEST(CameraModel, FromHfovRejectsBadInput) {
  EXPECT_THROW(Intrinsics::from_hfov(0, 480, 1.0), Error);
  EXPECT_THROW(Intrinsics::from_hfov(640, 480, M_PI), Error);
  try {
    Intrinsics::from_hfov(640, 480, -0.5);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Intrinsics::from_hfov: horizontal field of view"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rescuesim
