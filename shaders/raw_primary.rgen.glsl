#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/ray_flags.glsl"

// Raw ray rate of the traced G-buffer (rayster bench --raw-rays): the same primary rays as
// gbuffer.rgen, with a closest-hit shader that only marks the hit (raw.rchit) and a trivial miss,
// and one 16-bit write per pixel instead of the G-buffer's seven.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2, r16f) uniform writeonly image2D outHit;

layout(location = 0) rayPayloadEXT uint hit;

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  vec2 uv = (vec2(px) + 0.5) / vec2(gl_LaunchSizeEXT.xy);
  vec3 origin = frame.cameraPosition.xyz;
  vec3 dir = cameraRayDirection(frame.worldFromClip, uv, origin);
  hit = 0u;
  uint flags = sceneRayFlags();
  traceRayEXT(tlas, flags, kMaskVisible | kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
  imageStore(outHit, px, vec4(float(hit)));
}
