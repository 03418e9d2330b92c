#version 460
// variant: raw_specular.rgen RAW_RATE
// variant: specular_queue.rgen SPECULAR_QUEUE
// variant: specular_continue.rgen SPECULAR_QUEUE SPECULAR_CONTINUE
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/ray_flags.glsl"
#include "lib/textures.glsl"
#include "lib/surface.glsl"
#include "lib/lights.glsl"
#include "lib/light_select.glsl"
#include "lib/brdf.glsl"
#include "lib/dfg.glsl"
#include "lib/light_ray.glsl"
#include "lib/specular_weight.glsl"
#include "shared/vndf.h"
#ifndef RAW_RATE
#include "lib/sphere.glsl"
#include "lib/primary_payload.glsl"
#include "lib/hit_surface.glsl"
#include "lib/environment.glsl"
#include "lib/ray_cone.glsl"
#endif

// Ray-traced reflections and refractions (docs/techniques.md §12, §13): from every G-buffer pixel whose
// material is a mirror, glossy (one GGX VNDF sample per pixel up to the glossy threshold) or glass,
// a loop in raygen (no recursion) follows the specular path for up to frame.maxSpecularBounces
// traced rays (RenderSettings::maxDepth): Fresnel between reflection and refraction (chosen stochastically, so the
// estimate is unbiased and converges over frames), total internal reflection, η by side,
// Beer–Lambert absorption inside volumes, thin walls. Every hit is shaded by shadeSurface(), the
// lighting pass's own function, with shadow rays — or, with --shadows off (--effects mirrors,
// frame.effectFlags without kEffectShadows), with none: each light lights what it faces, as in the
// classic mirror-reflection samples (lib/shading.glsl shadeLight() never calls lightVisibility()). Output: the specular radiance the lighting pass
// adds (the diffuse layer of the first surface is the lighting pass's).
// Compaction (SPECULAR_QUEUE, where the device launches rays indirectly): the pass traces every
// path's first segment, then appends the paths that go on to a queue instead of looping on, and
// its variant specular_continue.rgen (SPECULAR_CONTINUE) traces their remaining segments, one
// dense invocation per path. In one launch a warp holding a single glass or mirror path runs every
// later bounce at one lane's worth of work; in the queue the paths that go on fill the warps.
// A path the full queue cannot take loops on in place, so the image is the same either way.
// RAW_RATE (raw_specular.rgen, the raw ray rate of rt-specular, rayster bench --raw-rays). Replayed
// exactly: the first ray of every path (lib/specular_path.glsl: the same mirror, glossy VNDF and
// Fresnel choices, the same half-rate checkerboard). Approximated: the shadow rays at its hit. The
// twin's closest hit (raw_t.rchit) returns only the distance, so the shading point is origin + t·dir
// with the normal facing the ray (−dir), and the pass's light loop is replayed as such: one
// importance-picked light after a glossy sample or in many-light mode, else every light that reaches
// the point. Not replayed: the deeper bounces, whose directions need the materials at the hits
// (mostly glass and mirror pixels); the pass's figure over this one's is therefore the share of the
// raw rate its first bounce (and the shading around it) reaches, and deeper bounces count against
// it. Rays are opaque, misses trivial. Output (R16F): 0 where the pass traces nothing (its alpha 0),
// 0.125 where a glossy sample leaves below the surface (nothing traced, 0 written), 0.25 a half-rate
// skip (filled from the neighbours), 0.5 the first ray missed, 1 it hit.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;
layout(set = 0, binding = 4) uniform sampler2D albedoTex;
layout(set = 0, binding = 5) uniform sampler2D materialTex;
#ifdef RAW_RATE
layout(set = 0, binding = 6, r16f) uniform writeonly image2D outHit;
#else
layout(set = 0, binding = 6, rgba16f) uniform writeonly image2D outSpecular;
#endif
layout(set = 0, binding = 7) uniform sampler2D emissiveTex;  // .a: the first surface's exact ior
layout(set = 0, binding = 8) uniform sampler2D specularGbufTex;  // encodeSpecular(): F0 tint, strength
#ifndef RAW_RATE
// Irradiance probes (--gi probes, lib/probes.glsl): the diffuse indirect light at the loop's hits,
// when grid.flags has kProbeLookup (else 1×1 stand-ins, never read).
#include "shared/probes.h"
layout(set = 0, binding = 9) uniform sampler2D probeIrradianceTex;
layout(set = 0, binding = 10) uniform sampler2D probeVisibilityTex;
layout(set = 0, binding = 11) uniform sampler2D probeDataTex;
layout(push_constant, scalar) uniform Push { ProbeGrid grid; };
#include "lib/probes.glsl"
#endif

