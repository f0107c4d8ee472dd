// The colour pass's shaders. Surface patterns are baked once per renderer into a mipmapped
// texture array (one layer per TextureKind, repeating every kPatternPeriod metres), because a
// CPU rasteriser runs every branch of a shader for every pixel: one filtered texture fetch per
// pixel replaces five procedural patterns, and the mipmaps do their anti-aliasing. Lighting is
// hemisphere ambient with contact darkening (or SSAO at high), a fill light, the scene's lights
// with Blinn-Phong highlights and, at medium and high, a PCF-filtered shadow map.

#include "render/gl/shaders.h"

namespace rescuesim::gl::shaders {

// compiled once per layer with KIND defined (a CPU rasteriser would run every branch)
const char* const kPatternFragment = R"(
uniform float u_period;    // metres covered by the layer (every pattern repeats exactly)
uniform float u_size;      // texels across
layout(location = 0) out vec4 o_factor;  // albedo multiplier / 2 per channel

uint pcg(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
float hash(ivec2 p) { return float(pcg(uint(p.x) * 1597334677u ^ pcg(uint(p.y)))) * (1.0 / 4294967296.0); }

// value noise on a lattice of n cells per period, wrapped so the layer tiles seamlessly
float value_noise(vec2 uv, float freq) {
  int n = int(round(freq * u_period));
  vec2 p = uv * float(n) / u_period;
  ivec2 i = ivec2(floor(p));
  vec2 f = fract(p);
  vec2 w = f * f * (3.0 - 2.0 * f);
  ivec2 a = ((i % n) + n) % n, b = (((i + 1) % n) + n) % n;
  return mix(mix(hash(a), hash(ivec2(b.x, a.y)), w.x), mix(hash(ivec2(a.x, b.y)), hash(b), w.x), w.y);
}

float fbm(vec2 uv, float freq, int octaves) {
  float sum = 0.0, amp = 0.5, norm = 0.0;
  for (int o = 0; o < octaves; ++o) {
    sum += amp * value_noise(uv + float(o) * 0.37, freq);
    norm += amp;
    amp *= 0.5;
    freq *= 2.0;
  }
  return sum / norm;
}

float line(float e, float half_width, float texel) { return 1.0 - smoothstep(half_width - 0.5 * texel, half_width + 0.5 * texel, e); }

// 0.5 m floor tiles with 8 mm grout, each tile its own shade, mottled
vec3 tiles(vec2 uv, float texel) {
  vec2 t = uv / 0.5;
  vec2 f = fract(t);
  float e = min(min(f.x, 1.0 - f.x), min(f.y, 1.0 - f.y)) * 0.5;
  float shade = 0.86 + 0.28 * hash(ivec2(floor(t)) & 1023);
  return vec3(mix(shade * (0.78 + 0.44 * fbm(uv, 5.0, 4)), 0.3, line(e, 0.004, texel)));
}

// cast concrete: blotches from 3 cycles/m down to centimetres, small dark pores
vec3 concrete(vec2 uv, float texel) {
  float pores = smoothstep(0.8, 0.88, value_noise(uv, 90.0));
  return vec3((1.0 + 0.7 * (fbm(uv, 3.0, 5) - 0.5)) * (1.0 - 0.4 * pores));
}

// 12.5 cm planks along u with butt joints every metre, wavy grain
vec3 wood(vec2 uv, float texel) {
  float row = floor(uv.y / 0.125);
  float offset = hash(ivec2(int(row) & 1023, 7));
  float across = fract(uv.y / 0.125);
  float x = uv.x + offset;
  float seam = max(line(min(across, 1.0 - across) * 0.125, 0.0015, texel), line(abs(fract(x + 0.5) - 0.5), 0.0015, texel));
  float warp = fbm(vec2(uv.x, uv.y * 4.0), 1.0, 3);
  float grain = 0.5 + 0.5 * sin(6.2831853 * (uv.y * 56.0 + warp * 4.0 + offset * 8.0));
  float shade = 0.85 + 0.3 * hash(ivec2(int(row) & 1023, 3));
  return vec3(mix(shade * mix(0.78, 1.12, grain), 0.35, seam));
}

// plain weave of 12.5 mm threads over soft folds
vec3 fabric(vec2 uv, float texel) {
  vec2 t = uv / 0.0125;
  ivec2 cell = ivec2(floor(t));
  vec2 f = fract(t);
  float thread = ((cell.x + cell.y) & 1) == 0 ? sin(3.1415927 * f.x) : sin(3.1415927 * f.y);
  return vec3((0.72 + 0.35 * thread) * (0.75 + 0.5 * fbm(uv, 2.5, 3)));
}

// skin: fine mottling and slightly redder blotches
vec3 skin(vec2 uv, float texel) {
  float blot = fbm(uv + 0.5, 4.0, 2) - 0.5;
  return (0.9 + 0.2 * fbm(uv, 12.0, 3)) * vec3(1.0 + 0.1 * blot, 1.0, 1.0 - 0.06 * blot);
}

vec3 pattern(vec2 uv, float texel) {
#if KIND == 1
  return tiles(uv, texel);
#elif KIND == 2
  return concrete(uv, texel);
#elif KIND == 3
  return wood(uv, texel);
#elif KIND == 4
  return fabric(uv, texel);
#elif KIND == 5
  return skin(uv, texel);
#else
  return vec3(1.0);
#endif
}

void main() {
  // 2 x 2 samples per texel
  float texel = u_period / u_size;
  vec3 sum = vec3(0.0);
  for (int i = 0; i < 4; ++i) {
    vec2 offset = vec2(float(i & 1), float(i >> 1)) * 0.5 - 0.25;
    sum += pattern((gl_FragCoord.xy + offset) * texel, 0.5 * texel);
  }
  o_factor = vec4(clamp(0.125 * sum, 0.0, 1.0), 1.0);
}
)";

// the lights, shared by both colour stages: the scene's lights and a fill light from the other side
const char* const kLightUniforms = R"(
uniform vec3 u_eye;                      // camera position, world (m)
uniform vec3 u_sky_ambient;              // ambient light from above (linear)
uniform vec3 u_ground_ambient;           // ambient light from below
uniform vec4 u_light[8];                 // w = 0: direction the light travels; w = 1: position (m)
uniform vec3 u_light_color[8];
uniform vec4 u_light_cone[8];            // spot: unit axis the light shines along, cos of the cone's edge (< -1: no cone)
uniform vec4 u_light_shape[8];           // cos of the fully lit core; 1 / range^2 (0: unlimited)
uniform vec3 u_fill_dir;                 // unit, towards the fill light
uniform vec3 u_fill_color;

// sky from above, bounce from below
vec3 ambient(vec3 n) { return mix(u_ground_ambient, u_sky_ambient, 0.5 + 0.5 * n.z); }
vec3 to_light(int i, vec3 p) {
  vec3 d = u_light[i].xyz - p * u_light[i].w;
  return u_light[i].w == 0.0 ? -normalize(d) : normalize(d);
}
// a point light falls off as 1/d^2, times a window that takes it smoothly to 0 at its range
// ((1 - (d/range)^4)^2, as Filament and Unreal do), times its cone: 1 in the core, 0 outside the edge
vec3 radiance(int i, vec3 p) {
  if (u_light[i].w == 0.0) return u_light_color[i];
  vec3 d = u_light[i].xyz - p;
  float d2 = max(dot(d, d), 0.01);
  float x = d2 * u_light_shape[i].y;
  float window = clamp(1.0 - x * x, 0.0, 1.0);
  float cone = smoothstep(u_light_cone[i].w, u_light_shape[i].x, dot(-d, u_light_cone[i].xyz) * inversesqrt(d2));
  return u_light_color[i] * (cone * window * window / d2);
}
)";

