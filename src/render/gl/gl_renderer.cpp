// The OpenGL 4.5 renderer: a headless EGL context, the scene in one vertex buffer, and the
// passes — shadow map, SSAO, colour, FXAA or MSAA resolve, depth, thermal with a separable
// Gaussian blur — each ending in a glReadPixels of the finished image.
//
// Every camera pass uses optical_projection_reversed_z: reversed Z into a 32-bit float depth
// buffer (precise metric depth far from the camera) and rows laid out top-down, so the read-back
// needs no flip. That projection mirrors the image vertically, so outward faces wind clockwise
// on screen (glFrontFace(GL_CW)).

#include "render/gl/gl_renderer.h"
#include "render/image_blur.h"

#include <array>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <stb_image.h>

#include "core/error.h"
#include "render/gl/egl_context.h"
#include "render/gl/gpu_scene.h"
#include "render/gl/render_targets.h"
#include "render/gl/shaders.h"
#include "render/fog_volumes.h"

namespace rescuesim::gl {

namespace {

constexpr int kMaxMaterials = 64;
constexpr int kMaxLights = 8;          ///< the shaders' light arrays (kLightUniforms)
constexpr int kMaxBlurRadius = 96;
constexpr std::size_t kMaxCachedSizes = 8;
constexpr double kAoRadius = 0.35;     ///< SSAO sampling radius (m)
constexpr double kAoBlurSigma = 1.5;   ///< px
constexpr int kPatternSize = 512;      ///< texels across a pattern layer
constexpr float kPatternPeriod = 2.0f; ///< m covered by a pattern layer (3.9 mm texels)
constexpr int kPatternLayers = 6;      ///< one per TextureKind; mesh images follow them (kImageLayer in the shader)
constexpr int kMaxImages = 16;         ///< mesh images per scene (each a 512 x 512 layer, 1.4 MB with mipmaps)
constexpr int kMaxFogPieces = 32;      ///< convex pieces of smoke and dust the camera shaders take
constexpr int kMaxFogSides = 192;      ///< and their sides (pieces x the most sides of any)
/// The depth camera's return is lost where its light's two-way transmittance through smoke or
/// dust falls below this: an active sensor tuned to find a dark surface at its full range has
/// perhaps 20x margin in clear air (docs/environment.md).
constexpr float kDepthMinReturn = 0.05f;

// lighting beside the scene's lights: ambient from the sky and the ground, a weak fill light
// from the side opposite the sun (all linear)
const Eigen::Vector3f kSkyAmbient(0.30f, 0.33f, 0.38f);
const Eigen::Vector3f kGroundAmbient(0.15f, 0.14f, 0.12f);
const Eigen::Vector3f kFillColor(0.16f, 0.16f, 0.17f);

/// Whether a fog piece is a box: a rectangular footprint (an SVG rect, turned or not) between its
/// bottom and top; then its axis u (a unit vector, (1, 0) for a rectangle along the world's axes)
/// and its corners in the frame (u, u turned 90 degrees, z). The shaders clip a ray against a box
/// with three multiplications by the ray's inverse direction in that frame instead of a division
/// per side.
bool box_of(const FogPiece& p, Vec3& lo, Vec3& hi, Vec2& axis) {
  if (p.half_planes.size() != 4) return false;
  const auto corners_along = [&](const Vec2& u) {
    const Vec2 v(-u.y(), u.x());
    lo = Vec3(-1e300, -1e300, p.bottom);
    hi = Vec3(1e300, 1e300, p.top);
    int seen = 0;
    for (const Vec3& h : p.half_planes) {
      const Vec2 n = h.head<2>();
      const double along[2] = {n.dot(u), n.dot(v)};
      for (int k = 0; k < 2; ++k) {
        if (std::abs(std::abs(along[k]) - 1) > 1e-12) continue;
        if (along[k] > 0) hi[k] = h.z(); else lo[k] = -h.z();
        seen |= 1 << (2 * k + (along[k] > 0 ? 1 : 0));
      }
    }
    return seen == 15;
  };
  // along the world's axes first, so such a box keeps exactly the arithmetic it always had
  axis = Vec2(1, 0);
  if (corners_along(axis)) return true;
  axis = p.half_planes[0].head<2>().normalized();
  return corners_along(axis);
}

int shadow_map_size(Quality q) { return q == Quality::high ? 2048 : q == Quality::medium ? 1024 : 0; }

/// World → clip of a camera view.
Eigen::Matrix4f view_projection(const CameraView& v) {
  const Pose3 X_WO = v.X_WC * X_BO();
  return (optical_projection_reversed_z(v.k, v.near_clip, v.far_clip) * X_WO.inverse().isometry().matrix()).cast<float>();
}

/// Depth test, culling and winding of every camera pass.
void camera_pass_state(int width, int height) {
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CW);
}

/// State of the full-screen image passes.
void image_pass_state(int width, int height) {
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
}

class GlRenderer final : public Renderer {
 public:
  explicit GlRenderer(Quality q);
  ~GlRenderer() override { context_.make_current(); }
  std::string device() const override { return context_.description(); }

 private:
  void do_load(const RenderScene& scene) override;
  void do_update(const RenderScene& scene) override;
  void do_color(const CameraView& view, ColorImage& out) override;
  void do_depth(const CameraView& view, DepthImage& out) override;
  void do_thermal(const CameraView& view, double blur_sigma_px, ThermalImage& out) override;
  void do_set_quality(Quality q) override;

  SizeTargets& targets(int width, int height);
  void configure_shadows(Quality q);
  void render_shadow_map();
  void render_ambient_occlusion(const CameraView& view, const Eigen::Matrix4f& view_proj, ColorTargets& t);
  void draw_scene(const Program& p, GLint model_location, const Eigen::Matrix4f& view_proj, const DrawFilter& filter) const;
  /// Separable Gaussian blur of the red channel: src → tmp across, tmp → dst down.
  void blur(GLuint src_tex, GLuint tmp_fbo, GLuint tmp_tex, GLuint dst_fbo, int width, int height, double sigma);