#ifdef RAW_RATE
layout(location = 0) rayPayloadEXT uint hitT;  // raw_t.rchit: the hit distance's bits; raw.rmiss keeps it
#else
layout(location = 0) rayPayloadEXT PrimaryPayload payload;
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

float lightVisibility(uint i, vec3 p, vec3 ng, inout uint rng) {
  vec3 origin, dir;
  float tMax;
  if (!lightShadowRay(i, p, ng, hitRayOffset(p), rng, origin, dir, tMax)) return 0.0;
  visible = 0u;
  traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | rayFlags(),
              kMaskCastsShadow, 0, 0, 1, origin, 0.0, dir, tMax, 1);
  return float(visible);
}

#include "lib/specular_path.glsl"

#ifdef RAW_RATE

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
  traceRayEXT(tlas, rayFlags(), kMaskVisible | kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
  float t = uintBitsToFloat(hitT);
  if (t >= 0.0 && shadowRaysOn()) {  // --shadows off: the pass traces no shadow ray at its hits
    vec3 p = origin + t * dir;
    if (glossy || frame.manyLights != 0u) {  // shadeDirect()'s one pick (lib/shading.glsl)
      float invPdf;
      uint i = selectLight(p, -dir, rng, invPdf);
      if (i < frame.lightCount) lightVisibility(i, p, -dir, rng);
    } else {  // its loop over the lights that reach p
      for (uint i = 0u; i < frame.lightCount; ++i) {
        vec3 l;
        float dist;
        if (!all(equal(lightIncident(loadLight(i), p, l, dist), vec3(0.0)))) lightVisibility(i, p, -dir, rng);
      }
    }
  }
  imageStore(outHit, px, vec4(t < 0.0 ? 0.5 : 1.0));
}

#else

void skipLightVisibility(inout uint rng) { skipLightShadowRay(rng); }

#include "lib/shading.glsl"

#ifdef SPECULAR_QUEUE
// The queue of paths that go on after their first segment (shared/types.h SpecularQueuedPath
// packing; kSpecularQueueDivisor: its capacity, a share of the pixels) and its length, which is also
// the width of the continuation's indirect launch (VkTraceRaysIndirectCommandKHR {width, 1, 1}).
#ifdef SPECULAR_CONTINUE
layout(set = 0, binding = 12, std430) readonly buffer SpecularQueue { uvec4 queuedPaths[]; };
#else
layout(set = 0, binding = 12, std430) writeonly buffer SpecularQueue { uvec4 queuedPaths[]; };
layout(set = 0, binding = 13, std430) buffer SpecularQueueLength { uint queueLength; };
#endif
#endif

// A specular path between segments.
struct SpecularPath {
  vec3 origin, dir;
  vec3 beta;      // throughput
  vec3 radiance;  // gathered so far, demodulated as the pass outputs it
  float coneWidth;
  uint rng;
  uint bounce;  // the next segment's number, from 1
  bool glossy;  // its first event was a glossy VNDF sample: one importance-picked light per hit
};

uint queueCapacity(uvec2 size) { return (size.x * size.y + kSpecularQueueDivisor - 1u) / kSpecularQueueDivisor; }

