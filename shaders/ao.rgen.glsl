#version 460
// variant: raw_ao.rgen RAW_RATE
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/ray_flags.glsl"

// Ray-traced ambient occlusion from the G-buffer (docs/techniques.md §15): one cosine-weighted ray about
// the shading normal per pixel per frame, from P offset along the geometric normal, as long as the
// AO radius (lib/ao_ray.glsl); any shadow caster in between occludes (terminate on first hit, no
// closest hit). With cosine sampling the AO is the plain mean of these visibilities. At half rate
// (--ao-rate half) the launch is half as wide and covers this frame's checkerboard half; rt-ao-fill
// (ao_fill.comp) writes the other half.
// Output (R16F, layer frame.aoLayer: its own one-layer image, or the shadow image's AO layer): 1 unoccluded, 0 occluded; directions under the geometric surface count
// as occluded (the surface itself blocks them); background pixels and AO off write 1.
// RAW_RATE (raw_ao.rgen, the raw ray rate of rt-ao, rayster bench --raw-rays): the very same rays,
// traced opaque (no alpha any-hit) with a trivial miss, into a one-layer image of its own. Output:
// the same visibility (equal wherever no geometry is alpha-tested); at half rate 0.25 on the pixels
// not traced this frame (which rt-ao-fill fills in the pass's image).
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;
#ifdef RAW_RATE
layout(set = 0, binding = 4, r16f) uniform writeonly image2D outAo;
void storeAo(ivec2 px, float value) { imageStore(outAo, px, vec4(value)); }
uint aoRayFlags() { return gl_RayFlagsOpaqueEXT | gl_RayFlagsCullBackFacingTrianglesEXT; }
#else
layout(set = 0, binding = 4, r16f) uniform writeonly image2DArray outAo;
void storeAo(ivec2 px, float value) { imageStore(outAo, ivec3(px, int(frame.aoLayer)), vec4(value)); }
uint aoRayFlags() { return sceneRayFlags(); }
#endif

layout(location = 0) rayPayloadEXT uint visible;

#include "lib/ao_ray.glsl"

void main() {
  ivec2 px = aoPixel(gl_LaunchIDEXT.xy);
#ifdef RAW_RATE
  // At half rate the other pixel of the invocation's pair is not traced this frame: 0.25 says so.
  if (aoHalfRate() && (px.x ^ 1) < int(frame.size.x)) storeAo(ivec2(px.x ^ 1, px.y), 0.25);
#endif
  if (px.x >= int(frame.size.x)) return;
  vec3 origin, dir;
  float value;
  if (!aoRay(px, origin, dir, value)) {
    storeAo(px, value);
    return;
  }
  visible = 0u;
  uint flags = gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | aoRayFlags();
  // Casters only: a light's visible shape does not occlude the light around it.
  traceRayEXT(tlas, flags, kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, frame.aoRadius, 0);
  storeAo(px, float(visible));
}
