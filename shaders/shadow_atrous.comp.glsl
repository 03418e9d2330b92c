#version 460
#extension GL_EXT_control_flow_attributes : require
#include "lib/common.glsl"
#include "lib/denoise.glsl"
#include "lib/atrous_tile.glsl"

// Shadow denoiser, one edge-aware à-trous iteration (TECHNIQUES.md §9): 5×5 B3-spline taps at
// p + step·(i, j), depth and normal weights (σz = 1, σn = 128), computed once for every light
// layer, times a per-layer value weight exp(−|v_p − v_q| / (σl·sqrt(var_p) + ε)) with the variance
// of the temporal pass (not propagated: each iteration uses the temporal estimate). The per-layer
// loops run to the constant kMaxShadowDenoiseLayers (lights + AO), unrolled, so the arrays stay in
// registers. The taps
// come from a shared-memory tile of the pixel's residue lattice (lib/atrous_tile.glsl).
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform usampler2D surfaceTex;
layout(set = 0, binding = 1) uniform sampler2DArray inputTex;
layout(set = 0, binding = 2, r16f) uniform writeonly image2DArray outVisibility;
layout(set = 0, binding = 3) uniform sampler2DArray varianceTex;
layout(push_constant, scalar) uniform Push { AtrousPush pc; };

// The tile: the surface texel (id kBackgroundId outside the image, so it never counts) and every
// layer's value.
shared uvec2 tileSurface[kAtrousTexels];
shared float tileValue[kMaxShadowDenoiseLayers][kAtrousTexels];

bool inside(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(pc.size))); }

void main() {
  const int layers = int(pc.layers);
  const AtrousLattice lattice = atrousLattice(pc.size, pc.step);
  for (int k = int(gl_LocalInvocationIndex); k < kAtrousTexels; k += kAtrousBlock * kAtrousBlock) {
    ivec2 q = atrousTexelPixel(lattice, ivec2(k % kAtrousSpan, k / kAtrousSpan));
    bool in_ = inside(q);
    tileSurface[k] = in_ ? texelFetch(surfaceTex, q, 0).xy : uvec2(0u);  // depth 0: sky
    [[unroll]] for (int l = 0; l < int(kMaxShadowDenoiseLayers); ++l) {
      if (l >= layers) break;
      tileValue[l][k] = in_ ? texelFetch(inputTex, ivec3(q, l), 0).r : 0.0;
    }
  }
  barrier();

  const ivec2 t = atrousTexel();
  const ivec2 p = atrousTexelPixel(lattice, t);
  if (!inside(p)) return;
  const int c = atrousIndex(t);
  Surface sp = loadSurface(surfaceTex, p, pc.size);
  float sum[kMaxShadowDenoiseLayers], weights[kMaxShadowDenoiseLayers], centre[kMaxShadowDenoiseLayers], scale[kMaxShadowDenoiseLayers];
  [[unroll]] for (int l = 0; l < int(kMaxShadowDenoiseLayers); ++l) {
    if (l >= layers) break;
    centre[l] = tileValue[l][c];
    scale[l] = 1.0 / (kSigmaLuminance * sqrt(texelFetch(varianceTex, ivec3(p, l), 0).r) + kShadowValueEpsilon);
    sum[l] = centre[l];
    weights[l] = 1.0;
  }
  if (!isSky(sp)) {
    [[unroll]] for (int l = 0; l < int(kMaxShadowDenoiseLayers); ++l) sum[l] = weights[l] = 0.0;
    for (int j = -2; j <= 2; ++j)
      for (int i = -2; i <= 2; ++i) {
        const int k = atrousIndex(t + ivec2(i, j));
        Surface sq = decodeSurface(tileSurface[k]);
        if (isSky(sq)) continue;  // also every tap outside the image
        const bool isCentre = i == 0 && j == 0;
        float w = b3(i) * b3(j) * (isCentre ? 1.0 : geometryWeight(sp, sq, vec2(int(pc.step) * ivec2(i, j))));
        if (w <= 0.0) continue;
        [[unroll]] for (int l = 0; l < int(kMaxShadowDenoiseLayers); ++l) {
          if (l >= layers) break;
          float v = tileValue[l][k];
          float wl = isCentre ? w : w * exp(-abs(centre[l] - v) * scale[l]);
          sum[l] += wl * v;
          weights[l] += wl;
        }
      }
  }
  [[unroll]] for (int l = 0; l < int(kMaxShadowDenoiseLayers); ++l)
    if (l < layers) imageStore(outVisibility, ivec3(p, l), vec4(sum[l] / weights[l]));
}
