#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/lights.glsl"
#include "lib/light_select.glsl"
#include "lib/light_ray.glsl"

// Raw ray rate of rt-direct (rayster bench --raw-rays, many-light mode): direct.rgen's rays exactly,
// the same light pick (selectLight at the G-buffer point, same random stream), the same "light
// gives nothing here" test and the same shadow ray (lib/light_ray.glsl, same offset), traced opaque
// with a trivial miss, without shading. Output: the shadow ray's visibility, 0 where none is traced.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;
layout(set = 0, binding = 4, r16f) uniform writeonly image2D outVisibility;

layout(location = 0) rayPayloadEXT uint visible;

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  float depth = texelFetch(depthTex, px, 0).r;
  visible = 0u;
  if (!isBackground(depth)) {
    vec2 uv = (vec2(px) + 0.5) / vec2(gl_LaunchSizeEXT.xy);
    vec3 p = worldFromDepth(frame.worldFromClip, uv, depth);
    float depthError = distance(p, worldFromDepth(frame.worldFromClip, uv, uintBitsToFloat(floatBitsToUint(depth) + 1u)));
    vec4 nn = texelFetch(normalTex, px, 0);
    vec3 n = octDecode(nn.xy), ng = octDecode(nn.zw);
    uint rng = rngInit(uvec2(px), frame.frameIndex, frame.seed ^ kShadowStream);
    float invPdf;
    uint i = selectLight(p, n, rng, invPdf);
    vec3 l, origin, dir;
    float dist, tMax;
    if (i < frame.lightCount && !all(equal(lightIncident(loadLight(i), p, l, dist), vec3(0.0))) &&
        lightShadowRay(i, p, ng, max(hitRayOffset(p), 4.0 * depthError), rng, origin, dir, tMax))
      traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | gl_RayFlagsOpaqueEXT | gl_RayFlagsCullBackFacingTrianglesEXT,
                  kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, tMax, 0);
  }
  imageStore(outVisibility, px, vec4(float(visible)));
}
