#version 460
#include "lib/common.glsl"
#include "lib/denoise.glsl"

// SVGF, temporal integration and variance estimate in one pass (docs/techniques.md §14).
// Integration of a radiance signal and the first two moments of its luminance. The moments blend
// with the HISTORY's moments (not the current ones, the book's mistake). n counts the samples
// including this one:
//   moving: n = min(n+1, 32), α = max(0.2, 1/n) (SVGF paper);
//   static: n = min(n+1, large), α = 1/n, the exact running mean, so a still frame converges.
// Writes the colour history (rgb, n; fp32 for the exact mean; overwritten by à-trous iteration 1
// while moving), the moments history (μ1, μ2) and the working image for à-trous: rgb the colour,
// a the variance, μ2 − μ1² where the history holds ≥ 4 samples, otherwise from the moments of a
// 7×7 bilateral neighbourhood (depth and normal weights only) of this frame's samples (the
// centre: its own moments), so a disoccluded pixel is still filtered. Static camera: the signal
// being filtered is the running mean of n samples, whose variance is var/n; the à-trous luminance
// weight then tightens as the mean converges and stops blurring it.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform usampler2D surfaceTex;
layout(set = 0, binding = 1) uniform usampler2D prevSurfaceTex;
layout(set = 0, binding = 2) uniform sampler2D motionTex;
layout(set = 0, binding = 3) uniform sampler2D rawTex;
layout(set = 0, binding = 4) uniform sampler2D colorHistoryTex;    // rgb mean, a n
layout(set = 0, binding = 5) uniform sampler2D momentsHistoryTex;  // μ1, μ2
layout(set = 0, binding = 6, rgba32f) uniform writeonly image2D outColor;
layout(set = 0, binding = 7, rg32f) uniform writeonly image2D outMoments;
layout(set = 0, binding = 8, rgba16f) uniform writeonly image2D outColorVariance;
layout(push_constant, scalar) uniform Push { TemporalPush pc; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), pc.size))) return;
  const bool moving = (pc.flags & kDenoiseMoving) != 0u;
  Surface cur = loadSurface(surfaceTex, p, pc.size);
  vec3 fresh = texelFetch(rawTex, p, 0).rgb;
  float l = luminance(fresh);

  Reprojection r;
  r.sum = 0.0;
  if (!isSky(cur) && (pc.flags & kDenoiseReset) == 0u)
    r = reproject(prevSurfaceTex, p, texelFetch(motionTex, p, 0).xy, pc.size, cur);

  vec3 color = fresh;
  vec2 moments = vec2(l, l * l);
  float n = 1.0;
  if (hasHistory(r)) {
    vec4 c = vec4(0.0);
    vec2 m = vec2(0.0);
    for (int k = 0; k < 4; ++k) {
      if (r.w[k] <= 0.0) continue;
      c += r.w[k] * texelFetch(colorHistoryTex, r.tap[k], 0);
      m += r.w[k] * texelFetch(momentsHistoryTex, r.tap[k], 0).xy;
    }
    c /= r.sum;
    m /= r.sum;
    // Written at last frame's exposure: the mean scales by the ratio, the second moment by its square.
    c.rgb *= pc.historyScale;
    m *= vec2(pc.historyScale, pc.historyScale * pc.historyScale);
    n = min(c.a + 1.0, moving ? kSvgfMaxLengthMoving : kSvgfMaxLengthStatic);
    float alpha = max(1.0 / n, moving ? kSvgfAlphaMinMoving : 0.0);
    color = mix(c.rgb, fresh, alpha);
    moments = mix(m, vec2(l, l * l), alpha);
  }
  imageStore(outColor, p, vec4(color, n));
  imageStore(outMoments, p, vec4(moments, 0.0, 0.0));

  vec2 mu = moments;
  if (n < kSvgfMinTemporalVarianceLength && !isSky(cur)) {
    vec2 sum = moments;
    float weights = 1.0;
    for (int j = -kSvgfVarianceRadius; j <= kSvgfVarianceRadius; ++j)
      for (int i = -kSvgfVarianceRadius; i <= kSvgfVarianceRadius; ++i) {
        ivec2 q = p + ivec2(i, j);
        if ((i == 0 && j == 0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(pc.size)))) continue;
        uvec2 t = texelFetch(surfaceTex, q, 0).xy;
        if (t.x == 0u) continue;  // sky
        float w = geometryWeight(cur, decodeSurface(t), vec2(i, j));
        float lq = luminance(texelFetch(rawTex, q, 0).rgb);
        sum += w * vec2(lq, lq * lq);
        weights += w;
      }
    mu = sum / weights;
  }
  float variance = max(0.0, mu.y - mu.x * mu.x);
  if (!moving) variance /= n;
  variance = min(variance, kSvgfMaxVariance);
  imageStore(outColorVariance, p, vec4(color, variance));
}