  /// The colour program of the current quality, with the media's fog or without (clear air, or
  /// no medium in this view: the clear program then costs nothing extra).
  int color_index(bool media) const { return (media ? 3 : 0) + static_cast<int>(quality()); }
  const Program& color(bool media) const { return color_[color_index(media)]; }
  /// Every colour program compiled (the fogged ones only while there are media).
  std::vector<const Program*> color_programs() const;
  /// Bakes the surface patterns into patterns_, then the scene's images after them.
  void bake_patterns();
  /// Decodes an image file and writes it, resampled to a layer, into layer `layer` of patterns_;
  /// false (and a warning) when the file cannot be decoded.
  bool upload_image(const std::string& file, int layer);
  /// Compiles the three colour programs for `lights` lights (0..kMaxLights), per pixel at every
  /// quality when `spots` (a cone's edge needs it), and with media three more with the fog of
  /// fog_pieces_ pieces and fog_boxes_ boxes.
  void build_color_programs(int lights, bool spots);
  /// Uploads the scene's lights to the colour programs, compiling them again first when the
  /// number of lights or whether there are spots changed, or when `rebuild`.
  void set_lights(const RenderScene& scene, bool rebuild);
  /// The loaded scene's materials into the colour programs.
  void upload_materials();
  /// Compiles the sky, depth and thermal fog programs for these pieces when their number or
  /// their sides' differ from what they were compiled for; true when they did (the colour
  /// programs must then be compiled again). Throws Error past kMaxFogPieces or kMaxFogSides.
  bool compile_fog(const std::vector<FogPiece>& pieces);
  /// Takes the pieces for every fog program: pieces past the compiled counts are left out (a
  /// footprint that stopped being simple as it grew), missing ones are clear air.
  void upload_fog(const std::vector<FogPiece>& pieces, double time);
  /// The pieces as seen from `eye` (world, m), into program `p`, before it draws a view.
  void set_fog_eye(const Program& p, const Vec3& eye) const;
  /// The window (x, y, width, height) of this view that holds the media's projection.
  std::array<int, 4> fog_window(const CameraView& view, const Eigen::Matrix4f& view_proj) const;
  /// Draws the sky through the media where the colour pass left the clear value.
  void draw_fog_sky(const CameraView& view, const Eigen::Matrix4f& view_proj, const std::array<int, 4>& window);
  bool fog() const { return fog_pieces_ + fog_boxes_ > 0; }

  EglContext context_;  // first member: made first, destroyed last, after every GL object
  Program color_[6];    // per Quality (shadows from medium, SSAO at high): clear, then through the media
  Program depth_, thermal_, fxaa_, ssao_;
  std::map<int, Program> blur_;  ///< blur programs by radius (px), made on first use
  GLint color_model_[6] = {-1, -1, -1, -1, -1, -1}, depth_model_ = -1, thermal_model_ = -1;
  Texture patterns_;
  std::vector<MediumSpec> media_;  ///< the scene's smoke and dust
  double fog_time_ = -1;           ///< sim time the fog uniforms were cut at
  int fog_pieces_ = 0, fog_sides_ = 0;  ///< what the fog programs were compiled for: general pieces, sides of each,
  int fog_boxes_ = 0;                   ///< and boxes (rectangular footprints, box_of)
  std::vector<FogPiece> fog_;           ///< the general pieces now, fog_pieces_ of them (clear air after the real ones)
  std::vector<Eigen::AlignedBox3d> fog_box_;  ///< the boxes now, fog_boxes_ of them, in their own frames
  std::vector<Vec2> fog_box_axis_;            ///< and their axes (box_of)
  std::vector<FogPiece> fog_now_;       ///< every piece as last uploaded (the programs compiled again take them)
  Program fog_sky_, depth_fog_, thermal_fog_;
  GLint depth_fog_model_ = -1, thermal_fog_model_ = -1;
  Eigen::Vector3f fog_light_ = Eigen::Vector3f::Zero();  ///< linear light on the media
  std::vector<std::string> images_;  ///< image files of the scene, in layer order after the patterns
  int light_count_ = -1;  ///< lights the colour programs were compiled for
  bool spot_lights_ = false;  ///< whether they were compiled for spot lights
  std::vector<float> material_, layer_;  ///< the colour programs' material uniforms
  float ambient_light_ = 1.0f;           ///< RenderScene::ambient_light
  VertexArray empty_vao_;
  GpuScene scene_;
  Eigen::Vector4f sky_ = Eigen::Vector4f::Zero();  ///< sRGB clear colour, luma in alpha
  float ambient_temperature_ = 293.15f;
  int shadow_light_ = -1;                          ///< light index with the shadow map, -1 none
  Vec3 shadow_direction_ = -Vec3::UnitZ();
  Texture shadow_map_;
  Framebuffer shadow_fbo_;
  int shadow_size_ = 0;
  bool shadow_dirty_ = true;
  std::vector<std::unique_ptr<SizeTargets>> targets_;  ///< least recently used first
  std::vector<float> blur_weights_;
  double blur_sigma_ = -1;
};

GlRenderer::GlRenderer(Quality q) : Renderer(q) {
  build_color_programs(1, false);
  depth_ = Program("depth", shaders::kDepthVertex, shaders::kDepthFragment);
  thermal_ = Program("thermal", shaders::kSceneVertex, shaders::kThermalFragment);
  fxaa_ = Program("fxaa", shaders::kFullscreenVertex, shaders::kFxaaFragment);
  ssao_ = Program("ssao", shaders::kFullscreenVertex, shaders::kSsaoFragment);
  depth_model_ = depth_.uniform("u_model");
  thermal_model_ = thermal_.uniform("u_model");
  fxaa_.set("u_src", 0);
  ssao_.set("u_depth", 0);
  empty_vao_ = VertexArray::create();
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  configure_shadows(q);
}

void GlRenderer::build_color_programs(int lights, bool spots) {
  for (int k = 0; k < 6; ++k) {
    const int i = k % 3;
    const bool media = k >= 3;
    color_[k] = Program();
    color_model_[k] = -1;
    if (media && !fog()) continue;
    // low: Gouraud lighting (per pixel when there are spot lights), no shadows; medium: per-pixel
    // with shadows; high: and SSAO
    const bool per_pixel = i > 0 || spots;
    const std::string header = fmt::format("#version 450 core\n#define LIGHTS {}\n#define PER_PIXEL {}\n#define SHADOWS {}\n#define AO {}\n"
                                           "#define MEDIA {}\n#define MEDIA_SIDES {}\n#define MEDIA_BOXES {}\n#define MEDIA_PIECES {}\n",
                                           lights, per_pixel ? 1 : 0, i > 0 ? 1 : 0, i > 1 ? 1 : 0, media ? 1 : 0, std::max(fog_sides_, 1),
                                           fog_boxes_, fog_pieces_);
    const std::string common = header + shaders::kLightUniforms;
    const std::string fog_code = media ? shaders::kFogFunctions : "";
    color_[k] = Program(media ? "colour through media" : "colour",
                        !per_pixel ? common + shaders::kGouraudVertex : std::string(shaders::kSceneVertex),
                        common + fog_code + shaders::kColorFragment);
    color_model_[k] = color_[k].uniform("u_model");
    // samplers of different types may not share a texture unit
    color_[k].set("u_shadow_map", 1);
    color_[k].set("u_ao", 2);
    color_[k].set("u_patterns", 3);
    color_[k].set("u_period", kPatternPeriod);
    color_[k].set("u_shadow_light", -1);
  }
  light_count_ = lights;
  spot_lights_ = spots;
}

std::vector<const Program*> GlRenderer::color_programs() const {
  std::vector<const Program*> out;
  for (const Program& p : color_) {
    if (p) out.push_back(&p);
  }
  return out;
}

void GlRenderer::bake_patterns() {
  const int levels = 1 + static_cast<int>(std::log2(kPatternSize));
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
  patterns_ = Texture(id);
  glTextureStorage3D(id, levels, GL_RGBA8, kPatternSize, kPatternSize, kPatternLayers + static_cast<int>(images_.size()));
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);  // bilinear in one level: trilinear costs a CPU rasteriser 15 %
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_REPEAT);
  const Framebuffer fbo = Framebuffer::create();
  image_pass_state(kPatternSize, kPatternSize);
  glBindVertexArray(empty_vao_.id());
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  for (int layer = 0; layer < kPatternLayers; ++layer) {
    const Program bake("pattern", shaders::kFullscreenVertex,
                       fmt::format("#version 450 core\n#define KIND {}\n{}", layer, shaders::kPatternFragment));
    bake.set("u_period", kPatternPeriod);
    bake.set("u_size", static_cast<float>(kPatternSize));
    glUseProgram(bake.id());
    glNamedFramebufferTextureLayer(fbo.id(), GL_COLOR_ATTACHMENT0, id, 0, layer);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  for (std::size_t i = 0; i < images_.size(); ++i) upload_image(images_[i], kPatternLayers + static_cast<int>(i));
  glGenerateTextureMipmap(id);
}