// per-vertex (Gouraud) lighting for the low quality: diffuse light is exact on flat faces lit by
// directional lights, and a CPU rasteriser shades several times faster without per-pixel loops
const char* const kGouraudVertex = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in float a_material;
uniform mat4 u_view_proj;
uniform mat4 u_model;
invariant gl_Position;
out float v_height;
out float v_upright;
#if MEDIA
out vec3 v_ray;  // from the eye to the vertex (m): the fragment's segment through the media
#endif
out vec2 v_uv;
out vec3 v_ambient;
out vec3 v_direct;
flat out int v_material;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  vec3 n = normalize(mat3(u_model) * a_normal);
#if MEDIA
  v_ray = world.xyz - u_eye;
#endif
  v_height = world.z;
  v_upright = 1.0 - abs(n.z);
  v_uv = a_uv;
  v_material = int(a_material + 0.5);
  v_ambient = ambient(n);
  v_direct = u_fill_color * max(dot(n, u_fill_dir), 0.0);
  for (int i = 0; i < LIGHTS; ++i) v_direct += radiance(i, world.xyz) * max(dot(n, to_light(i, world.xyz)), 0.0);
  gl_Position = u_view_proj * world;
}
)";

// the fragment stage of both variants; PER_PIXEL 0 takes light from the Gouraud vertex stage
const char* const kColorFragment = R"(
layout(location = 0) out vec4 o_color;
const int kMaxMaterials = 64;
uniform vec4 u_material[kMaxMaterials];  // linear albedo, roughness
uniform float u_layer[kMaxMaterials];    // pattern layer (TextureKind), or an image's (from kImageLayer on)
uniform sampler2DArray u_patterns;       // albedo multipliers / 2, repeating every u_period; then images' albedo / 2
const float kImageLayer = 6.0;           // the first image layer (after the TextureKind patterns)
uniform float u_period;                  // m
flat in int v_material;
in vec2 v_uv;
#if PER_PIXEL
in vec3 v_world;
in vec3 v_normal;
#else
in float v_height;
in float v_upright;
in vec3 v_ambient;
in vec3 v_direct;
#if MEDIA
in vec3 v_ray;
#endif
#endif
#if MEDIA
uniform vec3 u_fog_light;                // light on the media, as a white matte surface reflects it (linear)

