#version 460
// variant: raw_shadows.rgen RAW_RATE
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/ray_flags.glsl"
#include "lib/lights.glsl"

// RT shadows from the G-buffer (docs/techniques.md §9): one ray per pixel per light per frame, towards
// a uniform sample of the light's solid angle. gl_LaunchIDEXT.z is the light's layer.
// Output: 1 visible, 0 occluded; pixels facing away from the light (N·L <= 0) and background
// pixels write 0, which lighting multiplies with a zero N·L anyway.
// RAW_RATE (raw_shadows.rgen, the raw ray rate of rt-shadows, rayster bench --raw-rays): the very
// same rays, traced opaque (no alpha any-hit) with a trivial miss, so the pass's time over this
// one's is the share of the device's raw rate it reaches. Same output.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;
layout(set = 0, binding = 4, r16f) uniform writeonly image2DArray outVisibility;

layout(location = 0) rayPayloadEXT uint visible;

#include "lib/shadow_ray.glsl"

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  uint layer = gl_LaunchIDEXT.z;
  vec3 origin, dir;
  float tMax;
  if (!shadowRay(px, layer, origin, dir, tMax)) {
    imageStore(outVisibility, ivec3(px, layer), vec4(0.0));
    return;
  }
  visible = 0u;
#ifdef RAW_RATE
  uint flags = gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | gl_RayFlagsOpaqueEXT |
               gl_RayFlagsCullBackFacingTrianglesEXT;
#else
  // Opaque (no any-hit) only when no geometry needs alpha testing (docs/techniques.md §4).
  uint flags = gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | sceneRayFlags();
#endif
  traceRayEXT(tlas, flags, kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, tMax, 0);
  imageStore(outVisibility, ivec3(px, layer), vec4(float(visible)));
}