bool GlRenderer::upload_image(const std::string& file, int layer) {
  // stb_image (Debian's libstb) decodes PNG, JPEG, BMP and TGA into 8-bit RGB, rows top-down
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> pixels(stbi_load(file.c_str(), &w, &h, &channels, 3), stbi_image_free);
  if (!pixels || w <= 0 || h <= 0) {
    spdlog::warn("cannot decode the texture image {} ({}): the mesh is drawn white", file, stbi_failure_reason());
    return false;
  }
  // resampled (bilinear) to the layer's size; layer row 0 is t = 0, the image's bottom row, as
  // OBJ and COLLADA texture coordinates have v up; texels are linear albedo / 2, as the patterns'
  std::vector<std::uint8_t> texels(static_cast<std::size_t>(4 * kPatternSize * kPatternSize));
  float linear[256];
  for (int i = 0; i < 256; ++i) linear[i] = static_cast<float>(srgb_to_linear(i / 255.0));
  const auto at = [&](int x, int y, int c) {
    return linear[pixels.get()[3 * (static_cast<std::size_t>(std::clamp(y, 0, h - 1)) * static_cast<std::size_t>(w) +
                                    static_cast<std::size_t>(std::clamp(x, 0, w - 1))) + static_cast<std::size_t>(c)]];
  };
  for (int row = 0; row < kPatternSize; ++row) {
    const float fy = (1.0f - (row + 0.5f) / kPatternSize) * static_cast<float>(h) - 0.5f;
    const int y0 = static_cast<int>(std::floor(fy));
    const float ty = fy - static_cast<float>(y0);
    for (int col = 0; col < kPatternSize; ++col) {
      const float fx = (col + 0.5f) / kPatternSize * static_cast<float>(w) - 0.5f;
      const int x0 = static_cast<int>(std::floor(fx));
      const float tx = fx - static_cast<float>(x0);
      std::uint8_t* out = &texels[4 * (static_cast<std::size_t>(row) * kPatternSize + static_cast<std::size_t>(col))];
      for (int c = 0; c < 3; ++c) {
        const float top = at(x0, y0, c) * (1 - tx) + at(x0 + 1, y0, c) * tx;
        const float bottom = at(x0, y0 + 1, c) * (1 - tx) + at(x0 + 1, y0 + 1, c) * tx;
        out[c] = static_cast<std::uint8_t>(std::lround(std::clamp(0.5f * (top * (1 - ty) + bottom * ty), 0.0f, 1.0f) * 255.0f));
      }
      out[3] = 255;
    }
  }
  glTextureSubImage3D(patterns_.id(), 0, 0, 0, layer, kPatternSize, kPatternSize, 1, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
  return true;
}

void GlRenderer::configure_shadows(Quality q) {
  shadow_size_ = shadow_map_size(q);
  shadow_map_.reset();
  shadow_fbo_.reset();
  shadow_dirty_ = true;
  if (shadow_size_ == 0) return;
  shadow_map_ = Texture::create_2d(GL_DEPTH_COMPONENT32F, shadow_size_, shadow_size_);
  // hardware comparison with bilinear filtering: each lookup is already a 2 × 2 PCF
  glTextureParameteri(shadow_map_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(shadow_map_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(shadow_map_.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(shadow_map_.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  shadow_fbo_ = Framebuffer::create();
  glNamedFramebufferTexture(shadow_fbo_.id(), GL_DEPTH_ATTACHMENT, shadow_map_.id(), 0);
  glNamedFramebufferDrawBuffer(shadow_fbo_.id(), GL_NONE);
  shadow_fbo_.check_complete("shadow map");
}

SizeTargets& GlRenderer::targets(int width, int height) {
  auto it = std::find_if(targets_.begin(), targets_.end(), [&](const auto& t) { return t->width == width && t->height == height; });
  if (it == targets_.end()) {
    if (targets_.size() >= kMaxCachedSizes) targets_.erase(targets_.begin());
    auto t = std::make_unique<SizeTargets>();
    t->width = width;
    t->height = height;
    targets_.push_back(std::move(t));
  } else if (it + 1 != targets_.end()) {
    std::rotate(it, it + 1, targets_.end());
  }
  return *targets_.back();
}

void GlRenderer::do_load(const RenderScene& scene) {
  context_.make_current();
  if (scene.materials.size() > static_cast<std::size_t>(kMaxMaterials)) {
    throw Error(SourceRef{"", 0, "Renderer::load"},
                fmt::format("the scene has {} materials; at most {} are supported", scene.materials.size(), kMaxMaterials));
  }
  scene_.upload(scene);

  // materials: linear albedo and roughness, texture kind or image layer (the first kMaxImages
  // images; materials with more are drawn in their pattern)
  material_.assign(4 * kMaxMaterials, 0.0f);
  layer_.assign(kMaxMaterials, 0.0f);
  std::vector<std::string> images;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const RenderMaterial& m = scene.materials[i];
    for (int c = 0; c < 3; ++c) material_[4 * i + static_cast<std::size_t>(c)] = static_cast<float>(m.albedo[c]);
    material_[4 * i + 3] = static_cast<float>(m.roughness);
    layer_[i] = static_cast<float>(m.texture);
    if (m.image.empty()) continue;
    auto it = std::find(images.begin(), images.end(), m.image);
    if (it == images.end() && images.size() < static_cast<std::size_t>(kMaxImages)) it = images.insert(images.end(), m.image);
    if (it != images.end()) layer_[i] = static_cast<float>(kPatternLayers + (it - images.begin()));
  }
  if (images != images_) {
    images_ = std::move(images);
    patterns_ = Texture();  // baked again, with these images, on the next colour image
  }

  // daylight: the sky and the ambient and fill light scale together
  ambient_light_ = static_cast<float>(std::max(0.0, scene.ambient_light));
  Eigen::Vector3f sky = scene.sky_color.cast<float>().cwiseMax(0.0f).cwiseMin(1.0f);
  if (ambient_light_ < 1.0f) {
    for (int c = 0; c < 3; ++c) sky[c] = static_cast<float>(linear_to_srgb(srgb_to_linear(sky[c]) * ambient_light_));
  }
  sky_ = Eigen::Vector4f(sky.x(), sky.y(), sky.z(), sky.dot(Eigen::Vector3f(0.299f, 0.587f, 0.114f)));
  ambient_temperature_ = static_cast<float>(scene.ambient_temperature);

  media_ = scene.media;
  const std::vector<FogPiece> pieces = fog_pieces(media_, scene.time);
  const bool fog_compiled = compile_fog(pieces);
  set_lights(scene, fog_compiled);
  upload_materials();
  if (fog()) upload_fog(pieces, scene.time);
  shadow_dirty_ = true;
}

void GlRenderer::upload_materials() {
  if (material_.empty()) return;
  for (const Program* p : color_programs()) {
    glProgramUniform4fv(p->id(), p->uniform("u_material"), kMaxMaterials, material_.data());
    glProgramUniform1fv(p->id(), p->uniform("u_layer"), kMaxMaterials, layer_.data());
  }
}

void GlRenderer::set_lights(const RenderScene& scene, bool rebuild) {
  // the first kMaxLights; the first shadow-casting directional one gets the shadow map
  const int count = std::min<int>(kMaxLights, static_cast<int>(scene.lights.size()));
  std::vector<float> where(4 * kMaxLights, 0.0f), color(3 * kMaxLights, 0.0f), cone(4 * kMaxLights, 0.0f), shape(4 * kMaxLights, 0.0f);
  bool spots = false;
  shadow_light_ = -1;
  Vec3 sun = Vec3(-0.35, 0.45, -1.0).normalized();
  // the light on the media: the ambient a matte surface gets from all round, and a quarter of
  // each directional light's (an isotropic scatterer sends 1/4pi of it per steradian where a
  // Lambertian surface facing it sends 1/pi); point and spot lights are left out
  Eigen::Vector3f on_media = ambient_light_ * (0.5f * (kSkyAmbient + kGroundAmbient) + 0.25f * kFillColor);
  for (int i = 0; i < count; ++i) {
    const RenderLight& l = scene.lights[static_cast<std::size_t>(i)];
    const auto at = static_cast<std::size_t>(i);
    const Vec3 v = l.directional ? l.direction : l.position;
    for (int c = 0; c < 3; ++c) {
      where[4 * at + static_cast<std::size_t>(c)] = static_cast<float>(v[c]);
      color[3 * at + static_cast<std::size_t>(c)] = static_cast<float>(l.color[c]);
    }
    where[4 * at + 3] = l.directional ? 0.0f : 1.0f;
    // a cone (spot lights) as the axis and the cosines of its edge and core; none: cosines
    // below -1, so every direction is inside
    const bool spot = !l.directional && l.spot;
    const Vec3 axis = l.direction.norm() > 1e-9 ? l.direction.normalized() : Vec3(1, 0, 0);
    for (int c = 0; c < 3; ++c) cone[4 * at + static_cast<std::size_t>(c)] = static_cast<float>(axis[c]);
    cone[4 * at + 3] = spot ? static_cast<float>(std::cos(l.cone)) : -3.0f;
    shape[4 * at] = spot ? static_cast<float>(std::cos(std::min(l.inner_cone, l.cone - 1e-3))) : -2.0f;
    shape[4 * at + 1] = !l.directional && l.range > 0 ? static_cast<float>(1.0 / (l.range * l.range)) : 0.0f;
    spots = spots || spot;
    if (l.directional) on_media += 0.25f * l.color.cast<float>();
    if (l.directional && shadow_light_ < 0) sun = l.direction;
    if (l.directional && l.casts_shadows && shadow_light_ < 0) {
      shadow_light_ = i;
      shadow_direction_ = l.direction;
    }
  }
  fog_light_ = on_media;
  if (rebuild || count != light_count_ || spots != spot_lights_) {
    build_color_programs(count, spots);
    upload_materials();
    if (fog()) upload_fog(fog_now_, fog_time_);
    shadow_dirty_ = true;
  }
  // the fill light comes from the side the sun shines towards, a little above the horizon
  Vec3 across(sun.x(), sun.y(), 0);
  across = across.norm() > 1e-6 ? across.normalized() : Vec3::UnitX();
  for (const Program* program : color_programs()) {
    const Program& p = *program;
    glProgramUniform4fv(p.id(), p.uniform("u_light"), kMaxLights, where.data());
    glProgramUniform3fv(p.id(), p.uniform("u_light_color"), kMaxLights, color.data());
    glProgramUniform4fv(p.id(), p.uniform("u_light_cone"), kMaxLights, cone.data());
    glProgramUniform4fv(p.id(), p.uniform("u_light_shape"), kMaxLights, shape.data());
    p.set("u_fill_dir", Eigen::Vector3f((across + Vec3(0, 0, 0.7)).normalized().cast<float>()));
    p.set("u_fill_color", Eigen::Vector3f(ambient_light_ * kFillColor));
    p.set("u_sky_ambient", Eigen::Vector3f(ambient_light_ * kSkyAmbient));
    p.set("u_ground_ambient", Eigen::Vector3f(ambient_light_ * kGroundAmbient));
    if (fog()) p.set("u_fog_light", fog_light_);
  }
  if (fog()) fog_sky_.set("u_fog_light", fog_light_);
}

bool GlRenderer::compile_fog(const std::vector<FogPiece>& pieces) {
  int sides = 0, n = 0, boxes = 0;
  for (const FogPiece& p : pieces) {
    Vec3 lo, hi;
    Vec2 axis;
    if (box_of(p, lo, hi, axis)) {
      ++boxes;
    } else {
      ++n;
      sides = std::max(sides, static_cast<int>(p.half_planes.size()));
    }
  }
  if (n + boxes > kMaxFogPieces || n * sides > kMaxFogSides) {
    throw Error(SourceRef{"", 0, "Renderer::load"},
                fmt::format("the smoke and dust make {} convex pieces, {} of up to {} sides; the cameras draw at most {} pieces and {} "
                            "sides in all (fewer media, or footprints with fewer corners)",
                            n + boxes, n, sides, kMaxFogPieces, kMaxFogSides));
  }
  if (n == fog_pieces_ && sides == fog_sides_ && boxes == fog_boxes_) return false;
  fog_pieces_ = n;
  fog_sides_ = sides;
  fog_boxes_ = boxes;
  fog_sky_ = Program();
  depth_fog_ = Program();
  thermal_fog_ = Program();
  if (fog()) {
    const std::string head =
        fmt::format("#version 450 core\n#define MEDIA 1\n#define MEDIA_PIECES {}\n#define MEDIA_SIDES {}\n#define MEDIA_BOXES {}\n{}", n,
                    std::max(sides, 1), boxes, shaders::kFogFunctions);
    fog_sky_ = Program("fog sky", shaders::kFullscreenVertex, head + shaders::kFogSkyFragment);
    depth_fog_ = Program("depth through fog", shaders::kFogVertex, head + shaders::kDepthFogFragment);
    thermal_fog_ = Program("thermal through fog", shaders::kFogVertex, head + shaders::kThermalFogFragment);
    depth_fog_model_ = depth_fog_.uniform("u_model");
    thermal_fog_model_ = thermal_fog_.uniform("u_model");
    const float lost = 0.5f * std::log(1.0f / kDepthMinReturn);
    depth_fog_.set("u_lost_depth_squared", lost * lost);
  }
  return true;
}

void GlRenderer::upload_fog(const std::vector<FogPiece>& pieces, double time) {
  if (&pieces != &fog_now_) fog_now_ = pieces;
  fog_.assign(static_cast<std::size_t>(fog_pieces_), FogPiece{});
  fog_box_.assign(static_cast<std::size_t>(fog_boxes_), Eigen::AlignedBox3d(Vec3::Zero(), Vec3::Zero()));
  fog_box_axis_.assign(static_cast<std::size_t>(fog_boxes_), Vec2(1, 0));
  std::vector<float> sigma(4 * static_cast<std::size_t>(fog_pieces_), 0.0f), box_sigma(4 * static_cast<std::size_t>(fog_boxes_), 0.0f);
  const auto coefficients = [](const FogPiece& p, float* out) {
    out[0] = static_cast<float>(p.sigma_visible);
    out[1] = static_cast<float>(p.sigma_near_infrared);
    out[2] = static_cast<float>(p.sigma_long_wave);
    out[3] = static_cast<float>(p.albedo);
  };
  int general = 0, boxes = 0;
  for (const FogPiece& p : pieces) {
    Vec3 lo, hi;
    Vec2 axis;
    if (box_of(p, lo, hi, axis)) {
      if (boxes >= fog_boxes_) continue;  // more than the programs were compiled for: left out
      fog_box_[static_cast<std::size_t>(boxes)] = Eigen::AlignedBox3d(lo, hi);
      fog_box_axis_[static_cast<std::size_t>(boxes)] = axis;
      coefficients(p, &box_sigma[4 * static_cast<std::size_t>(boxes++)]);
    } else {
      // grown past what the programs were compiled for: left out
      if (general >= fog_pieces_ || static_cast<int>(p.half_planes.size()) > fog_sides_) continue;
      fog_[static_cast<std::size_t>(general)] = p;
      coefficients(p, &sigma[4 * static_cast<std::size_t>(general++)]);
    }
  }
  std::vector<const Program*> fogged = {&color_[3], &color_[4], &color_[5], &fog_sky_, &depth_fog_, &thermal_fog_};
  for (const Program* p : fogged) {
    if (!*p) continue;
    if (fog_pieces_ > 0) glProgramUniform4fv(p->id(), p->uniform("u_fog_sigma"), fog_pieces_, sigma.data());
    if (fog_boxes_ > 0) glProgramUniform4fv(p->id(), p->uniform("u_fog_box_sigma"), fog_boxes_, box_sigma.data());
  }
  for (const Program* p : color_programs()) p->set("u_fog_light", fog_light_);
  fog_sky_.set("u_fog_light", fog_light_);
  fog_time_ = time;
}

namespace {

/// The window rectangle (x, y, width, height in px, GL's origin bottom left) that holds the
/// projection of every piece's prism: only pixels in it have rays that cross a medium. Pieces
/// wholly behind the eye's plane are left out; the whole view when one straddles it (the eye in
/// or beside a medium); empty (width 0) when no piece is in front or every one is off screen.
std::array<int, 4> media_window(std::span<const FogPiece> pieces, const Eigen::Matrix4f& view_proj, int w, int h) {
  Eigen::Vector2f lo(1e30f, 1e30f), hi(-1e30f, -1e30f);
  std::vector<Eigen::Vector4f> clip;
  for (const FogPiece& piece : pieces) {
    clip.clear();
    for (const Vec2& c : piece.corners) {
      for (double z : {piece.bottom, piece.top}) {
        clip.push_back(view_proj * Eigen::Vector4f(static_cast<float>(c.x()), static_cast<float>(c.y()), static_cast<float>(z), 1.0f));
      }
    }
    // wholly behind the eye: no ray of the view enters it; partly: it may cover any pixel
    const auto in_front = std::count_if(clip.begin(), clip.end(), [](const Eigen::Vector4f& q) { return q.w() > 1e-4f; });
    if (in_front == 0) continue;
    if (in_front < static_cast<std::ptrdiff_t>(clip.size())) return {0, 0, w, h};
    for (const Eigen::Vector4f& q : clip) {
      const Eigen::Vector2f px((q.x() / q.w() + 1.0f) * 0.5f * static_cast<float>(w),
                               (q.y() / q.w() + 1.0f) * 0.5f * static_cast<float>(h));
      lo = lo.cwiseMin(px), hi = hi.cwiseMax(px);
    }
  }
  if (lo.x() > hi.x()) return {0, 0, 0, 0};
  const int x0 = std::clamp(static_cast<int>(std::floor(lo.x())) - 1, 0, w),
            y0 = std::clamp(static_cast<int>(std::floor(lo.y())) - 1, 0, h);
  const int x1 = std::clamp(static_cast<int>(std::ceil(hi.x())) + 1, 0, w), y1 = std::clamp(static_cast<int>(std::ceil(hi.y())) + 1, 0, h);
  return {x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

}  // namespace

std::array<int, 4> GlRenderer::fog_window(const CameraView& view, const Eigen::Matrix4f& view_proj) const {
  return media_window(fog_now_, view_proj, view.k.width, view.k.height);
}

void GlRenderer::set_fog_eye(const Program& p, const Vec3& eye) const {
  // a side n·p <= c as (n, n·eye - c): the shader adds n·d; unused sides hold everything
  std::vector<float> edge(4 * static_cast<std::size_t>(fog_pieces_ * fog_sides_), 0.0f), slab(4 * fog_.size(), 0.0f);
  for (std::size_t k = 2; k < edge.size(); k += 4) edge[k] = -1e30f;
  for (std::size_t i = 0; i < fog_.size(); ++i) {
    const FogPiece& f = fog_[i];
    for (std::size_t k = 0; k < f.half_planes.size(); ++k) {
      const Vec3& h = f.half_planes[k];
      float* e = &edge[4 * (i * static_cast<std::size_t>(fog_sides_) + k)];
      e[0] = static_cast<float>(h.x());
      e[1] = static_cast<float>(h.y());
      e[2] = static_cast<float>(h.x() * eye.x() + h.y() * eye.y() - h.z());
    }
    slab[4 * i] = static_cast<float>(f.bottom - eye.z());
    slab[4 * i + 1] = static_cast<float>(f.top - eye.z());
  }
  // a box's corners as seen from the eye, in the box's frame, and its axis
  std::vector<float> lo(4 * fog_box_.size(), 0.0f), hi(4 * fog_box_.size(), 0.0f), axis(4 * fog_box_.size(), 0.0f);
  for (std::size_t i = 0; i < fog_box_.size(); ++i) {
    const Vec2 u = fog_box_axis_[i];
    const Vec3 eye_b(u.dot(eye.head<2>()), Vec2(-u.y(), u.x()).dot(eye.head<2>()), eye.z());
    for (int c = 0; c < 3; ++c) {
      lo[4 * i + static_cast<std::size_t>(c)] = static_cast<float>(std::max(fog_box_[i].min()[c] - eye_b[c], -1e30));
      hi[4 * i + static_cast<std::size_t>(c)] = static_cast<float>(std::min(fog_box_[i].max()[c] - eye_b[c], 1e30));
    }
    axis[4 * i] = static_cast<float>(u.x());
    axis[4 * i + 1] = static_cast<float>(u.y());
  }
  if (fog_pieces_ > 0) {
    glProgramUniform4fv(p.id(), p.uniform("u_fog_edge"), fog_pieces_ * fog_sides_, edge.data());
    glProgramUniform4fv(p.id(), p.uniform("u_fog_slab"), fog_pieces_, slab.data());
  }
  if (fog_boxes_ > 0) {
    glProgramUniform4fv(p.id(), p.uniform("u_fog_box_lo"), fog_boxes_, lo.data());
    glProgramUniform4fv(p.id(), p.uniform("u_fog_box_hi"), fog_boxes_, hi.data());
    glProgramUniform4fv(p.id(), p.uniform("u_fog_box_axis"), fog_boxes_, axis.data());
  }
  p.set("u_eye", Eigen::Vector3f(eye.cast<float>()));
}

void GlRenderer::draw_fog_sky(const CameraView& view, const Eigen::Matrix4f& view_proj, const std::array<int, 4>& rect) {
  const int w = view.k.width, h = view.k.height;
  // the sky is fogged only where a medium stands in front of it: the pass is scissored to the
  // media's projection `rect` (a CPU rasteriser then shades only those pixels), and skipped without one
  if (rect[2] == 0 || rect[3] == 0) return;
  glEnable(GL_SCISSOR_TEST);
  glScissor(rect[0], rect[1], rect[2], rect[3]);
  glViewport(0, 0, w, h);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_EQUAL);  // the full-screen triangle lies at depth 0, the clear value: only where nothing was drawn
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  glUseProgram(fog_sky_.id());
  fog_sky_.set("u_inv_view_proj", Eigen::Matrix4f(view_proj.inverse()));
  fog_sky_.set("u_size", Eigen::Vector2f(static_cast<float>(w), static_cast<float>(h)));
  set_fog_eye(fog_sky_, view.X_WC.p);
  const auto linear = [](float c) { return static_cast<float>(srgb_to_linear(c)); };
  fog_sky_.set("u_sky", Eigen::Vector3f(linear(sky_.x()), linear(sky_.y()), linear(sky_.z())));
  glBindVertexArray(empty_vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
  glDisable(GL_SCISSOR_TEST);
}

void GlRenderer::do_update(const RenderScene& scene) {
  scene_.update(scene);
  shadow_dirty_ = true;
  // robot lamps move with their links and switch on and off
  if (!scene.lamps.empty()) {
    context_.make_current();
    set_lights(scene, false);
  }
  // media that grow or drift are cut again at the scene's time
  const bool moving =
      std::any_of(media_.begin(), media_.end(), [](const MediumSpec& m) { return m.growth != 0 || m.drift != Vec2::Zero(); });
  if (fog() && moving && scene.time != fog_time_) {
    context_.make_current();
    upload_fog(fog_pieces(media_, scene.time), scene.time);
  }
}

void GlRenderer::do_set_quality(Quality q) {
  context_.make_current();
  configure_shadows(q);
  for (auto& t : targets_) t->color.reset();
}

void GlRenderer::draw_scene(const Program& p, GLint model_location, const Eigen::Matrix4f& view_proj, const DrawFilter& filter) const {
  glUseProgram(p.id());
  p.set("u_view_proj", view_proj);
  scene_.draw(p.id(), model_location, filter);
}

void GlRenderer::render_shadow_map() {
  // an orthographic view along the light around everything that casts shadows
  Eigen::AlignedBox3d box = scene_.caster_bounds();
  if (box.isEmpty()) {
    for (const Program* p : color_programs()) p->set("u_shadow_light", -1);
    return;
  }
  box.extend(box.min() - Vec3::Constant(0.25));
  box.extend(box.max() + Vec3::Constant(0.25));
  const Vec3 f = shadow_direction_.normalized();
  const Vec3 r = f.cross(std::abs(f.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitX()).normalized();
  const Vec3 u = r.cross(f);
  Eigen::AlignedBox3d light_box;
  for (int c = 0; c < 8; ++c) {
    const Vec3 p = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
    light_box.extend(Vec3(r.dot(p), u.dot(p), f.dot(p)));
  }
  const Vec3 lo = light_box.min(), size = light_box.sizes();
  // world → shadow map (s, t, depth) in [0, 1], and the clip matrix of the same view
  Eigen::Matrix4d to_map = Eigen::Matrix4d::Identity();
  const Vec3 axes[3] = {r, u, f};
  for (int i = 0; i < 3; ++i) {
    to_map.block<1, 3>(i, 0) = axes[i].transpose() / size[i];
    to_map(i, 3) = -lo[i] / size[i];
  }
  Eigen::Matrix4d to_clip = Eigen::Matrix4d::Identity();
  to_clip(0, 0) = to_clip(1, 1) = 2;
  to_clip(0, 3) = to_clip(1, 3) = -1;

  glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_.id());
  const float one = 1.0f;
  glClearNamedFramebufferfv(shadow_fbo_.id(), GL_DEPTH, 0, &one);
  glViewport(0, 0, shadow_size_, shadow_size_);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.5f, 2.0f);
  draw_scene(depth_, depth_model_, (to_clip * to_map).cast<float>(), {RobotIndex(), true});
  glDisable(GL_POLYGON_OFFSET_FILL);

  for (const Program* p : color_programs()) {
    p->set("u_shadow_matrix", Eigen::Matrix4f(to_map.cast<float>()));
    p->set("u_shadow_texel", 1.0f / static_cast<float>(shadow_size_));
    p->set("u_shadow_texel_m", static_cast<float>(std::max(size.x(), size.y()) / shadow_size_));
    p->set("u_shadow_light", shadow_light_);
  }
  shadow_dirty_ = false;
}

void GlRenderer::render_ambient_occlusion(const CameraView& view, const Eigen::Matrix4f& view_proj, ColorTargets& t) {
  const int w = view.k.width, h = view.k.height;
  // single-sample depth of the view, then occlusion from it, then a light blur of the noise
  glBindFramebuffer(GL_FRAMEBUFFER, t.prepass.id());
  const float zero = 0.0f;
  glClearNamedFramebufferfv(t.prepass.id(), GL_DEPTH, 0, &zero);
  camera_pass_state(w, h);
  draw_scene(depth_, depth_model_, view_proj, {view.hide_robot, false});

  glBindFramebuffer(GL_FRAMEBUFFER, t.ao.id());
  image_pass_state(w, h);
  glUseProgram(ssao_.id());
  glProgramUniform4f(ssao_.id(), ssao_.uniform("u_k"), static_cast<float>(view.k.fx), static_cast<float>(view.k.fy),
                     static_cast<float>(view.k.cx), static_cast<float>(view.k.cy));
  ssao_.set("u_clip", Eigen::Vector2f(static_cast<float>(view.near_clip), static_cast<float>(view.far_clip)));
  ssao_.set("u_radius", static_cast<float>(kAoRadius));
  glBindTextureUnit(0, t.prepass_depth.id());
  glBindVertexArray(empty_vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  blur(t.ao_tex.id(), t.ao_tmp.id(), t.ao_tmp_tex.id(), t.ao.id(), w, h, kAoBlurSigma);
}

void GlRenderer::blur(GLuint src_tex, GLuint tmp_fbo, GLuint tmp_tex, GLuint dst_fbo, int width, int height, double sigma) {
  if (sigma != blur_sigma_) {
    const int radius = std::min(kMaxBlurRadius, static_cast<int>(std::ceil(3.0 * sigma)));
    blur_weights_.assign(static_cast<std::size_t>(radius) + 1, 0.0f);
    double sum = 0;
    for (int i = 0; i <= radius; ++i) sum += (i == 0 ? 1.0 : 2.0) * std::exp(-0.5 * i * i / (sigma * sigma));
    for (int i = 0; i <= radius; ++i) {
      blur_weights_[static_cast<std::size_t>(i)] = static_cast<float>(std::exp(-0.5 * i * i / (sigma * sigma)) / sum);
    }
    blur_sigma_ = sigma;
  }
  const int radius = std::max(1, static_cast<int>(blur_weights_.size()) - 1);
  auto it = blur_.find(radius);
  if (it == blur_.end()) {
    Program p("blur", shaders::kFullscreenVertex, fmt::format("#version 450 core\n#define RADIUS {}\n{}", radius, shaders::kBlurFragment));
    p.set("u_src", 0);
    it = blur_.emplace(radius, std::move(p)).first;
  }
  const Program& program = it->second;
  blur_weights_.resize(static_cast<std::size_t>(radius) + 1, 0.0f);
  image_pass_state(width, height);
  glUseProgram(program.id());
  glProgramUniform1fv(program.id(), program.uniform("u_weights"), static_cast<GLsizei>(blur_weights_.size()), blur_weights_.data());
  glBindVertexArray(empty_vao_.id());
  const GLint step = program.uniform("u_step");
  glBindFramebuffer(GL_FRAMEBUFFER, tmp_fbo);
  glProgramUniform2i(program.id(), step, 1, 0);
  glBindTextureUnit(0, src_tex);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindFramebuffer(GL_FRAMEBUFFER, dst_fbo);
  glProgramUniform2i(program.id(), step, 0, 1);
  glBindTextureUnit(0, tmp_tex);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void GlRenderer::do_color(const CameraView& view, ColorImage& out) {
  context_.make_current();
  if (!patterns_) bake_patterns();  // on first use: depth and thermal cameras never need them
  const int w = view.k.width, h = view.k.height;
  SizeTargets& st = targets(w, h);
  if (!st.color) st.color = make_color_targets(w, h, quality());
  ColorTargets& t = *st.color;
  const Eigen::Matrix4f view_proj = view_projection(view);

  // shadows (medium, high) and ambient occlusion (high) before the scene
  const bool shadows = shadow_size_ > 0 && shadow_light_ >= 0;
  if (shadows && shadow_dirty_) render_shadow_map();
  // the media's program only when one is in this view (the window its projection covers)
  const std::array<int, 4> window = fog() ? fog_window(view, view_proj) : std::array<int, 4>{};
  const bool through_media = window[2] > 0 && window[3] > 0;
  const Program& program = color(through_media);
  if (!shadows) program.set("u_shadow_light", -1);
  const bool ao = quality() == Quality::high;
  if (ao) render_ambient_occlusion(view, view_proj, t);

  glBindFramebuffer(GL_FRAMEBUFFER, t.scene.id());
  const float zero = 0.0f;
  glClearNamedFramebufferfv(t.scene.id(), GL_COLOR, 0, sky_.data());
  glClearNamedFramebufferfv(t.scene.id(), GL_DEPTH, 0, &zero);
  camera_pass_state(w, h);
  program.set("u_eye", Eigen::Vector3f(view.X_WC.p.cast<float>()));
  if (through_media) set_fog_eye(program, view.X_WC.p);
  if (shadows) glBindTextureUnit(1, shadow_map_.id());
  if (ao) glBindTextureUnit(2, t.ao_tex.id());
  glBindTextureUnit(3, patterns_.id());
  draw_scene(program, color_model_[color_index(through_media)], view_proj, {view.hide_robot, false});
  if (through_media) draw_fog_sky(view, view_proj, window);

  // anti-aliasing: FXAA into the output (medium) or the multisample resolve (high)
  if (quality() == Quality::medium) {
    glBindFramebuffer(GL_FRAMEBUFFER, t.output.id());
    image_pass_state(w, h);
    glUseProgram(fxaa_.id());
    fxaa_.set("u_texel", Eigen::Vector2f(1.0f / static_cast<float>(w), 1.0f / static_cast<float>(h)));
    glBindTextureUnit(0, t.color_tex.id());
    glBindVertexArray(empty_vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
  } else if (quality() == Quality::high) {
    glBlitNamedFramebuffer(t.scene.id(), t.output.id(), 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, t.readback());
  glNamedFramebufferReadBuffer(t.readback(), GL_COLOR_ATTACHMENT0);
  glReadnPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, static_cast<GLsizei>(out.rgb.size()), out.rgb.data());
}

void GlRenderer::do_depth(const CameraView& view, DepthImage& out) {
  context_.make_current();
  const int w = view.k.width, h = view.k.height;
  SizeTargets& st = targets(w, h);
  if (!st.depth) st.depth = make_depth_targets(w, h);
  DepthTargets& t = *st.depth;
  const GLuint fbo = t.fbo.id();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  const float zero = 0.0f;
  glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &zero);
  camera_pass_state(w, h);
  const Eigen::Matrix4f view_proj = view_projection(view);
  // media out of this view: the clear program, which costs nothing extra. Through media the
  // program flags a lost return in a colour target rather than by writing the depth: a shader
  // that writes depth is run for every fragment, one that does not only for those that pass the
  // early depth test (measured on llvmpipe: 0.75 -> 0.78 of the clear camera's frames/s)
  const std::array<int, 4> window = fog() ? fog_window(view, view_proj) : std::array<int, 4>{};
  const bool through_media = window[2] > 0 && window[3] > 0;
  if (through_media) {
    glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);
    const float clear[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, clear);
    set_fog_eye(depth_fog_, view.X_WC.p);
    draw_scene(depth_fog_, depth_fog_model_, view_proj, {view.hide_robot, false});
    glNamedFramebufferDrawBuffer(fbo, GL_NONE);
  } else {
    draw_scene(depth_, depth_model_, view_proj, {view.hide_robot, false});
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  glReadnPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<GLsizei>(out.z.size() * sizeof(float)), out.z.data());
  if (through_media) {
    t.lost.resize(out.z.size());  // no fill: the read-back writes every flag
    glNamedFramebufferReadBuffer(fbo, GL_COLOR_ATTACHMENT0);
    glReadnPixels(0, 0, w, h, GL_RED, GL_UNSIGNED_BYTE, static_cast<GLsizei>(t.lost.size()), t.lost.data());
    glNamedFramebufferReadBuffer(fbo, GL_NONE);
  } else {
    t.lost.clear();
  }
  // reversed Z: 0 is the far plane (and the clear value), so nothing in view reads +inf; a
  // flagged pixel has lost its return in the media (NaN)
  const double n = view.near_clip, f = view.far_clip;
  for (std::size_t i = 0; i < out.z.size(); ++i) {
    float& d = out.z[i];
    d = !t.lost.empty() && t.lost[i] != 0 ? std::numeric_limits<float>::quiet_NaN()
        : d > 0.0f                        ? static_cast<float>(depth_from_reversed_z(d, n, f))
                                          : std::numeric_limits<float>::infinity();
  }
}

void GlRenderer::do_thermal(const CameraView& view, double blur_sigma_px, ThermalImage& out) {
  context_.make_current();
  const int w = view.k.width, h = view.k.height;
  SizeTargets& st = targets(w, h);
  if (!st.thermal) st.thermal = make_thermal_targets(w, h);
  ThermalTargets& t = *st.thermal;
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo.id());
  const float background[4] = {ambient_temperature_, 0, 0, 0}, zero = 0.0f;
  glClearNamedFramebufferfv(t.fbo.id(), GL_COLOR, 0, background);
  glClearNamedFramebufferfv(t.fbo.id(), GL_DEPTH, 0, &zero);
  camera_pass_state(w, h);
  const Eigen::Matrix4f view_proj = view_projection(view);
  // media out of this view: the clear program, which costs nothing extra
  if (const std::array<int, 4> window = fog() ? fog_window(view, view_proj) : std::array<int, 4>{}; window[2] > 0 && window[3] > 0) {
    set_fog_eye(thermal_fog_, view.X_WC.p);
    thermal_fog_.set("u_ambient", ambient_temperature_);
    draw_scene(thermal_fog_, thermal_fog_model_, view_proj, {view.hide_robot, false});
  } else {
    draw_scene(thermal_, thermal_model_, view_proj, {view.hide_robot, false});
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, t.fbo.id());
  glNamedFramebufferReadBuffer(t.fbo.id(), GL_COLOR_ATTACHMENT0);
  glReadnPixels(0, 0, w, h, GL_RED, GL_FLOAT, static_cast<GLsizei>(out.kelvin.size() * sizeof(float)), out.kelvin.data());
  // the optics' blur on the CPU: on llvmpipe two float render passes cost several times more
  gaussian_blur(out.kelvin, w, h, blur_sigma_px);
}

}  // namespace

std::unique_ptr<Renderer> make_headless_renderer(Quality q) { return std::make_unique<GlRenderer>(q); }

}  // namespace rescuesim::gl
