// The bounce ray of pixel `px` for one-bounce indirect diffuse (docs/techniques.md §16), shared by
// indirect.rgen and its raw-rate twin raw_indirect.rgen: cosine-weighted about the shading normal,
// from P offset along the geometric normal. The includer declares depthTex and normalTex. Returns
// false when no ray is traced; `value` is then what the pass writes (0 on the background and with
// indirect light off; 0 with alpha 1 under the geometric surface). `rng` continues at the hit.
// At quarter rate (kEffectIndirectQuarter) both launch one invocation per 2×2 block and trace the
// block's pixel whose turn it is (lib/indirect_rate.glsl); indirect_fill.comp fills the other three.
#ifndef RAYSTER_INDIRECT_RAY_GLSL
#define RAYSTER_INDIRECT_RAY_GLSL

#include "indirect_rate.glsl"

bool indirectRay(ivec2 px, out vec3 origin, out vec3 dir, out vec4 value, out uint rng) {
  origin = vec3(0.0);
  dir = vec3(0.0, 1.0, 0.0);
  value = vec4(0.0);
  rng = 0u;
  float depth = texelFetch(depthTex, px, 0).r;
  if (isBackground(depth) || (frame.effectFlags & kEffectIndirect) == 0u) return false;
  vec2 uv = (vec2(px) + 0.5) / vec2(frame.size);
  vec3 p = worldFromDepth(frame.worldFromClip, uv, depth);
  vec4 nn = texelFetch(normalTex, px, 0);
  vec3 n = octDecode(nn.xy), ng = octDecode(nn.zw);
  rng = rngInit(uvec2(px), frame.frameIndex, frame.seed ^ kIndirectStream);
  dir = cosineSampleHemisphere(n, vec2(rnd(rng), rnd(rng)));
  if (dot(dir, ng) <= 0.0) {  // under the geometric surface: the surface itself blocks it
    value = vec4(0.0, 0.0, 0.0, 1.0);
    return false;
  }
  origin = p + ng * gbufferRayOffset(frame.worldFromClip, uv, depth, p);
  return true;
}

#endif
