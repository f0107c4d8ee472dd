// The camera shaders' smoke and dust: the optical depth of a ray through the media's convex
// prisms (render/fog_volumes.h), and the passes that use it — the colour camera's fog over the
// sky, the depth camera losing its return, the thermal camera's slight attenuation. The physics
// is in docs/environment.md ("Cameras").

#include "render/gl/shaders.h"

namespace rescuesim::gl::shaders {

const char* const kFogFunctions = R"(
#if MEDIA_PIECES > 0
// u_fog_edge: (nx, ny, s), a side n.p <= c of a piece's footprint as s = n.eye - c for this view (m)
uniform vec4 u_fog_edge[MEDIA_PIECES * MEDIA_SIDES];
uniform vec4 u_fog_slab[MEDIA_PIECES];                // bottom - eye z, top - eye z (m)
uniform vec4 u_fog_sigma[MEDIA_PIECES];               // extinction (1/m): visible, near infrared, long-wave infrared; scattering albedo
#endif
#if MEDIA_BOXES > 0
uniform vec4 u_fog_box_axis[MEDIA_BOXES];             // a box's axis u (xy, a unit vector): its frame is (u, u turned 90 deg, z)
uniform vec4 u_fog_box_lo[MEDIA_BOXES];               // its low corner - eye, in its frame (m)
uniform vec4 u_fog_box_hi[MEDIA_BOXES];               // its high corner - eye, in its frame (m)
uniform vec4 u_fog_box_sigma[MEDIA_BOXES];            // as u_fog_sigma
#endif

// Optical depths of the segment from the camera (the eye of the uniforms above) to eye + d:
// visible, near infrared, long-wave infrared, and in w the visible depth weighted by each
// medium's scattering albedo. A box (a rectangular footprint, turned or not) clips the segment
// with the inverse of d in its own frame (three slabs: a rotation of d and no division of its
// own; for a box along the world's axes the rotation is exact and changes nothing); any other
// piece against its floor-to-top slab and its sides (Cyrus-Beck, a division per side). Every
// piece has MEDIA_SIDES sides (padded with ones that hold everything), so the loops have
// constant bounds and constant uniform indices.
// Every fragment of a program with media pays for this, so the cameras take their clear
// programs when no medium is in view, and the sky pass is scissored to the media's window. A
// window test here (skip pixels outside it) was slower, not faster, on llvmpipe, which runs both
// sides of a branch that differs across its SIMD lanes: colour through smoke 0.77 -> 0.82 of
// the clear camera without it.
// fog_fraction is the same per metre of the segment (the extinctions times the fraction of the
// segment inside each piece): the depth camera compares its square, which needs no square root.
vec4 fog_fraction(vec3 d) {
  vec4 sum = vec4(0.0);
#if MEDIA_BOXES > 0
  for (int i = 0; i < MEDIA_BOXES; ++i) {
    vec2 u = u_fog_box_axis[i].xy;
    vec3 db = vec3(u.x * d.x + u.y * d.y, u.x * d.y - u.y * d.x, d.z);
    vec3 inv = 1.0 / vec3(abs(db.x) > 1e-9 ? db.x : 1e-9, abs(db.y) > 1e-9 ? db.y : 1e-9, abs(db.z) > 1e-9 ? db.z : 1e-9);
    vec3 a = u_fog_box_lo[i].xyz * inv, b = u_fog_box_hi[i].xyz * inv;
    vec3 near = min(a, b), far = max(a, b);
    float t0 = max(max(near.x, near.y), max(near.z, 0.0)), t1 = min(min(far.x, far.y), min(far.z, 1.0));
    vec4 s = u_fog_box_sigma[i];
    sum += vec4(s.xyz, s.x * s.w) * max(t1 - t0, 0.0);
  }
#endif
#if MEDIA_PIECES > 0
  float inv_dz = abs(d.z) > 1e-9 ? 1.0 / d.z : 1e9;
  for (int i = 0; i < MEDIA_PIECES; ++i) {
    vec2 slab = u_fog_slab[i].xy * inv_dz;
    float t0 = max(0.0, min(slab.x, slab.y)), t1 = min(1.0, max(slab.x, slab.y));
    for (int e = 0; e < MEDIA_SIDES; ++e) {
      vec4 h = u_fog_edge[i * MEDIA_SIDES + e];
      float ds = dot(h.xy, d.xy);
      float t = -h.z / ds;               // +-inf when parallel: then only the sign of s decides
      t1 = ds > 0.0 ? min(t1, t) : t1;
      t0 = ds < 0.0 ? max(t0, t) : t0;
      t1 = (ds == 0.0 && h.z > 0.0) ? -1.0 : t1;
    }
    vec4 s = u_fog_sigma[i];
    sum += vec4(s.xyz, s.x * s.w) * max(t1 - t0, 0.0);
  }
#endif
  return sum;
}

vec4 fog_depth(vec3 d) { return fog_fraction(d) * length(d); }
)";

