// Shaders of the geometry passes (depth, thermal), the image passes (blur, FXAA, SSAO) and the
// bare benchmark loop. The colour pass's fragment shader is in colour_shader.cpp.

#include "render/gl/shaders.h"

namespace rescuesim::gl::shaders {

const char* const kSceneVertex = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in float a_material;
layout(location = 4) in float a_temperature;
uniform mat4 u_view_proj;
uniform mat4 u_model;
invariant gl_Position;
out vec3 v_world;
out vec3 v_normal;
out vec2 v_uv;
flat out int v_material;
flat out float v_temperature;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = mat3(u_model) * a_normal;
  v_uv = a_uv;
  v_material = int(a_material + 0.5);
  v_temperature = a_temperature;
  gl_Position = u_view_proj * world;
}
)";

const char* const kDepthVertex = R"(#version 450 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_proj;
uniform mat4 u_model;
invariant gl_Position;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  gl_Position = u_view_proj * world;
}
)";

const char* const kDepthFragment = R"(#version 450 core
void main() {}
)";

const char* const kThermalFragment = R"(#version 450 core
flat in float v_temperature;
layout(location = 0) out float o_kelvin;
void main() { o_kelvin = v_temperature; }
)";

const char* const kFullscreenVertex = R"(#version 450 core
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
)";

// compiled per radius (RADIUS taps each side): a CPU rasteriser runs a fixed loop far faster
const char* const kBlurFragment = R"(
uniform sampler2D u_src;
uniform ivec2 u_step;         // (1, 0) across, (0, 1) down
uniform float u_weights[RADIUS + 1];  // normalised Gaussian weights, centre first
layout(location = 0) out float o_value;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(u_src, 0) - 1;
  float sum = u_weights[0] * texelFetch(u_src, p, 0).r;
  // edges repeat the border pixel, as a camera's optics would see more of the same surface
  for (int i = 1; i <= RADIUS; ++i) {
    float a = texelFetch(u_src, clamp(p + i * u_step, ivec2(0), last), 0).r;
    float b = texelFetch(u_src, clamp(p - i * u_step, ivec2(0), last), 0).r;
    sum += u_weights[i] * (a + b);
  }
  o_value = sum;
}
)";

const char* const kFxaaFragment = R"(#version 450 core
uniform sampler2D u_src;  // sRGB colour, luma in alpha, bilinear
uniform vec2 u_texel;     // 1 / size
layout(location = 0) out vec4 o_color;
const float kReduceMul = 1.0 / 8.0;
const float kReduceMin = 1.0 / 128.0;
const float kSpanMax = 8.0;
void main() {
  vec2 uv = gl_FragCoord.xy * u_texel;
  vec4 centre = texture(u_src, uv);
  float nw = texture(u_src, uv + vec2(-1.0, -1.0) * u_texel).a;
  float ne = texture(u_src, uv + vec2(1.0, -1.0) * u_texel).a;
  float sw = texture(u_src, uv + vec2(-1.0, 1.0) * u_texel).a;
  float se = texture(u_src, uv + vec2(1.0, 1.0) * u_texel).a;
  float m = centre.a;
  float lo = min(m, min(min(nw, ne), min(sw, se)));
  float hi = max(m, max(max(nw, ne), max(sw, se)));
  // the edge runs across the steepest luma change; blur along it, not across
  vec2 dir = vec2(-((nw + ne) - (sw + se)), (nw + sw) - (ne + se));
  float reduce = max((nw + ne + sw + se) * 0.25 * kReduceMul, kReduceMin);
  float scale = 1.0 / (min(abs(dir.x), abs(dir.y)) + reduce);
  dir = clamp(dir * scale, vec2(-kSpanMax), vec2(kSpanMax)) * u_texel;
  vec3 inner = 0.5 * (texture(u_src, uv + dir * (1.0 / 3.0 - 0.5)).rgb + texture(u_src, uv + dir * (2.0 / 3.0 - 0.5)).rgb);
  vec3 outer = 0.5 * inner + 0.25 * (texture(u_src, uv - 0.5 * dir).rgb + texture(u_src, uv + 0.5 * dir).rgb);
  float luma = dot(outer, vec3(0.299, 0.587, 0.114));
  o_color = vec4((luma < lo || luma > hi) ? inner : outer, 1.0);
}
)";

