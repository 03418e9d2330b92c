#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/lights.glsl"
#include "lib/light_select.glsl"
#include "lib/light_ray.glsl"

// Raw ray rate of rt-indirect (rayster bench --raw-rays). Replayed exactly: the bounce ray
// (lib/indirect_ray.glsl, same random stream). Approximated: its shadow ray. The twin's closest hit
// (raw_t.rchit) returns only the hit distance, so the shading point is origin + t·dir and, lacking
// the hit's normals, the light is picked (selectLight) and the "below the surface" test made with
// the normal facing the bounce ray's origin (−dir); the shadow ray (lib/light_ray.glsl, same
// offset) then goes from the same point to the same kind of light sample, so its length and
// coherence match, though not its exact direction. Rays are traced opaque with trivial misses.
// Output: 0 where no bounce ray is traced, 0.5 where it misses, 1 where it hits. At quarter rate
// the same block pixels trace (lib/indirect_ray.glsl) and the block's other pixels get
// kIndirectSkipped, so a test sees which pixel of each block traced.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;
layout(set = 0, binding = 4, r16f) uniform writeonly image2D outHit;

layout(location = 0) rayPayloadEXT uint hitT;
layout(location = 1) rayPayloadEXT uint visible;

#include "lib/indirect_ray.glsl"

const float kIndirectSkipped = 0.25;  // a pixel of a quarter-rate block that another pixel traces for

void main() {
  ivec2 px = indirectPixel(gl_LaunchIDEXT.xy);
  if (indirectQuarterRate()) {
    ivec2 size = ivec2(frame.size);
    for (int k = 0; k < 4; ++k) {
      ivec2 q = 2 * ivec2(gl_LaunchIDEXT.xy) + ivec2(k & 1, k >> 1);
      if (q != px && all(lessThan(q, size))) imageStore(outHit, q, vec4(kIndirectSkipped));
    }
  }
  vec3 origin, dir;
  vec4 value;
  uint rng;
  float result = 0.0;
  if (indirectRay(px, origin, dir, value, rng)) {
    hitT = floatBitsToUint(-1.0);
    traceRayEXT(tlas, gl_RayFlagsOpaqueEXT | gl_RayFlagsCullBackFacingTrianglesEXT, kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
    float t = uintBitsToFloat(hitT);
    result = t < 0.0 ? 0.5 : 1.0;
    if (t >= 0.0) {
      vec3 p = origin + t * dir;
      float invPdf;
      uint i = selectLight(p, -dir, rng, invPdf);
      vec3 shadowOrigin, shadowDir;
      float tMax;
      if (i < frame.lightCount && lightShadowRay(i, p, -dir, hitRayOffset(p), rng, shadowOrigin, shadowDir, tMax)) {
        visible = 0u;
        traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | gl_RayFlagsOpaqueEXT | gl_RayFlagsCullBackFacingTrianglesEXT,
                    kMaskCastsShadow, 0, 0, 1, shadowOrigin, 0.0, shadowDir, tMax, 1);
      }
    }
  }
  imageStore(outHit, px, vec4(result));
}
