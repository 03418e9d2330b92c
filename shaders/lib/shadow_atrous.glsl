// Body of shadow_atrous.comp (every layer count) and of its variant shadow_atrous_2.comp (at most two
// layers; cmake/shaders.cmake), which define SHADOW_ATROUS_LAYERS.
#extension GL_EXT_control_flow_attributes : require
#include "lib/common.glsl"
#include "lib/denoise.glsl"

// Shadow denoiser, one edge-aware à-trous iteration (docs/techniques.md §11): 5×5 B3-spline taps at
// p + step·(i, j), depth and normal weights (σz = 1, σn = 128), computed once for every light
// layer, times a per-layer value weight exp(−|v_p − v_q| / (σl·sqrt(var_p) + ε)) with the variance
// of the temporal pass (not propagated: each iteration uses the temporal estimate). The per-layer
// loops run to the constant SHADOW_ATROUS_LAYERS, unrolled, so the arrays stay in registers: the
// general pipeline takes kMaxShadowDenoiseLayers (8 lights + AO), shadow_atrous_2.comp two layers
// (one light and AO, the common case), whose smaller arrays keep more invocations in flight.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform usampler2D surfaceTex;
layout(set = 0, binding = 1) uniform sampler2DArray inputTex;
layout(set = 0, binding = 2, r16f) uniform writeonly image2DArray outVisibility;
layout(set = 0, binding = 3) uniform sampler2DArray varianceTex;
layout(push_constant, scalar) uniform Push { AtrousPush pc; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), pc.size))) return;
  const int layers = int(pc.layers);
  Surface sp = loadSurface(surfaceTex, p, pc.size);
  float sum[SHADOW_ATROUS_LAYERS], weights[SHADOW_ATROUS_LAYERS];
  float centre[SHADOW_ATROUS_LAYERS], scale[SHADOW_ATROUS_LAYERS];
  [[unroll]] for (int l = 0; l < int(SHADOW_ATROUS_LAYERS); ++l) {
    if (l >= layers) break;
    centre[l] = texelFetch(inputTex, ivec3(p, l), 0).r;
    scale[l] = 1.0 / (kSigmaLuminance * sqrt(texelFetch(varianceTex, ivec3(p, l), 0).r) + kShadowValueEpsilon);
    sum[l] = centre[l];
    weights[l] = 1.0;
  }
  if (!isSky(sp)) {
    float depthScales[5];
    atrousDepthScales(sp, int(pc.step), depthScales);
    [[unroll]] for (int l = 0; l < int(SHADOW_ATROUS_LAYERS); ++l) sum[l] = weights[l] = 0.0;
    [[unroll]] for (int j = -2; j <= 2; ++j)
      [[unroll]] for (int i = -2; i <= 2; ++i) {
        ivec2 q = p + int(pc.step) * ivec2(i, j);
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(pc.size)))) continue;
        Surface sq = decodeSurface(texelFetch(surfaceTex, q, 0).xy);
        if (isSky(sq)) continue;
        const bool isCentre = i == 0 && j == 0;
        // The depth weight's exponent joins each layer's value weight in one exp().
        float w = b3(i) * b3(j) * (isCentre ? 1.0 : normalWeight(sp, sq));
        if (w <= 0.0) continue;
        float dz = isCentre ? 0.0 : depthExponent(sp, sq, depthScales[atrousDistanceIndex(i, j)]);
        [[unroll]] for (int l = 0; l < int(SHADOW_ATROUS_LAYERS); ++l) {
          if (l >= layers) break;
          float v = texelFetch(inputTex, ivec3(q, l), 0).r;
          float wl = isCentre ? w : w * exp(-(dz + abs(centre[l] - v) * scale[l]));
          sum[l] += wl * v;
          weights[l] += wl;
        }
      }
  }
  [[unroll]] for (int l = 0; l < int(SHADOW_ATROUS_LAYERS); ++l)
    if (l < layers) imageStore(outVisibility, ivec3(p, l), vec4(sum[l] / weights[l]));
}
