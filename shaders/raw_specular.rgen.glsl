#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/textures.glsl"
#include "lib/surface.glsl"
#include "lib/lights.glsl"
#include "lib/light_select.glsl"
#include "lib/brdf.glsl"
#include "lib/dfg.glsl"
#include "lib/light_ray.glsl"
#include "lib/specular_weight.glsl"
#include "shared/vndf.h"

// Raw ray rate of rt-specular (rayster bench --raw-rays). Replayed exactly: the first ray of every
// path (lib/specular_path.glsl: the same mirror, glossy VNDF and Fresnel choices, the same half-rate
// checkerboard). Approximated: the shadow rays at its hit. The twin's closest hit (raw_t.rchit)
// returns only the distance, so the shading point is origin + t·dir with the normal facing the ray
// (−dir), and the pass's light loop is replayed as such: one importance-picked light after a glossy
// sample or in many-light mode, else every light that reaches the point. Not replayed: the deeper
// bounces, whose directions need the materials at the hits (mostly glass and mirror pixels); the
// pass's figure over this one's is therefore the share of the raw rate its first bounce (and the
// shading around it) reaches, and deeper bounces count against it. Rays are opaque, misses trivial.
// Output: 0 where the pass traces nothing (its alpha 0), 0.125 where a glossy sample leaves below the
// surface (nothing traced, 0 written), 0.25 a half-rate skip (filled from the neighbours), 0.5 the
// first ray missed, 1 it hit.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;
layout(set = 0, binding = 4) uniform sampler2D albedoTex;
layout(set = 0, binding = 5) uniform sampler2D materialTex;
layout(set = 0, binding = 6, r16f) uniform writeonly image2D outHit;
layout(set = 0, binding = 7) uniform sampler2D emissiveTex;
layout(set = 0, binding = 8) uniform sampler2D specularGbufTex;

layout(location = 0) rayPayloadEXT uint hitT;
layout(location = 1) rayPayloadEXT uint visible;

#include "lib/specular_path.glsl"

void shadowRay(uint i, vec3 p, vec3 n, inout uint rng) {
  vec3 origin, dir;
  float tMax;
  if (!lightShadowRay(i, p, n, hitRayOffset(p), rng, origin, dir, tMax)) return;
  visible = 0u;
  traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | gl_RayFlagsOpaqueEXT | gl_RayFlagsCullBackFacingTrianglesEXT,
              kMaskCastsShadow, 0, 0, 1, origin, 0.0, dir, tMax, 1);
}

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  vec3 origin, dir, beta;
  bool glossy;
  vec4 result;
  uint rng;
  if (!specularFirstRay(px, origin, dir, beta, glossy, result, rng)) {
    imageStore(outHit, px, vec4(result.a == kHalfRateSkipped ? 0.25 : result.a > 0.0 ? 0.125 : 0.0));
    return;
  }
  hitT = floatBitsToUint(-1.0);
  traceRayEXT(tlas, gl_RayFlagsOpaqueEXT | gl_RayFlagsCullBackFacingTrianglesEXT, kMaskVisible | kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
  float t = uintBitsToFloat(hitT);
  if (t >= 0.0) {
    vec3 p = origin + t * dir;
    if (glossy || frame.manyLights != 0u) {
      float invPdf;
      uint i = selectLight(p, -dir, rng, invPdf);
      if (i < frame.lightCount) shadowRay(i, p, -dir, rng);
    } else {
      for (uint i = 0u; i < frame.lightCount; ++i) {
        vec3 l;
        float dist;
        if (!all(equal(lightIncident(loadLight(i), p, l, dist), vec3(0.0)))) shadowRay(i, p, -dir, rng);
      }
    }
  }
  imageStore(outHit, px, vec4(t < 0.0 ? 0.5 : 1.0));
}
