#version 460
#include "lib/common.glsl"
#include "lib/denoise.glsl"

// SVGF, temporal integration (TECHNIQUES.md §12) of a radiance signal and the first two moments of
// its luminance. The moments blend with the HISTORY's moments (not the current ones, the book's
// mistake). n counts the samples including this one:
//   moving: n = min(n+1, 32), α = max(0.2, 1/n) (SVGF paper);
//   static: n = min(n+1, large), α = 1/n, the exact running mean, so a still frame converges.
// Writes the colour history (overwritten by à-trous iteration 1 while moving) and the moments
// history (μ1, μ2, n).
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform usampler2D surfaceTex;
layout(set = 0, binding = 1) uniform usampler2D prevSurfaceTex;
layout(set = 0, binding = 2) uniform sampler2D motionTex;
layout(set = 0, binding = 3) uniform sampler2D rawTex;
layout(set = 0, binding = 4) uniform sampler2D colorHistoryTex;
layout(set = 0, binding = 5) uniform sampler2D momentsHistoryTex;
layout(set = 0, binding = 6, rgba32f) uniform writeonly image2D outColor;
layout(set = 0, binding = 7, rgba32f) uniform writeonly image2D outMoments;
layout(push_constant, scalar) uniform Push { TemporalPush pc; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), pc.size))) return;
  const bool moving = (pc.flags & kDenoiseMoving) != 0u;
  Surface cur = decodeSurface(texelFetch(surfaceTex, p, 0));
  vec4 fresh = texelFetch(rawTex, p, 0);
  float l = luminance(fresh.rgb);

  Reprojection r;
  r.sum = 0.0;
  if (!isSky(cur) && (pc.flags & kDenoiseReset) == 0u)
    r = reproject(prevSurfaceTex, p, texelFetch(motionTex, p, 0).xy, pc.size, cur);

  vec4 color = fresh;
  vec3 moments = vec3(l, l * l, 1.0);
  if (hasHistory(r)) {
    vec4 c = vec4(0.0);
    vec3 m = vec3(0.0);
    for (int k = 0; k < 4; ++k) {
      if (r.w[k] <= 0.0) continue;
      c += r.w[k] * texelFetch(colorHistoryTex, r.tap[k], 0);
      m += r.w[k] * texelFetch(momentsHistoryTex, r.tap[k], 0).xyz;
    }
    c /= r.sum;
    m /= r.sum;
    float n = min(m.z + 1.0, moving ? kSvgfMaxLengthMoving : kSvgfMaxLengthStatic);
    float alpha = max(1.0 / n, moving ? kSvgfAlphaMinMoving : 0.0);
    color = mix(c, fresh, alpha);
    moments = vec3(mix(m.xy, vec2(l, l * l), alpha), n);
  }
  imageStore(outColor, p, color);
  imageStore(outMoments, p, vec4(moments, 0.0));
}
