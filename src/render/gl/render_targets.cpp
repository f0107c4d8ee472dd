#include "render/gl/render_targets.h"

namespace rescuesim::gl {

namespace {

constexpr int kMsaaSamples = 4;

/// A framebuffer with one colour texture attachment.
Framebuffer texture_fbo(const Texture& t) {
  Framebuffer f = Framebuffer::create();
  glNamedFramebufferTexture(f.id(), GL_COLOR_ATTACHMENT0, t.id(), 0);
  return f;
}

}  // namespace

std::unique_ptr<ColorTargets> make_color_targets(int w, int h, Quality q) {
  auto out = std::make_unique<ColorTargets>();
  ColorTargets& t = *out;
  t.scene = Framebuffer::create();
  const int samples = q == Quality::high ? kMsaaSamples : 0;
  t.depth_rb = Renderbuffer::create(GL_DEPTH_COMPONENT32F, w, h, samples);
  glNamedFramebufferRenderbuffer(t.scene.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t.depth_rb.id());
  if (q == Quality::medium) {
    // the scene into a texture FXAA can filter, FXAA into a plain renderbuffer
    t.color_tex = Texture::create_2d(GL_RGBA8, w, h);
    glTextureParameteri(t.color_tex.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t.color_tex.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glNamedFramebufferTexture(t.scene.id(), GL_COLOR_ATTACHMENT0, t.color_tex.id(), 0);
  } else {
    t.color_rb = Renderbuffer::create(GL_RGBA8, w, h, samples);
    glNamedFramebufferRenderbuffer(t.scene.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.color_rb.id());
  }
  t.scene.check_complete("colour");
  if (q != Quality::low) {
    t.output = Framebuffer::create();
    t.output_rb = Renderbuffer::create(GL_RGBA8, w, h);
    glNamedFramebufferRenderbuffer(t.output.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.output_rb.id());
    t.output.check_complete("colour output");
  }
  if (q == Quality::high) {
    t.prepass = Framebuffer::create();
    t.prepass_depth = Texture::create_2d(GL_DEPTH_COMPONENT32F, w, h);
    glNamedFramebufferTexture(t.prepass.id(), GL_DEPTH_ATTACHMENT, t.prepass_depth.id(), 0);
    glNamedFramebufferDrawBuffer(t.prepass.id(), GL_NONE);
    t.prepass.check_complete("depth prepass");
    t.ao_tex = Texture::create_2d(GL_R8, w, h);
    t.ao_tmp_tex = Texture::create_2d(GL_R8, w, h);
    t.ao = texture_fbo(t.ao_tex);
    t.ao_tmp = texture_fbo(t.ao_tmp_tex);
    t.ao.check_complete("ambient occlusion");
  }
  return out;
}

std::unique_ptr<DepthTargets> make_depth_targets(int w, int h) {
  auto out = std::make_unique<DepthTargets>();
  DepthTargets& t = *out;
  t.fbo = Framebuffer::create();
  t.depth_rb = Renderbuffer::create(GL_DEPTH_COMPONENT32F, w, h);
  glNamedFramebufferRenderbuffer(t.fbo.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t.depth_rb.id());
  t.lost_rb = Renderbuffer::create(GL_R8, w, h);
  glNamedFramebufferRenderbuffer(t.fbo.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.lost_rb.id());
  glNamedFramebufferDrawBuffer(t.fbo.id(), GL_NONE);
  glNamedFramebufferReadBuffer(t.fbo.id(), GL_NONE);
  t.fbo.check_complete("depth");
  return out;
}

std::unique_ptr<ThermalTargets> make_thermal_targets(int w, int h) {
  auto out = std::make_unique<ThermalTargets>();
  ThermalTargets& t = *out;
  t.kelvin = Texture::create_2d(GL_R32F, w, h);
  t.fbo = texture_fbo(t.kelvin);
  t.depth_rb = Renderbuffer::create(GL_DEPTH_COMPONENT32F, w, h);
  glNamedFramebufferRenderbuffer(t.fbo.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t.depth_rb.id());
  t.fbo.check_complete("thermal");
  return out;
}

}  // namespace rescuesim::gl