// the surface seen through the media: dimmed by exp(-tau) and veiled by the light they scatter
// towards the camera (the airlight: their albedo times the light on them)
vec3 fogged(vec3 color, vec3 ray) {
  vec4 tau = fog_depth(ray);
  float t = exp(-tau.x);
  vec3 air = tau.x > 0.0 ? u_fog_light * (tau.w / tau.x) : vec3(0.0);
  return color * t + air * (1.0 - t);
}
#endif
#if SHADOWS
uniform int u_shadow_light;              // light with the shadow map, -1 = none
uniform sampler2DShadow u_shadow_map;
uniform mat4 u_shadow_matrix;            // world -> shadow map (s, t, depth) in [0, 1]
uniform float u_shadow_texel;            // 1 / shadow map size
uniform float u_shadow_texel_m;          // one shadow texel in metres

// fraction of the shadow-casting light reaching this point: four bilinear comparisons half a
// texel apart (PCF over 3 x 3 texels), looked up from a point pushed out along the normal against acne
float sunlit(vec3 n, vec3 l) {
  float slope = 1.0 - max(dot(n, l), 0.0);
  vec4 s = u_shadow_matrix * vec4(v_world + n * u_shadow_texel_m * (1.0 + 2.0 * slope), 1.0);
  float sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    vec2 offset = (vec2(float(i & 1), float(i >> 1)) - 0.5) * u_shadow_texel;
    sum += texture(u_shadow_map, vec3(s.xy + offset, s.z - 0.0005));
  }
  bool outside = any(lessThan(s.xy, vec2(0.0))) || any(greaterThan(s.xy, vec2(1.0))) || s.z > 1.0;
  return outside ? 1.0 : 0.25 * sum;
}
#endif
#if AO
uniform sampler2D u_ao;                  // screen-space ambient occlusion of this view
#endif

vec3 to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// ambient darkened low on upright surfaces, where they meet the floor
float contact(float height, float upright) { return mix(1.0, mix(0.6, 1.0, smoothstep(0.0, 0.3, height)), upright); }

void main() {
  int m = clamp(v_material, 0, kMaxMaterials - 1);
  // patterns repeat in metres along the surface; an image spans its mesh's texture coordinates
  vec2 st = u_layer[m] >= kImageLayer ? v_uv : v_uv / u_period;
  vec3 albedo = u_material[m].rgb * 2.0 * texture(u_patterns, vec3(st, u_layer[m])).rgb;
#if PER_PIXEL
  vec3 n = normalize(v_normal);
  vec3 to_eye = normalize(u_eye - v_world);
  float occlusion = contact(v_world.z, 1.0 - abs(n.z));
#if AO
  occlusion = min(occlusion, texelFetch(u_ao, ivec2(gl_FragCoord.xy), 0).r);
#endif
  vec3 color = albedo * (ambient(n) * occlusion + u_fill_color * max(dot(n, u_fill_dir), 0.0) * mix(0.7, 1.0, occlusion));
  // direct lights with Blinn-Phong highlights of a dielectric (4 % reflectance)
  float alpha = max(u_material[m].a * u_material[m].a, 0.02);
  float shininess = clamp(2.0 / (alpha * alpha) - 2.0, 2.0, 256.0);
  for (int i = 0; i < LIGHTS; ++i) {
    vec3 l = to_light(i, v_world);
    vec3 e = radiance(i, v_world);
#if SHADOWS
    if (i == u_shadow_light) e *= sunlit(n, l);
#endif
    vec3 h = normalize(l + to_eye);
    float spec = 0.04 * (shininess + 8.0) / 25.1327 * pow(max(dot(n, h), 0.0), shininess);
    color += e * max(dot(n, l), 0.0) * (albedo + spec);
  }
#else
  vec3 color = albedo * (v_ambient * contact(v_height, v_upright) + v_direct);
#endif
#if MEDIA && PER_PIXEL
  color = fogged(color, v_world - u_eye);
#elif MEDIA
  color = fogged(color, v_ray);
#endif
  vec3 encoded = to_srgb(color);
  o_color = vec4(encoded, dot(encoded, vec3(0.299, 0.587, 0.114)));
}
)";

}  // namespace rescuesim::gl::shaders