#if defined(SPECULAR_QUEUE) && !defined(SPECULAR_CONTINUE)
// Three uvec4 per path: origin + cone width, direction + random state, then throughput and radiance
// as half floats and the pixel's index with the segment number and the glossy flag.
void storePath(uint slot, SpecularPath path, ivec2 px, uint width) {
  queuedPaths[3u * slot] = uvec4(floatBitsToUint(path.origin), floatBitsToUint(path.coneWidth));
  queuedPaths[3u * slot + 1u] = uvec4(floatBitsToUint(path.dir), path.rng);
  uint tag = uint(px.y) * width + uint(px.x) | path.bounce << kSpecularQueueBounceShift |
             (path.glossy ? kSpecularQueueGlossy : 0u);
  queuedPaths[3u * slot + 2u] = uvec4(packHalf2x16(path.beta.rg), packHalf2x16(vec2(path.beta.b, path.radiance.r)),
                                      packHalf2x16(path.radiance.gb), tag);
}
#endif
#ifdef SPECULAR_CONTINUE
SpecularPath loadPath(uint slot, uint width, out ivec2 px) {
  uvec4 a = queuedPaths[3u * slot], b = queuedPaths[3u * slot + 1u], c = queuedPaths[3u * slot + 2u];
  SpecularPath path;
  path.origin = uintBitsToFloat(a.xyz);
  path.coneWidth = uintBitsToFloat(a.w);
  path.dir = uintBitsToFloat(b.xyz);
  path.rng = b.w;
  vec2 br = unpackHalf2x16(c.x), bg = unpackHalf2x16(c.y), gb = unpackHalf2x16(c.z);
  path.beta = vec3(br, bg.x);
  path.radiance = vec3(bg.y, gb);
  uint index = c.w & kSpecularQueuePixelMask;
  px = ivec2(index % width, index / width);
  path.bounce = (c.w >> kSpecularQueueBounceShift) & kSpecularQueueBounceMask;
  path.glossy = (c.w & kSpecularQueueGlossy) != 0u;
  return path;
}
#endif

// One segment of the path: trace, shade the hit with shadow rays (the lighting pass's
// shadeSurface()) and scatter on. False when the path ends there (a miss, a rough hit fully shaded,
// a throughput too small to matter).
bool specularSegment(inout SpecularPath path, float spread) {
  payload.t = -1.0;
  traceRayEXT(tlas, rayFlags(), kMaskVisible | kMaskCastsShadow, 0, 0, 0, path.origin, 0.0, path.dir, 1e30, 0);
  if (payload.t < 0.0) {
    path.radiance += path.beta * environmentRadiance(path.dir);
    return false;
  }
  SurfacePoint sp;
  MaterialRecord m;
  surfaceAtHit(payload, path.origin, path.dir, sp, m);
  bool entering = dot(path.dir, sp.geometricNormal) < 0.0;
  bool thinHit = m.thickness <= 0.0;
  // Beer–Lambert: leaving a volume, the path inside it was payload.t long.
  if (!entering && !thinHit) path.beta *= volumeTransmittance(m, payload.t);
  path.coneWidth += spread * payload.t;
  setRayCone(path.coneWidth, sp.geometricNormal, path.dir);
  GBufferValues gb = evaluateSurface(m, sp, path.origin);
  ShadingInput s;
  s.p = sp.position;
  s.n = octDecode(gb.normals.xy);
  s.ng = octDecode(gb.normals.zw);
  s.v = -path.dir;
  s.baseColor = srgbToLinear(gb.albedo.rgb);
  s.metallic = gb.material.g;
  s.roughness = gb.material.r;
  s.transmission = gb.material.b;
  s.specular = gb.specular;
  s.ior = m.ior;
  s.ao = gb.albedo.a;
  s.emissive = gb.emissive.rgb;
  s.tracedWeight = tracedSpecular(s.roughness, s.transmission) ? 1.0 : 0.0;
  s.envOcclusion = 1.0;  // no AO at hits
  // With probes, a hit's diffuse indirect light is theirs (as at G-buffer pixels), not ambient + SH.
  s.useIndirect = (grid.flags & kProbeLookup) != 0u;
  s.sunHighlights = false;
  s.highlightWiden = 0.0;
  s.useIndirectSpecular = s.useIndirect && !tracedSpecular(s.roughness, s.transmission);
  s.indirect = s.indirectSpecular = vec3(0.0);
  setLayers(s, gb.coat, gb.sheen);
  if (s.useIndirect && readsIrradiance(s))  // not at the mirror and glass hits most paths go on through
    probeIrradiance2(grid, s.p, s.n, s.v, s.useIndirectSpecular, reflect(-s.v, s.n), s.indirect, s.indirectSpecular);
  // A glossy lobe averages its hits over frames and pixels anyway: there one light picked by
  // importance (divided by its probability) stands in for the loop over all lights.
  path.radiance += path.beta * shadeSurface(s, true, path.glossy || frame.manyLights != 0u, path.rng);
  if (!tracedSpecular(s.roughness, s.transmission)) return false;  // rough: fully shaded, the path ends
  scatter(path.dir, path.origin, path.beta, s.p, s.n, s.ng, entering, s.baseColor, s.metallic, s.transmission, m.ior,
          thinHit, gb.specular, path.rng);
  return max(path.beta.r, max(path.beta.g, path.beta.b)) >= 1e-3;
}