// the depth and thermal cameras' vertex stage through media: the world position, and the
// apparent temperature for the thermal camera (the scene vertex's other outputs would cost a CPU
// rasteriser their interpolation)
const char* const kFogVertex = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 4) in float a_temperature;
uniform mat4 u_view_proj;
uniform mat4 u_model;
uniform vec3 u_eye;
invariant gl_Position;
out vec3 v_ray;  // from the eye to the vertex (m): the fragments' segment through the media
flat out float v_temperature;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_ray = world.xyz - u_eye;
  v_temperature = a_temperature;
  gl_Position = u_view_proj * world;
}
)";

// No #version: "#version 450 core", MEDIA, MEDIA_PIECES, MEDIA_SIDES, MEDIA_BOXES, kFogFunctions, then this.
const char* const kFogSkyFragment = R"(
uniform mat4 u_inv_view_proj;  // clip -> world of the camera
uniform vec2 u_size;           // px
uniform vec3 u_eye;            // m
uniform vec3 u_sky;            // linear
uniform vec3 u_fog_light;      // light on the media, as a white matte surface reflects it (linear)
layout(location = 0) out vec4 o_color;

vec3 to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// where nothing was drawn: the sky seen through the media up to the far clip plane (reversed Z: depth 0)
void main() {
  vec4 far = u_inv_view_proj * vec4(2.0 * gl_FragCoord.xy / u_size - 1.0, 0.0, 1.0);
  vec4 tau = fog_depth(far.xyz / far.w - u_eye);
  float t = exp(-tau.x);
  vec3 air = tau.x > 0.0 ? u_fog_light * (tau.w / tau.x) : vec3(0.0);
  vec3 encoded = to_srgb(u_sky * t + air * (1.0 - t));
  o_color = vec4(encoded, dot(encoded, vec3(0.299, 0.587, 0.114)));
}
)";

// No #version (as above). The depth camera's light goes out and back through the media: a pixel
// whose two-way transmittance exp(-2 tau) falls below the least return has none, flagged 1 in the
// pass's R8 target (the read-back turns it into NaN). The depth itself is left to the fixed
// function, so the early depth test still skips hidden fragments.
const char* const kDepthFogFragment = R"(
in vec3 v_ray;
uniform float u_lost_depth_squared;  // (ln(1 / the least return) / 2)^2: a one-way optical depth past its root loses the return
layout(location = 0) out float o_lost;
void main() {
  float per_metre = fog_fraction(v_ray).y;
  o_lost = per_metre * per_metre * dot(v_ray, v_ray) > u_lost_depth_squared ? 1.0 : 0.0;
}
)";

// No #version (as above). The thermal camera sees the surface through the media's long-wave
// extinction and the media's own emission at the ambient temperature.
const char* const kThermalFogFragment = R"(
flat in float v_temperature;
in vec3 v_ray;
uniform float u_ambient;
layout(location = 0) out float o_kelvin;
void main() { o_kelvin = mix(u_ambient, v_temperature, exp(-fog_depth(v_ray).z)); }
)";

}  // namespace rescuesim::gl::shaders
