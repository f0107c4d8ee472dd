#pragma once
/// Renderer: camera images of a RenderScene — colour (sRGB), metric depth and apparent
/// temperature — rendered off-screen. The interface has no graphics types; the OpenGL 4.5 + EGL
/// implementation lives in render/gl. Public calls validate their input and then call the
/// backend (Drake's RenderColorImage → DoRenderColorImage habit), so every backend rejects bad
/// views with the same messages.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/camera_model.h"
#include "render/render_scene.h"

namespace rescuesim {

/// How much the colour image costs. low: per-vertex (Gouraud) lighting without highlights, no
/// shadows, no AO, no anti-aliasing (fast on a CPU rasteriser); medium: per-pixel Blinn-Phong,
/// 1024² shadow map with PCF + FXAA; high: 2048² shadows + 4× MSAA + screen-space ambient
/// occlusion. All qualities draw the same textures. Depth and thermal images are the same at
/// every quality.
enum class Quality { low, medium, high };

/// "low", "medium" or "high"; throws Error for any other value.
const char* quality_name(Quality q);

/// An 8-bit sRGB image, row 0 at the top, 3 bytes per pixel (R, G, B).
struct ColorImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

/// Depth along the optical axis (z of the optical frame, m), row 0 at the top; +inf where
/// nothing lies between the near and far clip planes, NaN where smoke or dust swallowed the
/// sensor's light (its two-way transmittance below 5 %, docs/environment.md).
struct DepthImage {
  int width = 0, height = 0;
  std::vector<float> z;
};

/// Apparent temperature (K) per pixel after the Gaussian blur, row 0 at the top. A surface at
/// temperature T with emissivity e reads e·T + (1 − e)·T_ambient (it reflects its surroundings,
/// taken to be at ambient); where nothing is in view the camera reads the ambient temperature.
/// Through smoke or dust of long-wave optical depth τ it reads T_ambient + (that − T_ambient)·e^−τ
/// (the media are at ambient).
struct ThermalImage {
  int width = 0, height = 0;
  std::vector<float> kelvin;
};

/// Where a camera is and what it sees.
struct CameraView {
  Pose3 X_WC;              ///< camera BODY frame in the world (x forward, y left, z up); optical frame = X_WC * X_BO()
  Intrinsics k;            ///< pinhole intrinsics (pixel convention in camera_model.h)
  double near_clip = 0.05; ///< m, > 0
  double far_clip = 30.0;  ///< m, > near_clip
  RobotIndex hide_robot;   ///< the robot whose links are not drawn (they still cast shadows); invalid: none
};

/// Checks a view: width and height in [1, 8192], fx, fy > 0 with a horizontal field of view in
/// (0, π), finite principal point, 0 < near < far, all finite, a finite unit-length rotation.
/// Throws Error whose text starts with `who` (e.g. "Renderer::color") and names the bad field.
void validate_view(const CameraView& view, const char* who);

/// Renders camera images of one scene. Not thread-safe: use it from one thread at a time (the
/// GL backend makes its context current on the calling thread at each call).
class Renderer {
 public:
  /// A headless OpenGL renderer. Picks an EGL device: a hardware device with a DRM render node
  /// (EGL_EXT_device_drm) through EGL_PLATFORM_DEVICE_EXT when there is one, else Mesa's
  /// surfaceless platform (llvmpipe on machines without a GPU). Throws Error with a plain reason
  /// ("no EGL display could be opened: …", "OpenGL 4.5 core is not available: the driver offers
  /// …") when it cannot, and for a Quality value outside the enum.
  static std::unique_ptr<Renderer> create_headless(Quality q = Quality::low);

  virtual ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Renderer and platform, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) via EGL surfaceless".
  virtual std::string device() const = 0;

  /// Uploads meshes and materials of a scene, replacing any scene loaded before.
  void load(const RenderScene& scene);
  /// Takes the current poses of the movable items (rubble, robot links) of the scene that was
  /// loaded; throws Error when `scene` has different items.
  void update(const RenderScene& scene);

  /// Colour image at the current quality. Throws Error for an invalid view or before load().
  ColorImage color(const CameraView& view);
  /// Depth image from the depth buffer, linearised to optical-axis depth.
  DepthImage depth(const CameraView& view);
  /// Thermal image blurred with a Gaussian of `blur_sigma_px` pixels (0 = no blur, at most 32).
  ThermalImage thermal(const CameraView& view, double blur_sigma_px);
  /// The same three, writing into an image whose pixel buffer is reused when it is big enough
  /// (no allocation per frame for a camera that keeps its image).
  void color(const CameraView& view, ColorImage& out);
  void depth(const CameraView& view, DepthImage& out);
  void thermal(const CameraView& view, double blur_sigma_px, ThermalImage& out);

  /// Changes the colour quality; throws Error for a value outside the enum.
  void set_quality(Quality q);
  Quality quality() const { return quality_; }

 protected:
  explicit Renderer(Quality q) : quality_(q) {}

 private:
  virtual void do_load(const RenderScene& scene) = 0;
  virtual void do_update(const RenderScene& scene) = 0;
  virtual void do_color(const CameraView& view, ColorImage& out) = 0;
  virtual void do_depth(const CameraView& view, DepthImage& out) = 0;
  virtual void do_thermal(const CameraView& view, double blur_sigma_px, ThermalImage& out) = 0;
  virtual void do_set_quality(Quality q) = 0;

  void require_scene(const char* who) const;

  Quality quality_;
  bool loaded_ = false;
  std::size_t item_count_ = 0;
};

}  // namespace rescuesim
