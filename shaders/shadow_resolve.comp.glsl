#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "shared/shadow_types.h"

// Shadow-map resolve (raster mode): per shadowed light, the visibility of every G-buffer pixel
// from the light's shadow map, written where the ray-traced shadows would be (one R16F layer per
// light), so the lighting pass stays unchanged. Soft edges: percentage-closer soft shadows (Fernando
// 2005) in a light form: a blocker search gives the mean occluder depth, the light's size (sphere
// radius, the sun's angular radius) the penumbra width, and percentage-closer filtering over a
// rotated Poisson disk of that width (at least pcfRadius texels) the visibility. A normal offset and
// a slope-scaled bias keep surfaces from shadowing themselves.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D depthTex;
layout(set = 0, binding = 2) uniform sampler2D normalTex;
layout(set = 0, binding = 3) uniform sampler2D atlasTex;
layout(set = 0, binding = 4, scalar) uniform ShadowBlock { ShadowSetup shadow; };
layout(set = 0, binding = 5, r16f) uniform writeonly image2DArray outVisibility;

// Bias in texels: constant, and per unit of tan(angle to the light) (the slope); normal offset.
const float kBiasConstant = 1.0;
const float kBiasSlope = 1.5;
const float kNormalOffset = 1.5;
const float kMaxSlope = 6.0;
const float kSearchTexels = 8.0;      // blocker search radius
const float kMaxFilterTexels = 12.0;  // widest PCF kernel

const vec2 kPoisson[16] = vec2[16](
    vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.09418410, -0.92938870),
    vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
    vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
    vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
    vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
    vec2(0.14383161, -0.14100790));

float linearDepth(ShadowView v, float d) {
  if (v.perspective != 0u) return v.nearPlane * v.farPlane / (d * (v.farPlane - v.nearPlane) + v.nearPlane);
  return v.farPlane - d * (v.farPlane - v.nearPlane);
}

// Visibility of p from one view; -1 when p lies outside the view's tile. `lightSize`: the sphere
// light's radius (perspective views) or the tangent of the sun's angular radius (orthographic).
float sampleView(ShadowView v, vec3 p, vec3 ng, vec3 l, float angle, float lightSize) {
  float nl = clamp(dot(ng, l), 0.0, 1.0);
  vec4 c0 = v.clipFromWorld * vec4(p, 1.0);
  float texel = v.texelWorld * (v.perspective != 0u ? max(c0.w, 0.0) : 1.0);
  vec3 q = p + ng * (kNormalOffset * texel * sqrt(1.0 - nl * nl));
  vec4 c = v.clipFromWorld * vec4(q, 1.0);
  if (c.w <= 0.0) return -1.0;
  vec3 ndc = c.xyz / c.w;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z < 0.0 || ndc.z > 1.0) return -1.0;
  float z = linearDepth(v, ndc.z);
  float slope = min(sqrt(1.0 - nl * nl) / max(nl, 1e-3), kMaxSlope);
  vec2 atlasSize = 1.0 / shadow.atlasTexel;
  vec2 tileMin = v.tile.xy * atlasSize, tileMax = (v.tile.xy + v.tile.zw) * atlasSize - 1.0;
  vec2 centre = (v.tile.xy + uv * v.tile.zw) * atlasSize;
  float c2 = cos(angle), s2 = sin(angle);
  mat2 rot = mat2(c2, s2, -s2, c2);
  float radius = shadow.pcfRadius;
  if (lightSize > 0.0) {
    float searchBias = texel * (kBiasConstant + kBiasSlope * kSearchTexels * slope);
    float blockerSum = 0.0, blockers = 0.0;
    for (int k = 0; k < 16; ++k) {
      vec2 t = clamp(centre + rot * kPoisson[k] * kSearchTexels, tileMin, tileMax);
      float occluder = linearDepth(v, texelFetch(atlasTex, ivec2(t), 0).r);
      if (z - searchBias > occluder) {
        blockerSum += occluder;
        blockers += 1.0;
      }
    }
    if (blockers == 0.0) return 1.0;
    float zBlocker = blockerSum / blockers;
    float penumbra = v.perspective != 0u ? lightSize * (z - zBlocker) / max(zBlocker, 1e-4) : lightSize * (z - zBlocker);
    radius = clamp(penumbra / texel, shadow.pcfRadius, kMaxFilterTexels);  // penumbra half-width
  }
  float bias = texel * (kBiasConstant + kBiasSlope * radius * slope);
  float lit = 0.0;
  for (int k = 0; k < 16; ++k) {
    vec2 t = clamp(centre + rot * kPoisson[k] * radius, tileMin, tileMax);
    float occluder = linearDepth(v, texelFetch(atlasTex, ivec2(t), 0).r);
    lit += z - bias <= occluder ? 1.0 : 0.0;
  }
  return lit / 16.0;
}

uint cubeFace(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x > 0.0 ? 0u : 1u;
  if (a.y >= a.z) return d.y > 0.0 ? 2u : 3u;
  return d.z > 0.0 ? 4u : 5u;
}

float lightVisibility(uint i, vec3 p, vec3 ng, float angle) {
  ShadowLight sl = shadow.lights[i];
  LightRecord light = loadLight(i);
  if (sl.kind == kShadowNone) return 1.0;
  if (sl.kind == kShadowCascaded) {
    vec3 l = -normalize(light.direction);
    float viewDepth = dot(p - frame.cameraPosition.xyz, shadow.cameraForward.xyz);
    for (uint c = 0u; c < kShadowCascades; ++c) {
      if (viewDepth > shadow.cascadeEnds[c] && c + 1u < kShadowCascades) continue;
      float vis = sampleView(shadow.views[sl.firstView + c], p, ng, l, angle, tan(light.angularRadius));
      if (vis >= 0.0) return vis;
    }
    return 1.0;
  }
  vec3 l = normalize(light.position - p);
  uint view = sl.firstView + (sl.kind == kShadowCube ? cubeFace(p - light.position) : 0u);
  float vis = sampleView(shadow.views[view], p, ng, l, angle, light.radius);
  return vis < 0.0 ? (sl.kind == kShadowSpot ? 0.0 : 1.0) : vis;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), frame.size))) return;
  float depth = texelFetch(depthTex, px, 0).r;
  if (isBackground(depth)) {
    for (uint i = 0u; i < frame.shadowLightCount; ++i) imageStore(outVisibility, ivec3(px, i), vec4(1.0));
    return;
  }
  vec2 uv = (vec2(px) + 0.5) / vec2(frame.size);
  vec3 p = worldFromDepth(frame.worldFromClip, uv, depth);
  vec3 ng = octDecode(texelFetch(normalTex, px, 0).zw);
  // Interleaved gradient noise (Jimenez 2014) turns the disk per pixel; TAA averages the rotations.
  float angle = 2.0 * kPi * fract(52.9829189 * fract(dot(vec2(px) + 5.588238 * float(frame.frameIndex % 64u),
                                                         vec2(0.06711056, 0.00583715))));
  for (uint i = 0u; i < frame.shadowLightCount; ++i)
    imageStore(outVisibility, ivec3(px, i), vec4(lightVisibility(i, p, ng, angle)));
}
