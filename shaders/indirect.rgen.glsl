#version 460
// variant: raw_indirect.rgen RAW_RATE
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/ray_flags.glsl"
#include "lib/lights.glsl"
#include "lib/light_select.glsl"
#include "lib/light_ray.glsl"
#ifndef RAW_RATE
#include "lib/textures.glsl"
#include "lib/surface.glsl"
#include "lib/sphere.glsl"
#include "lib/primary_payload.glsl"
#include "lib/hit_surface.glsl"
#include "lib/brdf.glsl"
#include "lib/environment.glsl"
#include "shared/probes.h"
#endif

// One-bounce indirect diffuse from the G-buffer (docs/techniques.md §16): one cosine-weighted ray about
// the shading normal per pixel per frame. A hit is shaded with its emission, direct light from one
// light picked by importance (shadow ray, divided by the pick probability) and the probes'
// irradiance (with --gi path the probes still run for this: every later bounce), or without probes
// the environment's SH irradiance (no AO at hits); a miss sees the environment.
// Output (RGBA16F): rgb = E = π·L, one sample of the irradiance, demodulated (no albedo): lighting
// applies albedo/π·E. Rays see shadow casters only, so a light's visible shape (which the lighting
// pass already counts as direct light) is not counted again. Background and indirect off write 0.
// At quarter rate (--indirect-rate quarter) one pixel per 2×2 block, rotating over 4 frames;
// indirect_fill.comp gives the other three a depth- and normal-weighted mean of traced ones.
// RAW_RATE (raw_indirect.rgen, the raw ray rate of rt-indirect, rayster bench --raw-rays). Replayed
// exactly: the bounce ray (lib/indirect_ray.glsl, same random stream). Approximated: its shadow ray.
// The twin's closest hit (raw_t.rchit) returns only the hit distance, so the shading point is
// origin + t·dir and, lacking the hit's normals, the light is picked (selectLight) and the "below
// the surface" test made with the normal facing the bounce ray's origin (−dir); the shadow ray
// (lib/light_ray.glsl, same offset) then goes from the same point to the same kind of light sample,
// so its length and coherence match, though not its exact direction. Rays are traced opaque with
// trivial misses. Output (R16F): 0 where no bounce ray is traced, 0.5 where it misses, 1 where it
// hits. At quarter rate the same block pixels trace and the block's other pixels get
// kIndirectSkipped, so a test sees which pixel of each block traced.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;
#ifdef RAW_RATE
layout(set = 0, binding = 4, r16f) uniform writeonly image2D outHit;
layout(location = 0) rayPayloadEXT uint hitT;  // raw_t.rchit: the hit distance's bits; raw.rmiss keeps it
#else
layout(set = 0, binding = 4, rgba16f) uniform writeonly image2D outIndirect;
layout(location = 0) rayPayloadEXT PrimaryPayload payload;
// The probes (this frame's atlases, render/passes/gi_probes.cpp) light the bounce's hits when
// grid.flags has kProbeLookup; else 1×1 stand-ins, never read.
layout(set = 0, binding = 5) uniform sampler2D probeIrradianceTex;
layout(set = 0, binding = 6) uniform sampler2D probeVisibilityTex;
layout(set = 0, binding = 7) uniform sampler2D probeDataTex;
layout(push_constant, scalar) uniform Push { ProbeGrid grid; };
#endif
layout(location = 1) rayPayloadEXT uint visible;

// Every ray's flags: the scene's (lib/ray_flags.glsl), or at raw rate opaque.
uint rayFlags() {
#ifdef RAW_RATE
  return gl_RayFlagsOpaqueEXT | gl_RayFlagsCullBackFacingTrianglesEXT;
#else
  return sceneRayFlags();
#endif
}

// The shadow ray towards light `i` from a bounce hit at p (geometric normal ng): 1 visible, 0 not
// or no ray (below the surface).
float lightVisibility(uint i, vec3 p, vec3 ng, inout uint rng) {
  vec3 origin, dir;
  float tMax;
  if (!lightShadowRay(i, p, ng, hitRayOffset(p), rng, origin, dir, tMax)) return 0.0;
  visible = 0u;
  traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | rayFlags(),
              kMaskCastsShadow, 0, 0, 1, origin, 0.0, dir, tMax, 1);
  return float(visible);
}

#include "lib/indirect_ray.glsl"

#ifdef RAW_RATE

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
    traceRayEXT(tlas, rayFlags(), kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
    float t = uintBitsToFloat(hitT);
    result = t < 0.0 ? 0.5 : 1.0;
    if (t >= 0.0) {
      vec3 p = origin + t * dir;
      float invPdf;
      uint i = selectLight(p, -dir, rng, invPdf);
      if (i < frame.lightCount && shadowRaysOn()) lightVisibility(i, p, -dir, rng);
    }
  }
  imageStore(outHit, px, vec4(result));
}

#else

#include "lib/one_light.glsl"
#include "lib/probes.glsl"

void main() {
  ivec2 px = indirectPixel(gl_LaunchIDEXT.xy);  // at quarter rate, its 2×2 block's pixel of this frame
  vec3 origin, dir;
  vec4 value;
  uint rng;
  if (!indirectRay(px, origin, dir, value, rng)) {
    imageStore(outIndirect, px, value);
    return;
  }
  payload.t = -1.0;
  traceRayEXT(tlas, rayFlags(), kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
  vec3 radiance;
  if (payload.t < 0.0) {
    radiance = environmentRadiance(dir);
  } else {
    SurfacePoint sp;
    MaterialRecord m;
    surfaceAtHit(payload, origin, dir, sp, m);
    GBufferValues gb = evaluateSurface(m, sp, origin);  // normals face the ray's origin
    vec3 hn = octDecode(gb.normals.xy), hng = octDecode(gb.normals.zw);
    SurfaceBsdf bsdf = makeBsdf(srgbToLinear(gb.albedo.rgb), gb.material.g, gb.material.r, gb.specular, m.ior);
    bsdf.diffuse *= 1.0 - gb.material.b;
    radiance = gb.emissive.rgb + directFromOneLight(bsdf, sp.position, hn, hng, -dir, rng);
    // The hit's own diffuse light: the probes' (every later bounce), else the environment's SH
    // irradiance and the ambient term.
    vec3 hitIrradiance = (grid.flags & kProbeLookup) != 0u ? probeIrradiance(grid, sp.position, hn, -dir)
                                                           : environmentIrradiance(hn) + frame.ambient.rgb * kPi;
    radiance += bsdf.diffuse / kPi * hitIrradiance * gb.albedo.a;
  }
  // E = π·L for a cosine-weighted sample; clamp rare fireflies to a bright but finite value.
  imageStore(outIndirect, px, vec4(min(kPi * radiance, vec3(256.0)), 1.0));
}

#endif
