#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/ray_flags.glsl"

// Sky visibility (rt-sky-visibility, --sky-visibility on): one cosine-weighted ray about the shading
// normal per pixel per frame, of unbounded length, from P offset along the geometric normal; 1 when
// it leaves the scene (reaches the sky), 0 when any shadow caster is in the way. With cosine
// sampling the mean is the cosine-weighted fraction of the hemisphere that sees the sky: the
// visibility an environment light of constant radiance is scaled by (ambient occlusion without a
// radius). Directions under the geometric surface count as occluded; background pixels write 1.
// Output: R16F, layer 0 of a one-layer array (so the shadow denoiser takes it unchanged).
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;
layout(set = 0, binding = 4, r16f) uniform writeonly image2DArray outSkyVisibility;

layout(location = 0) rayPayloadEXT uint visible;

const uint kSkyStream = 0x5c1e5c1eu;  // its own random stream: uncorrelated with AO's rays
const float kUnbounded = 1.0e30;

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  float depth = texelFetch(depthTex, px, 0).r;
  float value = 1.0;
  if (!isBackground(depth)) {
    vec2 uv = (vec2(px) + 0.5) / vec2(gl_LaunchSizeEXT.xy);
    vec3 p = worldFromDepth(frame.worldFromClip, uv, depth);
    vec4 nn = texelFetch(normalTex, px, 0);
    vec3 n = octDecode(nn.xy), ng = octDecode(nn.zw);
    uint rng = rngInit(uvec2(px), frame.frameIndex, frame.seed ^ kSkyStream);
    vec3 dir = cosineSampleHemisphere(n, vec2(rnd(rng), rnd(rng)));
    value = 0.0;
    if (dot(dir, ng) > 0.0) {
      vec3 origin = p + ng * gbufferRayOffset(frame.worldFromClip, uv, depth, p);
      visible = 0u;
      uint flags = gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | sceneRayFlags();
      traceRayEXT(tlas, flags, kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, kUnbounded, 0);
      value = float(visible);
    }
  }
  imageStore(outSkyVisibility, ivec3(px, 0), vec4(value));
}
