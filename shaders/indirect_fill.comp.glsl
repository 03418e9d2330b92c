#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/denoise.glsl"

// Quarter-rate indirect diffuse (--indirect-rate quarter, lib/indirect_rate.glsl): indirect.rgen traced
// one pixel of each 2×2 block this frame; every other pixel becomes a weighted mean of the traced
// pixels of its own and the 8 surrounding blocks, so the raw image is defined everywhere before SVGF.
// Weights: a Gaussian of the distance (σ = 1 px: the nearest traced pixels dominate) times SVGF's
// depth and normal edge-stopping weight (lib/denoise.glsl) against the denoisers' surface image, so
// light does not leak across silhouettes and creases. Where no traced neighbour is on a similar
// surface (a feature thinner than a block), the distance weight alone decides. Sky pixels get 0, as
// indirect.rgen writes there. In place: pixels traced this frame are only read, the others only written.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1, rgba16f) uniform image2D indirect;
layout(set = 0, binding = 2) uniform usampler2D surfaceTex;

#include "lib/indirect_rate.glsl"

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.size);
  if (any(greaterThanEqual(px, size))) return;
  ivec2 block = px >> 1;
  if (indirectTracedPixel(block) == px) return;
  Surface c = loadSurface(surfaceTex, px, uvec2(size));
  if (isSky(c)) {
    imageStore(indirect, px, vec4(0.0));
    return;
  }
  vec3 sum = vec3(0.0), sumAny = vec3(0.0);
  float weight = 0.0, weightAny = 0.0;
  ivec2 blocks = (size + 1) >> 1;
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i) {
      ivec2 b = block + ivec2(i, j);
      if (any(lessThan(b, ivec2(0))) || any(greaterThanEqual(b, blocks))) continue;
      ivec2 q = indirectTracedPixel(b);
      Surface s = decodeSurface(texelFetch(surfaceTex, q, 0).xy);
      if (isSky(s)) continue;
      vec2 d = vec2(q - px);
      float wd = exp(-0.5 * dot(d, d));
      vec3 v = imageLoad(indirect, q).rgb;
      float w = wd * geometryWeight(c, s, d);
      sum += w * v;
      weight += w;
      sumAny += wd * v;
      weightAny += wd;
    }
  vec3 value = weight > 1e-4 ? sum / weight : (weightAny > 0.0 ? sumAny / weightAny : vec3(0.0));
  imageStore(indirect, px, vec4(value, 1.0));
}
