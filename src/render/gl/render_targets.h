#pragma once
/// Off-screen targets of one image size, created on first use by each kind of pass and kept
/// for the next frame of that size (a camera renders the same size over and over).

#include <cstdint>
#include <memory>
#include <vector>

#include "render/gl/gl_objects.h"
#include "render/renderer.h"

namespace rescuesim::gl {

/// Colour pass targets for one quality.
struct ColorTargets {
  Framebuffer scene;           ///< where the scene is drawn (multisampled at high)
  Renderbuffer color_rb, depth_rb;
  Texture color_tex;           ///< medium: the scene's colour, input of FXAA
  Framebuffer output;          ///< medium: FXAA result; high: MSAA resolve
  Renderbuffer output_rb;
  Framebuffer prepass;         ///< high: single-sample depth for SSAO
  Texture prepass_depth;
  Framebuffer ao, ao_tmp;      ///< high: occlusion and its blur
  Texture ao_tex, ao_tmp_tex;

  /// The framebuffer to read the finished image from.
  GLuint readback() const { return output ? output.id() : scene.id(); }
};

/// Depth pass targets: a 32-bit float depth buffer, and an R8 flag per pixel for the pass through
/// smoke (1 where the return is lost), drawn to only by that pass: the clear pass has no colour
/// output at all.
struct DepthTargets {
  Framebuffer fbo;
  Renderbuffer depth_rb;
  Renderbuffer lost_rb;
  std::vector<std::uint8_t> lost;  ///< the flags read back, row by row from the bottom
};

/// Thermal pass targets: kelvin (R32F) with depth (the blur runs on the CPU after readback).
struct ThermalTargets {
  Framebuffer fbo;
  Texture kelvin;
  Renderbuffer depth_rb;
};

/// All targets of one size.
struct SizeTargets {
  int width = 0, height = 0;
  std::unique_ptr<ColorTargets> color;
  std::unique_ptr<DepthTargets> depth;
  std::unique_ptr<ThermalTargets> thermal;
};

std::unique_ptr<ColorTargets> make_color_targets(int width, int height, Quality q);
std::unique_ptr<DepthTargets> make_depth_targets(int width, int height);
std::unique_ptr<ThermalTargets> make_thermal_targets(int width, int height);

}  // namespace rescuesim::gl
