#pragma once
/// Pinhole camera maths shared by the renderer and the camera sensors, with no graphics types.
///
/// Pixel convention (ROS CameraInfo / OpenCV): a point p_O in the camera's optical frame
/// (z forward, x right, y down) projects to u = fx·x/z + cx, v = fy·y/z + cy, where (u, v) are
/// continuous pixel coordinates whose integers are pixel centres: pixel (i, j) — column i, row j,
/// row 0 at the top — covers u ∈ [i − 0.5, i + 0.5], v ∈ [j − 0.5, j + 0.5]. The whole image spans
/// u ∈ [−0.5, w − 0.5], v ∈ [−0.5, h − 0.5]. Intrinsics::from_hfov puts the principal point at
/// (w/2, h/2), half a pixel right of and below the geometric image centre; every function here
/// (and the renderer's projection) uses the same convention, so a rendered point lands exactly
/// where project() says.

#include <functional>

#include <Eigen/Core>

#include "core/pose.h"

namespace rescuesim {

/// Pinhole intrinsics in pixels (the K matrix of ROS CameraInfo).
struct Intrinsics {
  int width = 0, height = 0;   ///< image size (px)
  double fx = 0, fy = 0;       ///< focal lengths (px)
  double cx = 0, cy = 0;       ///< principal point (px, pixel-centre convention above)

  /// Square pixels with the horizontal field of view `hfov_rad` across the width:
  /// fx = fy = (w/2) / tan(hfov/2), cx = w/2, cy = h/2. Throws Error unless w and h are in
  /// [1, 8192] and hfov is in (0, π).
  static Intrinsics from_hfov(int w, int h, double hfov_rad);

  /// Horizontal field of view (rad) spanned by the width: 2·atan(w / (2·fx)).
  double hfov() const;
};

/// Pose of the optical frame O (z forward, x right, y down) in a camera body frame B (x forward,
/// y left, z up, REP-103): a pure rotation, so that X_WO = X_WB * X_BO().
Pose3 X_BO();

/// Pixel coordinates (u, v) of a point p_O in the optical frame (m); p_O.z() must be > 0.
Vec2 project(const Intrinsics& k, const Vec3& p_O);

/// The point in the optical frame (m) seen at pixel (u, v) with optical-axis depth `depth` (m).
Vec3 unproject(const Intrinsics& k, double u, double v, double depth);

/// OpenGL projection matrix from intrinsics, in the classic glFrustum conventions: eye
/// coordinates x right, y up, z backward (the optical frame with y and z negated); NDC z in
/// [−1, 1] from `near` to `far` (m); window y up, so pixel (u, v) lands at window coordinates
/// (u + 0.5, h − v − 0.5).
Eigen::Matrix4d gl_projection(const Intrinsics& k, double near, double far);

/// The renderer's own projection: takes optical-frame points (x right, y down, z forward)
/// straight to clip space with reversed Z for glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE): NDC
/// depth 1 at `near`, 0 at `far`. Window row y = v + 0.5, so reading the framebuffer back
/// bottom-up yields image rows top-down without a flip.
Eigen::Matrix4d optical_projection_reversed_z(const Intrinsics& k, double near, double far);

/// Optical-axis depth (m) from a reversed-Z window depth d in [0, 1] made by
/// optical_projection_reversed_z(…, near, far): z = near·far / ((far − near)·d + near).
double depth_from_reversed_z(double d, double near, double far);

/// Brown–Conrady lens distortion (OpenCV "plumb_bob": k1, k2, p1, p2, k3), on normalised image
/// coordinates (x/z, y/z of the optical frame).
struct BrownDistortion {
  double k1 = 0, k2 = 0, k3 = 0;  ///< radial coefficients
  double p1 = 0, p2 = 0;          ///< tangential coefficients
};

/// Distorts undistorted normalised coordinates.
Vec2 distort(const BrownDistortion& d, const Vec2& xy);

/// Inverts distort() by fixed-point iteration (as OpenCV's undistortPoints); accurate to about
/// 1e-9 for distortions of real lenses within their field of view.
Vec2 undistort(const BrownDistortion& d, const Vec2& xy_distorted, int iterations = 20);

/// Pose of a level camera body frame B (x forward, y left, z up; no roll) at the eye `p_WE`
/// looking at the target `p_WT` (world frame, m). Straight up or down, y is taken as world +y;
/// eye = target gives the world's orientation.
Pose3 look_at(const Vec3& p_WE, const Vec3& p_WT);

/// How the chase camera (the third-person view of `rescuesim view` and `snapshot`) trails the
/// robot (m, in the robot's heading frame).
inline constexpr double kChaseBack = 2.5;   ///< behind the robot
inline constexpr double kChaseUp = 1.8;     ///< above the robot's base
inline constexpr double kChaseAhead = 1.2;  ///< the point looked at, ahead of the robot
inline constexpr double kChaseAim = 0.1;    ///< height of that point above the base (m)

/// Eye and aim point of a camera (world frame, m).
struct ChasePoints {
  Vec3 eye = Vec3::Zero(), target = Vec3::Zero();
};

/// Where the chase camera is for a robot whose base is at `X_WB`: kChaseBack behind and kChaseUp
/// above it, aimed kChaseAhead ahead and kChaseAim up (heading only: it does not roll or pitch
/// with the chassis).
ChasePoints chase_points(const Pose3& X_WB);

/// Most an eye is raised to see over a wall (m).
inline constexpr double kMaxEyeLift = 1.5;

/// Whether something hides `to` from `from` (world frame, m). A function rather than a ray scene
/// so that render needs no raycast (the caller binds RayScene::occluded).
using SightBlocked = std::function<bool(const Vec3& from, const Vec3& to)>;

/// The eye moved so that nothing `blocked` reports hides the target `p_WT` or the robot point
/// `p_WR` from it: raised in sixths of kMaxEyeLift while that is enough, else moved from the
/// lifted eye towards the target in tenths (at most to 0.1 of the way). Unchanged when both are
/// in sight.
Vec3 clear_eye(const SightBlocked& blocked, const Vec3& p_WE, const Vec3& p_WT, const Vec3& p_WR);

}  // namespace rescuesim
