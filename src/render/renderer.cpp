#include "render/renderer.h"

#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "render/gl/gl_renderer.h"

namespace rescuesim {

namespace {

constexpr int kMaxImageSize = 8192;
constexpr double kMaxBlurSigma = 32.0;

bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

Error view_error(const char* who, const std::string& message) { return Error(SourceRef{"", 0, who}, message); }

void check_quality(Quality q, const char* who) {
  if (q != Quality::low && q != Quality::medium && q != Quality::high) {
    throw Error(SourceRef{"", 0, who}, fmt::format("unknown quality {} (expected low, medium or high)", static_cast<int>(q)));
  }
}

}  // namespace

const char* quality_name(Quality q) {
  check_quality(q, "quality_name");
  switch (q) {
    case Quality::low: return "low";
    case Quality::medium: return "medium";
    case Quality::high: return "high";
  }
  return "low";
}

void validate_view(const CameraView& view, const char* who) {
  const Intrinsics& k = view.k;
  if (k.width < 1 || k.width > kMaxImageSize || k.height < 1 || k.height > kMaxImageSize) {
    throw view_error(who, fmt::format("view size {}x{} px is outside [1, {}]", k.width, k.height, kMaxImageSize));
  }
  if (!std::isfinite(k.fx) || !std::isfinite(k.fy) || !(k.fx > 0) || !(k.fy > 0)) {
    throw view_error(who, fmt::format("focal lengths fx = {}, fy = {} px must be finite and > 0", k.fx, k.fy));
  }
  const double hfov = k.hfov();
  if (!(hfov > 0 && hfov < M_PI)) {
    throw view_error(who, fmt::format("horizontal field of view {} rad is outside (0, pi)", hfov));
  }
  if (!std::isfinite(k.cx) || !std::isfinite(k.cy)) {
    throw view_error(who, fmt::format("principal point ({}, {}) px is not finite", k.cx, k.cy));
  }
  if (!std::isfinite(view.near_clip) || !std::isfinite(view.far_clip) || !(view.near_clip > 0) || !(view.near_clip < view.far_clip)) {
    throw view_error(who, fmt::format("clip planes near = {} m, far = {} m must be finite with 0 < near < far", view.near_clip,
                                      view.far_clip));
  }
  const Quat& q = view.X_WC.q;
  if (!finite(view.X_WC.p) || !std::isfinite(q.w()) || !finite(q.vec()) || std::abs(q.norm() - 1.0) > 1e-6) {
    throw view_error(who, "camera pose X_WC must be finite with a unit quaternion");
  }
}

std::unique_ptr<Renderer> Renderer::create_headless(Quality q) {
  check_quality(q, "Renderer::create_headless");
  return gl::make_headless_renderer(q);
}

Renderer::~Renderer() = default;

void Renderer::require_scene(const char* who) const {
  if (!loaded_) throw Error(SourceRef{"", 0, who}, "no scene loaded: call load() first");
}

void Renderer::load(const RenderScene& scene) {
  for (const RenderItem& item : scene.items) {
    if (item.mesh < 0 || static_cast<std::size_t>(item.mesh) >= scene.meshes.size() || item.material < 0 ||
        static_cast<std::size_t>(item.material) >= scene.materials.size()) {
      throw Error(SourceRef{"", 0, "Renderer::load"}, "an item refers to a mesh or material the scene does not have");
    }
  }
  do_load(scene);
  loaded_ = true;
  item_count_ = scene.items.size();
}

void Renderer::update(const RenderScene& scene) {
  require_scene("Renderer::update");
  if (scene.items.size() != item_count_) {
    throw Error(SourceRef{"", 0, "Renderer::update"},
                fmt::format("the scene has {} items but the loaded one has {}: load() it first", scene.items.size(), item_count_));
  }
  do_update(scene);
}

ColorImage Renderer::color(const CameraView& view) {
  ColorImage out;
  color(view, out);
  return out;
}

DepthImage Renderer::depth(const CameraView& view) {
  DepthImage out;
  depth(view, out);
  return out;
}

ThermalImage Renderer::thermal(const CameraView& view, double blur_sigma_px) {
  ThermalImage out;
  thermal(view, blur_sigma_px, out);
  return out;
}

void Renderer::color(const CameraView& view, ColorImage& out) {
  validate_view(view, "Renderer::color");
  require_scene("Renderer::color");
  out.width = view.k.width;
  out.height = view.k.height;
  out.rgb.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 3);
  do_color(view, out);
}

void Renderer::depth(const CameraView& view, DepthImage& out) {
  validate_view(view, "Renderer::depth");
  require_scene("Renderer::depth");
  out.width = view.k.width;
  out.height = view.k.height;
  out.z.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height));
  do_depth(view, out);
}

void Renderer::thermal(const CameraView& view, double blur_sigma_px, ThermalImage& out) {
  validate_view(view, "Renderer::thermal");
  if (!std::isfinite(blur_sigma_px) || blur_sigma_px < 0 || blur_sigma_px > kMaxBlurSigma) {
    throw Error(SourceRef{"", 0, "Renderer::thermal"}, fmt::format("blur sigma {} px is outside [0, {}]", blur_sigma_px, kMaxBlurSigma));
  }
  require_scene("Renderer::thermal");
  out.width = view.k.width;
  out.height = view.k.height;
  out.kelvin.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height));
  do_thermal(view, blur_sigma_px, out);
}

void Renderer::set_quality(Quality q) {
  check_quality(q, "Renderer::set_quality");
  if (q == quality_) return;
  do_set_quality(q);
  quality_ = q;
}

}  // namespace rescuesim