const char* const kSsaoFragment = R"(#version 450 core
uniform sampler2D u_depth;  // reversed-Z window depth of the camera
uniform vec4 u_k;           // fx, fy, cx, cy (px)
uniform vec2 u_clip;        // near, far (m)
uniform float u_radius;     // sampling radius (m)
layout(location = 0) out float o_ao;
const int kSamples = 12;

// window texel (i, j) is image pixel (u = i, v = j): the projection puts row v at y = v + 0.5
vec3 optical_point(ivec2 p) {
  float d = texelFetch(u_depth, p, 0).r;
  float z = d <= 0.0 ? 1e6 : u_clip.x * u_clip.y / ((u_clip.y - u_clip.x) * d + u_clip.x);
  return vec3((float(p.x) - u_k.z) / u_k.x * z, (float(p.y) - u_k.w) / u_k.y * z, z);
}

uint pcg(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(u_depth, 0) - 1;
  vec3 c = optical_point(p);
  if (c.z > u_clip.y) { o_ao = 1.0; return; }
  // normal from the flatter side of each neighbour pair, so silhouettes do not bend it
  vec3 dx1 = optical_point(min(p + ivec2(1, 0), last)) - c, dx0 = c - optical_point(max(p - ivec2(1, 0), ivec2(0)));
  vec3 dy1 = optical_point(min(p + ivec2(0, 1), last)) - c, dy0 = c - optical_point(max(p - ivec2(0, 1), ivec2(0)));
  vec3 dx = abs(dx1.z) < abs(dx0.z) ? dx1 : dx0;
  vec3 dy = abs(dy1.z) < abs(dy0.z) ? dy1 : dy0;
  vec3 n = normalize(cross(dx, dy));
  if (dot(n, c) > 0.0) n = -n;
  // a per-pixel rotation of a fixed spiral of sample directions (4 × 4 interleaved pattern)
  float angle = 6.2831853 * float(pcg(uint(p.x & 3) + 4u * uint(p.y & 3)) & 1023u) / 1024.0;
  float occluded = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    float t = (float(i) + 0.5) / float(kSamples);
    float phi = angle + 2.39996323 * float(i);
    float cz = 1.0 - t;
    vec3 s = vec3(sqrt(1.0 - cz * cz) * cos(phi), sqrt(1.0 - cz * cz) * sin(phi), cz);
    if (dot(s, n) < 0.0) s = -s;
    vec3 q = c + s * u_radius * mix(0.2, 1.0, t * t);
    ivec2 qp = ivec2(floor(vec2(u_k.x * q.x / q.z + u_k.z, u_k.y * q.y / q.z + u_k.w) + 0.5));
    if (any(lessThan(qp, ivec2(0))) || any(greaterThan(qp, last))) continue;
    float scene_z = optical_point(qp).z;
    float in_range = smoothstep(0.0, 1.0, u_radius / max(abs(c.z - scene_z), 1e-4));
    occluded += (scene_z < q.z - 0.01 ? 1.0 : 0.0) * in_range;
  }
  o_ao = clamp(1.0 - 1.2 * occluded / float(kSamples), 0.0, 1.0);
}
)";

const char* const kBareVertex = R"(#version 450 core
layout(location = 0) in vec2 a_position;
void main() { gl_Position = vec4(a_position, 0.5, 1.0); }
)";

const char* const kBareFragment = R"(#version 450 core
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(0.6, 0.5, 0.4, 1.0); }
)";

}  // namespace rescuesim::gl::shaders
