#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/textures.glsl"
#include "lib/surface.glsl"
#include "lib/sphere.glsl"
#include "lib/primary_payload.glsl"
#include "lib/hit_surface.glsl"
#include "lib/lights.glsl"
#include "lib/light_select.glsl"
#include "lib/brdf.glsl"
#include "lib/environment.glsl"
#include "lib/dfg.glsl"
#include "shared/vndf.h"

// Ray-traced reflections and refractions (TECHNIQUES.md §10, §11): from every G-buffer pixel whose
// material is a mirror, glossy (one GGX VNDF sample per pixel up to the glossy threshold) or glass,
// a loop in raygen (no recursion) follows the specular path for up to frame.maxSpecularBounces
// traced rays (RenderSettings::maxDepth): Fresnel between reflection and refraction (chosen stochastically, so the
// estimate is unbiased and converges over frames), total internal reflection, η by side,
// Beer–Lambert absorption inside volumes, thin walls. Every hit is shaded by shadeSurface(), the
// lighting pass's own function, with shadow rays. Output: the specular radiance the lighting pass
// adds (the diffuse layer of the first surface is the lighting pass's).
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;
layout(set = 0, binding = 4) uniform sampler2D albedoTex;
layout(set = 0, binding = 5) uniform sampler2D materialTex;
layout(set = 0, binding = 6, rgba16f) uniform writeonly image2D outSpecular;
layout(set = 0, binding = 7) uniform sampler2D emissiveTex;  // .a: the first surface's exact ior

layout(location = 0) rayPayloadEXT PrimaryPayload payload;
layout(location = 1) rayPayloadEXT uint visible;

uint baseRayFlags() { return (frame.sceneFlags & kSceneAlphaTested) != 0u ? 0u : gl_RayFlagsOpaqueEXT; }

float offsetFor(vec3 p) { return max(max(abs(p.x), max(abs(p.y), abs(p.z))), 1.0) * 1e-4; }

float lightVisibility(uint i, vec3 p, vec3 ng, inout uint rng) {
  LightRecord light = Lights(frame.lights).l[i];
  float dist;
  vec3 dir = sampleLightDirection(light, p, vec2(rnd(rng), rnd(rng)), dist);
  if (dot(dir, ng) <= 0.0) return 0.0;
  float eps = offsetFor(p);
  visible = 0u;
  traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | baseRayFlags(),
              kMaskCastsShadow, 0, 0, 1, p + ng * eps, 0.0, dir, max(dist - eps, 0.0), 1);
  return float(visible);
}

#include "lib/shading.glsl"

// One specular event at a surface. `n`, `ng` face the incoming ray; `entering`: the ray is outside
// the object (for closed meshes, by the triangle's winding). Updates the ray and the throughput.
void scatter(inout vec3 dir, inout vec3 origin, inout vec3 beta, vec3 p, vec3 n, vec3 ng, bool entering,
             vec3 baseColor, float metallic, float transmission, float ior, bool thinWalled, inout uint rng) {
  float cosI = clamp(dot(-dir, n), 0.0, 1.0);
  vec3 next;
  if (transmission <= 0.0) {
    // Opaque: the mirror lobe with Schlick Fresnel (metals tint it with their base colour).
    vec3 f0 = mix(vec3(0.04), baseColor, metallic);
    beta *= f0 + (1.0 - f0) * pow(1.0 - cosI, 5.0);
    next = reflect(dir, n);
  } else {
    float etaI = entering ? 1.0 : ior;  // glass in air; GLSL refract() wants etaI / etaT
    float etaT = entering ? ior : 1.0;
    float f = thinWalled ? fresnelDielectric(cosI, 1.0, ior) : fresnelDielectric(cosI, etaI, etaT);
    if (rnd(rng) < f) {
      next = reflect(dir, n);  // chosen with probability F: the weight F/F is 1
    } else {
      // Chosen with probability 1−F; the diffuse share (1−transmission) is the lighting pass's.
      beta *= transmission * baseColor;
      next = thinWalled ? dir : refract(dir, n, etaI / etaT);
      if (dot(next, next) == 0.0) next = reflect(dir, n);  // unreachable when f == 1 under TIR
    }
  }
  // Leave from the side the new ray goes to.
  origin = p + (dot(next, ng) > 0.0 ? ng : -ng) * offsetFor(p);
  dir = normalize(next);
}

