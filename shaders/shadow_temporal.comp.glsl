#version 460
#extension GL_EXT_control_flow_attributes : require
#include "lib/common.glsl"
#include "lib/denoise.glsl"

// Shadow denoiser, temporal step (docs/techniques.md §11), all light layers of a pixel in one
// invocation so the reprojection is paid once. History: R32F array, layers 0..L−1 the running
// means, layer L the history length n (fp32, so the static running mean stays exact).
//   α = max(1/(1+n), αmin); static: αmin = 0, no clamp; moving: αmin = 0.2 and the history is
//   clamped to the 3×3 min/max of the new visibility.
// Also writes the variance of each layer for the à-trous value weight (shared/denoise.h). The
// per-layer loop runs to the constant kMaxShadowDenoiseLayers, unrolled.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform usampler2D surfaceTex;
layout(set = 0, binding = 1) uniform usampler2D prevSurfaceTex;
layout(set = 0, binding = 2) uniform sampler2D motionTex;
layout(set = 0, binding = 3) uniform sampler2DArray rawTex;
layout(set = 0, binding = 4) uniform sampler2DArray historyTex;
layout(set = 0, binding = 5, r32f) uniform writeonly image2DArray outHistory;
layout(set = 0, binding = 6, r16f) uniform writeonly image2DArray outVariance;
layout(push_constant, scalar) uniform Push { TemporalPush pc; };

// 3×3 range of the new signal of one layer (taps clamped to the screen).
vec2 neighbourhood(ivec2 p, int layer) {
  vec2 range = vec2(1.0e30, -1.0e30);
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      ivec2 q = clamp(p + ivec2(x, y), ivec2(0), ivec2(pc.size) - 1);
      float v = texelFetch(rawTex, ivec3(q, layer), 0).r;
      range = vec2(min(range.x, v), max(range.y, v));
    }
  return range;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), pc.size))) return;
  const bool moving = (pc.flags & kDenoiseMoving) != 0u;
  const int layers = int(pc.layers);
  Surface cur = loadSurface(surfaceTex, p, pc.size);

  Reprojection r;
  r.sum = 0.0;
  if (!isSky(cur) && (pc.flags & kDenoiseReset) == 0u)
    r = reproject(prevSurfaceTex, p, texelFetch(motionTex, p, 0).xy, pc.size, cur);
  const bool history = hasHistory(r);

  float n = 0.0;  // samples in the history
  if (history) {
    for (int k = 0; k < 4; ++k)
      if (r.w[k] > 0.0) n += r.w[k] * texelFetch(historyTex, ivec3(r.tap[k], layers), 0).r;
    n /= r.sum;
  }
  const float alpha = max(1.0 / (1.0 + n), moving ? kShadowAlphaMinMoving : 0.0);
  const float nOut = history ? min(n + 1.0, kShadowMaxLength) : 1.0;

  // A short history: the variance comes from the bilateral 3×3 mean of the new samples.
  const bool spatial = nOut < kShadowMinTemporalVarianceLength && !isSky(cur);
  float spatialWeight[9];
  for (int k = 0; k < 9; ++k) {
    ivec2 o = ivec2(k % 3 - 1, k / 3 - 1), q = p + o;
    spatialWeight[k] = 0.0;
    if (!spatial || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(pc.size)))) continue;
    Surface sq = decodeSurface(texelFetch(surfaceTex, q, 0).xy);
    if (!isSky(sq)) spatialWeight[k] = k == 4 ? 1.0 : geometryWeight(cur, sq, vec2(o));
  }

  [[unroll]] for (int layer = 0; layer < int(kMaxShadowDenoiseLayers); ++layer) {
    if (layer >= layers) break;
    float fresh = texelFetch(rawTex, ivec3(p, layer), 0).r;
    float value = fresh;
    if (history) {
      float h = 0.0;
      for (int k = 0; k < 4; ++k)
        if (r.w[k] > 0.0) h += r.w[k] * texelFetch(historyTex, ivec3(r.tap[k], layer), 0).r;
      h /= r.sum;
      if (moving) {
        vec2 range = neighbourhood(p, layer);
        h = clamp(h, range.x, range.y);
      }
      value = mix(h, fresh, alpha);
    }
    imageStore(outHistory, ivec3(p, layer), vec4(value));

    float m = value;
    if (spatial) {
      float sum = 0.0, weights = 0.0;
      for (int k = 0; k < 9; ++k) {
        if (spatialWeight[k] <= 0.0) continue;
        sum += spatialWeight[k] * texelFetch(rawTex, ivec3(p + ivec2(k % 3 - 1, k / 3 - 1), layer), 0).r;
        weights += spatialWeight[k];
      }
      m = sum / weights;
    }
    m = clamp(m, 0.0, 1.0);
    float variance = isSky(cur) ? 0.0 : m * (1.0 - m);
    if (!moving) variance /= nOut;
    imageStore(outVariance, ivec3(p, layer), vec4(variance));
  }
  imageStore(outHistory, ivec3(p, layers), vec4(nOut));
}
