#version 460
// variant: raw_direct.rgen RAW_RATE
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/ray_flags.glsl"
#include "lib/lights.glsl"
#include "lib/light_select.glsl"
#ifndef RAW_RATE
#include "lib/textures.glsl"
#include "lib/brdf.glsl"
#include "lib/environment.glsl"
#endif
#include "lib/light_ray.glsl"

// Many-light direct lighting (docs/techniques.md §10), used when the scene has more lights than shadow
// layers: per pixel one light picked by importance (lib/light_select.glsl), one shadow ray towards a
// uniform sample of its solid angle, and the light's shaded contribution divided by the pick's
// probability, so the cost is one ray whatever the light count. Output: RGBA16F direct radiance
// (the lighting pass adds it instead of looping over lights); 0 on the background.
// RAW_RATE (raw_direct.rgen, the raw ray rate of rt-direct, rayster bench --raw-rays): this pass's
// rays exactly, the same light pick (selectLight at the G-buffer point, same random stream), the
// same "light gives nothing here" test and the same shadow ray, traced opaque with a trivial miss,
// without shading. Output (R16F): the shadow ray's visibility, 0 where none is traced.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;
#ifdef RAW_RATE
layout(set = 0, binding = 4, r16f) uniform writeonly image2D outVisibility;
#else
layout(set = 0, binding = 4) uniform sampler2D albedoTex;
layout(set = 0, binding = 5) uniform sampler2D materialTex;
layout(set = 0, binding = 6, rgba16f) uniform writeonly image2D outDirect;
layout(set = 0, binding = 7) uniform sampler2D emissiveTex;      // .a: the exact ior
layout(set = 0, binding = 8) uniform sampler2D specularGbufTex;  // encodeSpecular(): F0 tint, strength
layout(set = 0, binding = 9) uniform usampler2D layersTex;        // encodeLayers(): clear coat and sheen
#endif

layout(location = 0) rayPayloadEXT uint visible;

float gDepthError;  // P's reconstruction error from quantised depth: part of the ray offset

// The shadow ray of lib/light_ray.glsl, offset by more than P's reconstruction error.
float directRayOffset(vec3 p) { return max(hitRayOffset(p), 4.0 * gDepthError); }

float lightVisibility(uint i, vec3 p, vec3 ng, inout uint rng) {
  vec3 origin, dir;
  float tMax;
  if (!lightShadowRay(i, p, ng, directRayOffset(p), rng, origin, dir, tMax)) return 0.0;
  visible = 0u;
#ifdef RAW_RATE
  uint flags = gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | gl_RayFlagsOpaqueEXT |
               gl_RayFlagsCullBackFacingTrianglesEXT;
#else
  uint flags = gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | sceneRayFlags();
#endif
  traceRayEXT(tlas, flags, kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, tMax, 0);
  return float(visible);
}

// The G-buffer point of pixel px: P (and gDepthError), its shading and geometric normals. False on
// the background.
bool gbufferPoint(ivec2 px, out vec3 p, out vec3 n, out vec3 ng) {
  p = n = ng = vec3(0.0);
  float depth = texelFetch(depthTex, px, 0).r;
  if (isBackground(depth)) return false;
  vec2 uv = (vec2(px) + 0.5) / vec2(gl_LaunchSizeEXT.xy);
  p = worldFromDepth(frame.worldFromClip, uv, depth);
  float nextDepth = uintBitsToFloat(floatBitsToUint(depth) + 1u);
  gDepthError = distance(p, worldFromDepth(frame.worldFromClip, uv, nextDepth));
  vec4 nn = texelFetch(normalTex, px, 0);
  n = octDecode(nn.xy);
  ng = octDecode(nn.zw);
  return true;
}

#ifdef RAW_RATE

// shadeDirect()'s one pick (lib/shading.glsl) and its shadow ray, without the shading.
void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  vec3 p, n, ng;
  visible = 0u;
  if (gbufferPoint(px, p, n, ng)) {
    uint rng = rngInit(uvec2(px), frame.frameIndex, frame.seed ^ kShadowStream);
    float invPdf;
    uint i = selectLight(p, n, rng, invPdf);
    vec3 l;
    float dist;
    if (i < frame.lightCount && !all(equal(lightIncident(loadLight(i), p, l, dist), vec3(0.0))))
      lightVisibility(i, p, ng, rng);
  }
  imageStore(outVisibility, px, vec4(float(visible)));
}

#else

void skipLightVisibility(inout uint rng) { skipLightShadowRay(rng); }

#include "lib/shading.glsl"

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  ShadingInput s;
  if (!gbufferPoint(px, s.p, s.n, s.ng)) {
    imageStore(outDirect, px, vec4(0.0));
    return;
  }
  s.v = normalize(frame.cameraPosition.xyz - s.p);
  vec4 albedo = texelFetch(albedoTex, px, 0);
  s.baseColor = srgbToLinear(albedo.rgb);
  s.ao = albedo.a;
  vec4 mat = texelFetch(materialTex, px, 0);
  s.roughness = mat.r;
  s.metallic = mat.g;
  s.transmission = mat.b;
  s.ior = texelFetch(emissiveTex, px, 0).a;
  s.specular = decodeSpecular(texelFetch(specularGbufTex, px, 0));
  s.emissive = vec3(0.0);
  s.tracedWeight = tracedSpecularWeight(s.roughness, s.transmission);
  s.envOcclusion = 1.0;  // direct light only: AO never applies to it
  s.useIndirect = false;
  s.useIndirectSpecular = false;
  s.sunHighlights = true;
  s.highlightWiden = 0.0;
  s.indirectSpecular = vec3(0.0);
  s.indirect = vec3(0.0);
  vec4 coat, sheen;
  decodeLayers(fetchNeutral(layersTex, px), coat, sheen);  // one zero texel without coats and sheens
  setLayers(s, coat, sheen);
  uint rng = rngInit(uvec2(px), frame.frameIndex, frame.seed ^ kShadowStream);
  vec3 direct = shadeDirect(s, shadingTerms(s), rng);
  // A bright but finite clamp: a rare pick of a weak light far away must not become a firefly NaN.
  imageStore(outDirect, px, vec4(min(direct, vec3(1e4)), 1.0));
}

#endif