// The reflection off an opaque G-buffer surface, demodulated (TECHNIQUES.md §11): no Fresnel (lighting
// applies F0·A + B). At most mirrorRoughness rough: the mirror direction, weight 1; rougher: one GGX
// VNDF sample (Heitz 2018) weighted G2/G1 / (A + B), whose mean is 1. False when the sample leaves
// below the surface (weight 0).
bool firstReflection(inout vec3 dir, out vec3 origin, out vec3 beta, vec3 p, vec3 n, vec3 ng, float roughness,
                     uvec2 px) {
  vec3 next;
  beta = vec3(1.0);
  if (roughness <= frame.mirrorRoughness) {
    next = reflect(dir, n);
  } else {
    // Its own stream: the rest of the path draws the same numbers as the mirror path would.
    uint lobeRng = rngInit(px, frame.frameIndex, frame.seed ^ kGlossyStream);
    vec3 t, b;
    orthonormalBasis(n, t, b);
    vec3 v = -dir;
    vec3 vt = normalize(vec3(dot(v, t), dot(v, b), max(dot(v, n), 1e-4)));  // tangent frame, N = +z
    float alpha = roughness * roughness;
    vec3 h = sampleGgxVndf(vt, alpha, vec2(rnd(lobeRng), rnd(lobeRng)));
    vec3 lt = reflect(-vt, h);
    if (lt.z <= 0.0) return false;
    vec2 ab = dfgTerms(max(dot(n, v), 1e-4), roughness);
    beta = vec3(smithG2OverG1(vt.z, lt.z, alpha) / max(ab.x + ab.y, 1e-4));
    next = t * lt.x + b * lt.y + n * lt.z;
  }
  origin = p + (dot(next, ng) > 0.0 ? ng : -ng) * offsetFor(p);
  dir = normalize(next);
  return true;
}

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  float depth = texelFetch(depthTex, px, 0).r;
  vec4 mat = texelFetch(materialTex, px, 0);
  if (isBackground(depth) || tracedSpecularWeight(mat.r, mat.b) <= 0.0) {
    imageStore(outSpecular, px, vec4(0.0));
    return;
  }
  vec2 uv = (vec2(px) + 0.5) / vec2(gl_LaunchSizeEXT.xy);
  vec3 p = worldFromDepth(frame.worldFromClip, uv, depth);
  vec4 nn = texelFetch(normalTex, px, 0);
  vec3 n = octDecode(nn.xy), ng = octDecode(nn.zw);
  vec3 baseColor = srgbToLinear(texelFetch(albedoTex, px, 0).rgb);
  float ior;
  bool thin;
  unpackIor(mat.a, ior, thin);
  // Entering with the 7-bit ior and leaving with the exact one would make a slab a prism.
  ior = texelFetch(emissiveTex, px, 0).a;
  uint rng = rngInit(uvec2(px), frame.frameIndex, frame.seed ^ kSpecularStream);

  vec3 dir = normalize(p - frame.cameraPosition.xyz);
  vec3 origin;
  vec3 beta = vec3(1.0), radiance = vec3(0.0);
  // The G-buffer surface: P comes from quantised depth, so step off by its reconstruction error.
  float nextDepth = uintBitsToFloat(floatBitsToUint(depth) + 1u);
  float depthError = distance(p, worldFromDepth(frame.worldFromClip, uv, nextDepth));
  if (mat.b > 0.0) {
    scatter(dir, origin, beta, p, n, ng, true, baseColor, mat.g, mat.b, ior, thin, rng);
  } else if (!firstReflection(dir, origin, beta, p, n, ng, mat.r, uvec2(px))) {
    imageStore(outSpecular, px, vec4(0.0, 0.0, 0.0, 1.0));  // the sample left below the surface
    return;
  }
  origin += (origin - p) / max(length(origin - p), 1e-12) * 4.0 * depthError;

  for (uint bounce = 1u; bounce <= min(frame.maxSpecularBounces, kMaxSpecularBounces); ++bounce) {
    payload.t = -1.0;
    traceRayEXT(tlas, baseRayFlags(), kMaskVisible | kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
    if (payload.t < 0.0) {
      radiance += beta * environmentRadiance(dir);
      break;
    }
    SurfacePoint sp;
    MaterialRecord m;
    surfaceAtHit(payload, origin, dir, sp, m);
    bool entering = dot(dir, sp.geometricNormal) < 0.0;
    bool thinHit = m.thickness <= 0.0;
    // Beer–Lambert: leaving a volume, the path inside it was payload.t long.
    if (!entering && !thinHit) beta *= volumeTransmittance(m, payload.t);
    GBufferValues gb = evaluateSurface(m, sp, origin);
    ShadingInput s;
    s.p = sp.position;
    s.n = octDecode(gb.normals.xy);
    s.ng = octDecode(gb.normals.zw);
    s.v = -dir;
    s.baseColor = srgbToLinear(gb.albedo.rgb);
    s.metallic = gb.material.g;
    s.roughness = gb.material.r;
    s.transmission = gb.material.b;
    s.ao = gb.albedo.a;
    s.emissive = gb.emissive.rgb;
    s.tracedWeight = tracedSpecular(s.roughness, s.transmission) ? 1.0 : 0.0;
    s.envOcclusion = 1.0;  // no AO at hits
    s.useIndirect = false;
    s.indirect = vec3(0.0);
    radiance += beta * shadeSurface(s, true, rng);
    if (!tracedSpecular(s.roughness, s.transmission)) break;  // rough: fully shaded, the path ends
    scatter(dir, origin, beta, s.p, s.n, s.ng, entering, s.baseColor, s.metallic, s.transmission, m.ior, thinHit,
            rng);
    if (max(beta.r, max(beta.g, beta.b)) < 1e-3) break;
  }
  // Clamp fireflies of the stochastic glass paths to a bright but finite value before accumulation.
  imageStore(outSpecular, px, vec4(min(radiance, vec3(64.0)), 1.0));
}
