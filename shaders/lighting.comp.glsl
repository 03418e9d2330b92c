#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/lights.glsl"
#include "lib/light_select.glsl"
#include "lib/brdf.glsl"
#include "lib/textures.glsl"
#include "lib/environment.glsl"
#include "lib/dfg.glsl"

// Deferred lighting: shadeSurface() (lib/shading.glsl, shared with the bounce loop) with the
// ray-traced shadow visibility (or, with many lights, the stochastic direct light of direct.rgen),
// ray-traced AO (ambient and environment light only) and one-bounce indirect diffuse irradiance,
// plus the traced specular light of mirrors, glossy surfaces and glass (opaque surfaces:
// demodulated lobe-average radiance, × F0·A + B here, docs/techniques.md §13), under the clear coat
// and sheen where the material has them (lib/shading.glsl).
// Output: linear HDR radiance (RGBA16F).
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D depthTex;
layout(set = 0, binding = 2) uniform sampler2D normalTex;
layout(set = 0, binding = 3) uniform sampler2D albedoTex;
layout(set = 0, binding = 4) uniform sampler2D materialTex;
layout(set = 0, binding = 5) uniform sampler2D emissiveTex;
layout(set = 0, binding = 6) uniform sampler2DArray visibilityTex;
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D outColor;
layout(set = 0, binding = 8) uniform sampler2D specularTex;
layout(set = 0, binding = 9) uniform sampler2DArray aoTex;  // layer frame.aoLayer: 1 unoccluded; 1 when AO is off
layout(set = 0, binding = 10) uniform sampler2D indirectTex;  // rgb: irradiance E; read when kEffectIndirect
layout(set = 0, binding = 11) uniform sampler2D directTex;  // many-light mode: stochastic direct light
layout(set = 0, binding = 12) uniform sampler2D specularGbufTex;  // encodeSpecular(): F0 tint, strength
layout(set = 0, binding = 13) uniform sampler2D indirectSpecularTex;  // kEffectIndirectSpecular: E about r
layout(set = 0, binding = 14) uniform usampler2D layersTex;  // encodeLayers(): clear coat and sheen

ivec2 gPixel;

float lightVisibility(uint i, vec3 p, vec3 ng, inout uint rng) {
  return i < frame.shadowLightCount ? fetchNeutralLayer(visibilityTex, gPixel, int(i)).r : 1.0;
}
void skipLightVisibility(inout uint rng) {}

#include "lib/shading.glsl"

// Half the largest angle between this pixel's shading normal and its four neighbours' (radians,
// at most 0.5): how far the normal turns across the pixel (ShadingInput::highlightWiden).
float normalSpread(ivec2 px, vec3 n) {
  float cosMin = 1.0;
  const ivec2 offsets[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
  for (int k = 0; k < 4; ++k) {
    ivec2 q = clamp(px + offsets[k], ivec2(0), ivec2(frame.size) - 1);
    if (isBackground(texelFetch(depthTex, q, 0).r)) continue;
    cosMin = min(cosMin, dot(n, octDecode(texelFetch(normalTex, q, 0).xy)));
  }
  return min(0.5 * acos(clamp(cosMin, -1.0, 1.0)), 0.5);
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), frame.size))) return;
  gPixel = px;
  float depth = texelFetch(depthTex, px, 0).r;
  vec2 uv = (vec2(px) + 0.5) / vec2(frame.size);
  if (isBackground(depth)) {
    vec3 viewDir = cameraRayDirection(frame.worldFromClip, uv, frame.cameraPosition.xyz);
    imageStore(outColor, px, vec4(environmentRadiance(viewDir), 1.0));
    return;
  }
  ShadingInput s;
  s.p = worldFromDepth(frame.worldFromClip, uv, depth);
  vec4 nn = texelFetch(normalTex, px, 0);
  s.n = octDecode(nn.xy);
  s.ng = octDecode(nn.zw);
  s.v = normalize(frame.cameraPosition.xyz - s.p);
  vec4 albedo = texelFetch(albedoTex, px, 0);
  s.baseColor = srgbToLinear(albedo.rgb);
  s.ao = albedo.a;
  vec4 mat = texelFetch(materialTex, px, 0);
  s.roughness = mat.r;
  s.metallic = mat.g;
  s.transmission = mat.b;
  vec4 emissive = texelFetch(emissiveTex, px, 0);
  s.emissive = emissive.rgb;
  s.ior = emissive.a;
  s.specular = decodeSpecular(texelFetch(specularGbufTex, px, 0));
  s.tracedWeight = tracedSpecularWeight(s.roughness, s.transmission);
  s.envOcclusion = fetchNeutralLayer(aoTex, px, int(frame.aoLayer)).r;
  s.useIndirect = (frame.effectFlags & kEffectIndirect) != 0u;
  s.indirect = s.useIndirect ? fetchNeutral(indirectTex, px).rgb : vec3(0.0);
  s.sunHighlights = true;
  s.highlightWiden = s.tracedWeight > 0.0 ? normalSpread(px, s.n) : 0.0;  // used for the traced share only
  s.useIndirectSpecular = (frame.effectFlags & kEffectIndirectSpecular) != 0u;
  s.indirectSpecular = s.useIndirectSpecular ? fetchNeutral(indirectSpecularTex, px).rgb : vec3(0.0);
  vec4 coat, sheen;
  decodeLayers(fetchNeutral(layersTex, px), coat, sheen);  // a one-texel zero image without coats and sheens
  setLayers(s, coat, sheen);
  uint rng = 0u;  // visibility comes from the shadow image: no random numbers needed here
  vec3 traced = fetchNeutral(specularTex, px).rgb;
  // Glass writes radiance; opaque surfaces the lobe average, remodulated by the lobe's albedo.
  if (s.transmission <= 0.0) {
    SurfaceBsdf bsdf = makeBsdf(s.baseColor, s.metallic, s.roughness, s.specular, s.ior);
    traced *= specularAlbedo(bsdf.f0, bsdf.f90, max(dot(s.n, s.v), 1e-4), s.roughness);
  }
  bool many = frame.manyLights != 0u;
  vec3 radiance = shadeSurface(s, !many, rng) + s.tracedWeight * underLayers(s) * traced;
  if (many) radiance += fetchNeutral(directTex, px).rgb;
  imageStore(outColor, px, vec4(radiance, 1.0));
}
