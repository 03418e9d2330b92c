#version 460
#include "lib/common.glsl"
#include "lib/denoise.glsl"

// SVGF, variance estimate (TECHNIQUES.md §12): μ2 − μ1² where the history holds ≥ 4 samples,
// otherwise from the moments of a 7×7 bilateral neighbourhood (depth and normal weights only), so a
// disoccluded pixel is still filtered. Output: rgb the integrated colour, a the variance.
// Static camera: the signal being filtered is the running mean of n samples, whose variance is
// var/n; the à-trous luminance weight then tightens as the mean converges and stops blurring it.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform usampler2D surfaceTex;
layout(set = 0, binding = 1) uniform sampler2D colorTex;
layout(set = 0, binding = 2) uniform sampler2D momentsTex;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D outColorVariance;
layout(push_constant, scalar) uniform Push { TemporalPush pc; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), pc.size))) return;
  vec3 color = texelFetch(colorTex, p, 0).rgb;
  vec3 m = texelFetch(momentsTex, p, 0).xyz;
  Surface sp = decodeSurface(texelFetch(surfaceTex, p, 0));
  vec2 moments = m.xy;
  if (m.z < kSvgfMinTemporalVarianceLength && !isSky(sp)) {
    vec2 sum = vec2(0.0);
    float weights = 0.0;
    for (int j = -kSvgfVarianceRadius; j <= kSvgfVarianceRadius; ++j)
      for (int i = -kSvgfVarianceRadius; i <= kSvgfVarianceRadius; ++i) {
        ivec2 q = p + ivec2(i, j);
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(pc.size)))) continue;
        Surface sq = decodeSurface(texelFetch(surfaceTex, q, 0));
        if (isSky(sq)) continue;
        float w = (i == 0 && j == 0) ? 1.0 : geometryWeight(sp, sq, vec2(i, j));
        sum += w * texelFetch(momentsTex, q, 0).xy;
        weights += w;
      }
    moments = sum / weights;
  }
  float variance = max(0.0, moments.y - moments.x * moments.x);
  if ((pc.flags & kDenoiseMoving) == 0u) variance /= max(m.z, 1.0);
  variance = min(variance, kSvgfMaxVariance);
  imageStore(outColorVariance, p, vec4(color, variance));
}
