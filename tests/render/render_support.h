#pragma once
// Helpers of the render tests: a renderer or a skip when this machine has no headless OpenGL,
// camera views, small hand-built worlds, image statistics, and PNG dumps for looking at the
// images (set RESCUESIM_RENDER_PNG_DIR to a folder).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "render/renderer.h"
#include "support/require_gl.h"
#include "viz/canvas.h"

namespace rescuesim::render_test {

/// A headless renderer, or nullptr with the reason when EGL or GL 4.5 is genuinely missing.
inline std::unique_ptr<Renderer> try_renderer(Quality q, std::string& reason) {
  try {
    return Renderer::create_headless(q);
  } catch (const Error& e) {
    reason = e.what();
    return nullptr;
  }
}

/// Declares `var`, a renderer of quality `q`, or skips the test saying why there is none (fails
/// instead when RESCUESIM_REQUIRE_GL=1, support/require_gl.h).
#define RS_RENDERER_OR_SKIP(var, q)                                                                     \
  std::string var##_reason;                                                                             \
  std::unique_ptr<::rescuesim::Renderer> var = ::rescuesim::render_test::try_renderer(q, var##_reason); \
  RS_GL_OR_SKIP(var != nullptr, var##_reason)

/// A camera whose body frame sits at `p` (world, m) with heading `yaw` and `pitch` (rad,
/// positive pitch looks down).
inline CameraView camera(const Vec3& p, double yaw, double pitch, int w, int h, double hfov, double near_clip = 0.05,
                         double far_clip = 30.0) {
  CameraView v;
  v.X_WC = Pose3::from_rpy(p, 0, pitch, yaw);
  v.k = Intrinsics::from_hfov(w, h, hfov);
  v.near_clip = near_clip;
  v.far_clip = far_clip;
  return v;
}

/// A 20 m × 20 m floor around the origin, default materials, ambient 293 K, no robots.
inline WorldSpec floor_spec() {
  WorldSpec s;
  s.name = "render_test";
  s.materials = default_materials();
  s.floor_min = {-10, -10};
  s.floor_max = {10, 10};
  s.ambient_temperature = 293.0;
  return s;
}

inline std::size_t at(int w, int x, int y) {
  return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
}

/// Grey level (0..255) of a colour pixel.
inline double grey(const ColorImage& img, int x, int y) {
  const std::size_t i = 3 * at(img.width, x, y);
  return 0.299 * img.rgb[i] + 0.587 * img.rgb[i + 1] + 0.114 * img.rgb[i + 2];
}

/// Mean absolute grey-level difference to the right and downward neighbours over a region.
inline double mean_gradient(const ColorImage& img, int x0, int y0, int x1, int y1) {
  double sum = 0;
  int n = 0;
  for (int y = y0; y < y1 - 1; ++y) {
    for (int x = x0; x < x1 - 1; ++x) {
      sum += std::abs(grey(img, x + 1, y) - grey(img, x, y)) + std::abs(grey(img, x, y + 1) - grey(img, x, y));
      ++n;
    }
  }
  return n > 0 ? sum / n : 0.0;
}

inline Canvas to_canvas(const ColorImage& img) {
  Canvas c(img.width, img.height);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const std::size_t i = 3 * at(img.width, x, y);
      c.set(x, y, {img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]});
    }
  }
  return c;
}

/// Where to write PNGs for people to look at, or "" when RESCUESIM_RENDER_PNG_DIR is unset.
inline std::string dump_dir() {
  const char* d = std::getenv("RESCUESIM_RENDER_PNG_DIR");
  return d != nullptr ? d : "";
}

inline void dump(const std::string& name, const ColorImage& img) {
  if (dump_dir().empty()) return;
  to_canvas(img).write_png(std::filesystem::path(dump_dir()) / (name + ".png"));
}

/// Depth in false colour from near (red) through green to far (blue); +inf black.
inline void dump(const std::string& name, const DepthImage& img, double max_depth) {
  if (dump_dir().empty()) return;
  Canvas c(img.width, img.height, {0, 0, 0});
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const float z = img.z[at(img.width, x, y)];
      if (!std::isfinite(z)) continue;
      const double t = std::clamp(z / max_depth, 0.0, 1.0);
      const auto ch = [](double v) { return static_cast<std::uint8_t>(std::clamp(v, 0.0, 1.0) * 255); };
      c.set(x, y, {ch(1.5 - 3 * std::abs(t - 0.0)), ch(1.5 - 3 * std::abs(t - 0.5)), ch(1.5 - 3 * std::abs(t - 1.0))});
    }
  }
  c.write_png(std::filesystem::path(dump_dir()) / (name + ".png"));
}

/// Temperature as grey from `lo` (black) to `hi` (white) kelvin.
inline void dump(const std::string& name, const ThermalImage& img, double lo, double hi) {
  if (dump_dir().empty()) return;
  Canvas c(img.width, img.height);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const auto g = static_cast<std::uint8_t>(std::clamp((img.kelvin[at(img.width, x, y)] - lo) / (hi - lo), 0.0, 1.0) * 255);
      c.set(x, y, {g, g, g});
    }
  }
  c.write_png(std::filesystem::path(dump_dir()) / (name + ".png"));
}

}  // namespace rescuesim::render_test