// The remaining segments, up to the frame's bound.
void finishPath(inout SpecularPath path, float spread) {
  const uint bounces = min(frame.maxSpecularBounces, kMaxSpecularBounces);
  while (path.bounce <= bounces && specularSegment(path, spread)) ++path.bounce;
}

// Clamp fireflies of the stochastic glass paths to a bright but finite value before accumulation.
vec4 pathResult(SpecularPath path) { return vec4(min(path.radiance, vec3(64.0)), 1.0); }

#ifdef SPECULAR_CONTINUE

void main() {
  const uint slot = gl_LaunchIDEXT.x;
  uvec2 size = uvec2(imageSize(outSpecular));
  if (slot >= queueCapacity(size)) return;  // a full queue's overflow looped on in its own pixel
  ivec2 px;
  SpecularPath path = loadPath(slot, size.x, px);
  finishPath(path, pixelSpreadAngle());
  imageStore(outSpecular, px, pathResult(path));
}

#else

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  SpecularPath path;
  vec4 result;
  if (!specularFirstRay(px, path.origin, path.dir, path.beta, path.glossy, result, path.rng)) {
    imageStore(outSpecular, px, result);
    return;
  }
  path.radiance = vec3(0.0);
  // The pixel's ray cone: as wide at the G-buffer surface as the camera ray made it, then widening
  // by the same angle along every bounce (flat mirrors).
  const float spread = pixelSpreadAngle();
  path.coneWidth = spread * distance(frame.cameraPosition.xyz, path.origin);
  path.bounce = 1u;
  // One copy of the segment's code (a second inlined copy, for the first segment alone, made the
  // in-place loop a third slower on an H200): after the first segment a path that goes on is queued.
  const uint bounces = min(frame.maxSpecularBounces, kMaxSpecularBounces);
  while (specularSegment(path, spread) && ++path.bounce <= bounces) {
#ifdef SPECULAR_QUEUE
    if (path.bounce == 2u) {
      uint slot = atomicAdd(queueLength, 1u);
      if (slot < queueCapacity(gl_LaunchSizeEXT.xy)) {
        storePath(slot, path, px, gl_LaunchSizeEXT.x);
        return;  // specular_continue.rgen writes the pixel
      }
    }
#endif
  }
  imageStore(outSpecular, px, pathResult(path));
}

#endif
#endif
