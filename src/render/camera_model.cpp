#include "render/camera_model.h"

#include <cmath>
#include <fmt/format.h>

#include "core/error.h"

namespace rescuesim {

Intrinsics Intrinsics::from_hfov(int w, int h, double hfov_rad) {
  const SourceRef where{"", 0, "Intrinsics::from_hfov"};
  if (w < 1 || w > 8192 || h < 1 || h > 8192) {
    throw Error(where, fmt::format("image size {}x{} is outside [1, 8192] px", w, h));
  }
  if (!(hfov_rad > 0 && hfov_rad < M_PI)) {
    throw Error(where, fmt::format("horizontal field of view {} rad is outside (0, pi)", hfov_rad));
  }
  Intrinsics k;
  k.width = w;
  k.height = h;
  k.fx = k.fy = 0.5 * w / std::tan(0.5 * hfov_rad);
  k.cx = 0.5 * w;
  k.cy = 0.5 * h;
  return k;
}

double Intrinsics::hfov() const { return 2.0 * std::atan(0.5 * width / fx); }

Pose3 X_BO() {
  // columns: the optical axes expressed in the body frame (x right = −y, y down = −z, z forward = x)
  Eigen::Matrix3d R_BO;
  R_BO << 0, 0, 1,
          -1, 0, 0,
          0, -1, 0;
  return {Vec3::Zero(), Quat(R_BO)};
}

Vec2 project(const Intrinsics& k, const Vec3& p_O) {
  return {k.fx * p_O.x() / p_O.z() + k.cx, k.fy * p_O.y() / p_O.z() + k.cy};
}

Vec3 unproject(const Intrinsics& k, double u, double v, double depth) {
  return {(u - k.cx) / k.fx * depth, (v - k.cy) / k.fy * depth, depth};
}

Eigen::Matrix4d gl_projection(const Intrinsics& k, double n, double f) {
  // pixel u spans NDC x = 2(u + 0.5)/w − 1 and window y = h − v − 0.5, with x_e = x, y_e = −y, z_e = −z
  const double w = k.width, h = k.height;
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  P(0, 0) = 2 * k.fx / w;
  P(0, 2) = 1 - 2 * (k.cx + 0.5) / w;
  P(1, 1) = 2 * k.fy / h;
  P(1, 2) = 2 * (k.cy + 0.5) / h - 1;
  P(2, 2) = -(f + n) / (f - n);
  P(2, 3) = -2 * f * n / (f - n);
  P(3, 2) = -1;
  return P;
}

Eigen::Matrix4d optical_projection_reversed_z(const Intrinsics& k, double n, double f) {
  // NDC x = 2(u + 0.5)/w − 1, NDC y = 2(v + 0.5)/h − 1, depth d = n(f − z) / (z(f − n)), w_clip = z
  const double w = k.width, h = k.height;
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  P(0, 0) = 2 * k.fx / w;
  P(0, 2) = 2 * (k.cx + 0.5) / w - 1;
  P(1, 1) = 2 * k.fy / h;
  P(1, 2) = 2 * (k.cy + 0.5) / h - 1;
  P(2, 2) = -n / (f - n);
  P(2, 3) = n * f / (f - n);
  P(3, 2) = 1;
  return P;
}

double depth_from_reversed_z(double d, double n, double f) { return n * f / ((f - n) * d + n); }

Vec2 distort(const BrownDistortion& d, const Vec2& xy) {
  const double x = xy.x(), y = xy.y();
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
  return {x * radial + 2 * d.p1 * x * y + d.p2 * (r2 + 2 * x * x), y * radial + d.p1 * (r2 + 2 * y * y) + 2 * d.p2 * x * y};
}

Vec2 undistort(const BrownDistortion& d, const Vec2& xy_distorted, int iterations) {
  // fixed point: x = (x_d − tangential(x)) / radial(x), starting from the distorted point
  Vec2 p = xy_distorted;
  for (int i = 0; i < iterations; ++i) {
    const double x = p.x(), y = p.y();
    const double r2 = x * x + y * y;
    const double radial = 1 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
    const double tx = 2 * d.p1 * x * y + d.p2 * (r2 + 2 * x * x);
    const double ty = d.p1 * (r2 + 2 * y * y) + 2 * d.p2 * x * y;
    p = {(xy_distorted.x() - tx) / radial, (xy_distorted.y() - ty) / radial};
  }
  return p;
}

Pose3 look_at(const Vec3& p_WE, const Vec3& p_WT) {
  // body frame: x towards the target, y left (level), z completing a right-handed frame
  Vec3 x = p_WT - p_WE;
  if (!(x.norm() > 1e-9)) x = Vec3::UnitX();
  x.normalize();
  Vec3 y = Vec3::UnitZ().cross(x);
  if (y.norm() < 1e-6) y = Vec3::UnitY();  // looking straight up or down
  y.normalize();
  const Vec3 z = x.cross(y);
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = y;
  R.col(2) = z;
  return {p_WE, Quat(R).normalized()};
}

ChasePoints chase_points(const Pose3& X_WB) {
  const double yaw = X_WB.yaw();
  const Vec3 forward(std::cos(yaw), std::sin(yaw), 0);
  return {X_WB.p - kChaseBack * forward + Vec3(0, 0, kChaseUp), X_WB.p + kChaseAhead * forward + Vec3(0, 0, kChaseAim)};
}

Vec3 clear_eye(const SightBlocked& blocked, const Vec3& p_WE, const Vec3& p_WT, const Vec3& p_WR) {
  const auto clear = [&](const Vec3& eye) { return !blocked(eye, p_WT) && !blocked(eye, p_WR); };
  // over the wall if a modest lift will do (the framing stays), else closer in under it
  for (int i = 0; i <= 6; ++i) {
    const Vec3 eye = p_WE + Vec3(0, 0, kMaxEyeLift * i / 6);
    if (clear(eye)) return eye;
  }
  const Vec3 lifted = p_WE + Vec3(0, 0, kMaxEyeLift);
  for (int i = 9; i >= 1; --i) {
    const Vec3 eye = p_WT + (lifted - p_WT) * (i / 10.0);
    if (clear(eye)) return eye;
  }
  return p_WT + (lifted - p_WT) * 0.1;
}

}  // namespace rescuesim
