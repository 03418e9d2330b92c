// Body of svgf_atrous.comp and of its variant svgf_atrous_history.comp (cmake/shaders.cmake; it
// defines SVGF_WRITE_HISTORY): two pipelines, so the plain iterations bind no history image at all.
#extension GL_EXT_control_flow_attributes : require
#include "lib/common.glsl"
#include "lib/denoise.glsl"

// SVGF, one à-trous iteration (docs/techniques.md §14): 5×5 B3-spline taps at p + step·(i, j), weights
// w_z (σz = 1), w_n (σn = 128) and w_l = exp(−|l_p − l_q| / (σl·sqrt(g3×3(var_p)) + ε)) (σl = 4).
// Colour Σ h·w·c / Σ h·w; variance Σ (h·w)²·var / (Σ h·w)², passed on in .a. Mirrors and glass
// (roughness ≤ kSharpRoughness: the surface texel's sharp flag, so nothing reads the material image)
// are passed through and never used as neighbours of rougher pixels.
// With SVGF_WRITE_HISTORY (iteration 1 while moving) the output also becomes the colour history
// (rgb; its a, the history length n written by the temporal pass, is kept).
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform usampler2D surfaceTex;  // with the sharp flag
layout(set = 0, binding = 1) uniform sampler2D inputTex;     // rgb colour, a variance
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D outColorVariance;
#ifdef SVGF_WRITE_HISTORY
layout(set = 0, binding = 3, rgba32f) uniform image2D outHistory;
#endif
layout(push_constant, scalar) uniform Push { AtrousPush pc; };

bool inside(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(pc.size))); }

// 3×3 Gaussian (1/4, 1/2, 1/4) of the variance around p.
float blurredVariance(ivec2 p) {
  float sum = 0.0, weights = 0.0;
  [[unroll]] for (int j = -1; j <= 1; ++j)
    [[unroll]] for (int i = -1; i <= 1; ++i) {
      ivec2 q = p + ivec2(i, j);
      if (!inside(q)) continue;
      float w = (i == 0 ? 0.5 : 0.25) * (j == 0 ? 0.5 : 0.25);
      sum += w * texelFetch(inputTex, q, 0).a;
      weights += w;
    }
  return sum / weights;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), pc.size))) return;
  vec4 centre = texelFetch(inputTex, p, 0);
  Surface sp = loadSurface(surfaceTex, p, pc.size);
  vec4 result = centre;
  if (!isSky(sp) && !sp.sharp) {
    float lp = luminance(centre.rgb);
    float lumScale = 1.0 / (kSigmaLuminance * sqrt(blurredVariance(p)) + kLuminanceEpsilon);
    float depthScales[5];
    atrousDepthScales(sp, int(pc.step), depthScales);
    vec3 color = vec3(0.0);
    float variance = 0.0, weights = 0.0;
    [[unroll]] for (int j = -2; j <= 2; ++j)
      [[unroll]] for (int i = -2; i <= 2; ++i) {
        ivec2 q = p + int(pc.step) * ivec2(i, j);
        if (!inside(q)) continue;
        vec4 c = texelFetch(inputTex, q, 0);
        float w = b3(i) * b3(j);
        if (i != 0 || j != 0) {
          Surface sq = decodeSurface(texelFetch(surfaceTex, q, 0).xy);
          if (isSky(sq) || sq.sharp) continue;
          w *= normalWeight(sp, sq) * exp(-(depthExponent(sp, sq, depthScales[atrousDistanceIndex(i, j)]) +
                                             abs(lp - luminance(c.rgb)) * lumScale));
        }
        color += w * c.rgb;
        variance += w * w * c.a;
        weights += w;
      }
    result = vec4(color / weights, variance / (weights * weights));
  }
  imageStore(outColorVariance, p, result);
#ifdef SVGF_WRITE_HISTORY
  imageStore(outHistory, p, vec4(result.rgb, imageLoad(outHistory, p).a));
#endif
}
