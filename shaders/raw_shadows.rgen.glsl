#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/lights.glsl"

// Raw ray rate of the shadow pass (rayster bench --raw-rays): the very rays of shadows.rgen
// (lib/shadow_ray.glsl), traced opaque (no alpha any-hit) with a trivial miss, so the pass's time
// over this one's is the share of the device's raw rate it reaches.
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
  visible = 0u;
  if (shadowRay(px, layer, origin, dir, tMax))
    traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | gl_RayFlagsOpaqueEXT | gl_RayFlagsCullBackFacingTrianglesEXT,
                kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, tMax, 0);
  imageStore(outVisibility, ivec3(px, layer), vec4(float(visible)));
}
