#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"

// Raw ray rate of rt-ao (rayster bench --raw-rays): the very rays of ao.rgen (lib/ao_ray.glsl),
// traced opaque (no alpha any-hit) with a trivial miss. Output: the same visibility ao.rgen writes
// (equal wherever no geometry is alpha-tested).
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;
layout(set = 0, binding = 4, r16f) uniform writeonly image2D outVisibility;

layout(location = 0) rayPayloadEXT uint visible;

#include "lib/ao_ray.glsl"

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  vec3 origin, dir;
  float value;
  if (aoRay(px, origin, dir, value)) {
    visible = 0u;
    traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | gl_RayFlagsOpaqueEXT | gl_RayFlagsCullBackFacingTrianglesEXT,
                kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, frame.aoRadius, 0);
    value = float(visible);
  }
  imageStore(outVisibility, px, vec4(value));
}
