#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/lights.glsl"
#include "lib/brdf.glsl"
#include "lib/textures.glsl"
#include "lib/environment.glsl"

// Deferred lighting: every light with its ray-traced visibility, emission, and the uniform ambient
// stand-in for indirect light. Output: linear HDR radiance (RGBA16F).
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D depthTex;
layout(set = 0, binding = 2) uniform sampler2D normalTex;
layout(set = 0, binding = 3) uniform sampler2D albedoTex;
layout(set = 0, binding = 4) uniform sampler2D materialTex;
layout(set = 0, binding = 5) uniform sampler2D emissiveTex;
layout(set = 0, binding = 6) uniform sampler2DArray visibilityTex;
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D outColor;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), frame.size))) return;
  float depth = texelFetch(depthTex, px, 0).r;
  vec2 uv = (vec2(px) + 0.5) / vec2(frame.size);
  if (isBackground(depth)) {
    vec3 viewDir = worldFromDepth(frame.worldFromClip, uv, 1.0) - frame.cameraPosition.xyz;
    imageStore(outColor, px, vec4(environmentRadiance(viewDir), 1.0));
    return;
  }
  vec3 p = worldFromDepth(frame.worldFromClip, uv, depth);
  vec3 n = octDecode(texelFetch(normalTex, px, 0).xy);
  vec3 v = normalize(frame.cameraPosition.xyz - p);
  vec4 albedo = texelFetch(albedoTex, px, 0);
  vec3 baseColor = srgbToLinear(albedo.rgb);
  float ao = albedo.a;
  vec4 mat = texelFetch(materialTex, px, 0);
  SurfaceBsdf bsdf = makeBsdf(baseColor, mat.g, mat.r);

  vec3 radiance = texelFetch(emissiveTex, px, 0).rgb;
  radiance += frame.ambient.rgb * (bsdf.diffuse + bsdf.f0) * ao;
  // Unshadowed environment light until ray-traced AO and reflections exist: diffuse from the SH
  // irradiance, specular from the map along the mirror direction, blurred towards the irradiance
  // as roughness grows.
  if (frame.environmentKind != kEnvironmentBlack) {
    vec3 r = reflect(-v, n);
    float nv = max(dot(n, v), 1e-4);
    vec3 fr = bsdf.f0 + (max(vec3(1.0 - mat.r), bsdf.f0) - bsdf.f0) * pow(1.0 - nv, 5.0);
    vec3 specularEnv = mix(environmentRadiance(r), environmentIrradiance(r) / kPi, mat.r);
    radiance += (bsdf.diffuse * environmentIrradiance(n) / kPi * (1.0 - fr) + fr * specularEnv) * ao;
  }
  for (uint i = 0u; i < frame.lightCount; ++i) {
    LightRecord light = Lights(frame.lights).l[i];
    vec3 l;
    float dist;
    vec3 incident = lightIncident(light, p, l, dist);
    float widen = light.type == kLightDirectional ? light.angularRadius : light.radius / max(dist, 1e-3);
    float visibility = i < frame.shadowLightCount ? texelFetch(visibilityTex, ivec3(px, i), 0).r : 1.0;
    radiance += evalBsdfCos(bsdf, n, v, l, 0.5 * widen) * incident * visibility;
  }
  imageStore(outColor, px, vec4(radiance, 1.0));
}
