#pragma once
/// GLSL 4.50 sources of every pass, as C++ raw strings (shaders.cpp, colour_shader.cpp).

namespace rescuesim::gl::shaders {

/// Scene vertex stage: attributes position, normal, uv (m), material, apparent temperature (K);
/// uniforms u_view_proj (world → clip) and u_model (item → world).
extern const char* const kSceneVertex;
/// Position-only vertex stage for depth passes (same uniforms).
extern const char* const kDepthVertex;
/// Writes nothing: the depth buffer is the result.
extern const char* const kDepthFragment;
/// Writes the vertex's apparent temperature (K) to an R32F target.
extern const char* const kThermalFragment;
/// Colour stages. They have no #version line: compose "#version 450 core", the defines
/// LIGHTS (number of lights, 0..4), PER_PIXEL, SHADOWS and AO (0 or 1), kLightUniforms, then the
/// stage. Low quality: kGouraudVertex + kColorFragment with PER_PIXEL 0; medium and high:
/// kSceneVertex (which has its own #version) + kColorFragment with PER_PIXEL 1. The fragment
/// writes sRGB with luma in alpha (for FXAA).
extern const char* const kLightUniforms;
extern const char* const kGouraudVertex;
extern const char* const kColorFragment;
/// Bakes one layer of surface patterns as albedo multipliers / 2, repeating every u_period
/// metres, at u_size texels across. No #version line: prepend it and "#define KIND n" (TextureKind).
extern const char* const kPatternFragment;
/// A triangle covering the viewport, from gl_VertexID (draw 3 vertices, no attributes).
extern const char* const kFullscreenVertex;
/// One direction of a separable Gaussian blur of the red channel (u_src, u_step, u_weights). No
/// #version line: prepend it and "#define RADIUS n" (taps each side, ≥ 1).
extern const char* const kBlurFragment;
/// Fast approximate anti-aliasing of an sRGB image with luma in alpha (u_src, u_texel).
extern const char* const kFxaaFragment;
/// Screen-space ambient occlusion from a reversed-Z depth texture (1 = open, 0 = occluded).
extern const char* const kSsaoFragment;
/// Smoke and dust (media_shader.cpp). kFogFunctions declares the media's uniforms and
/// fog_depth(d), the optical depths of the segment from the camera to camera + d; compose
/// "#version 450 core", "#define MEDIA 1", MEDIA_PIECES (general convex pieces), MEDIA_SIDES
/// (sides of each, ≥ 1) and MEDIA_BOXES (axis-aligned boxes), it, then a stage. The colour
/// fragment fogs itself when MEDIA is 1; kFogSkyFragment fogs the sky (a full-screen pass where
/// the depth is still the clear value); kDepthFogFragment and kThermalFogFragment follow
/// kFogVertex for the depth and thermal cameras.
extern const char* const kFogFunctions;
/// Vertex stage of kDepthFogFragment and kThermalFogFragment: v_world and v_temperature only.
extern const char* const kFogVertex;
extern const char* const kFogSkyFragment;
extern const char* const kDepthFogFragment;
extern const char* const kThermalFogFragment;
/// The bare benchmark loop's shaders: position in, flat colour out.
extern const char* const kBareVertex;
extern const char* const kBareFragment;

}  // namespace rescuesim::gl::shaders
