#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/ray_flags.glsl"
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
#include "lib/light_ray.glsl"
#include "lib/specular_weight.glsl"
#include "shared/vndf.h"

// Ray-traced reflections and refractions (docs/techniques.md §12, §13): from every G-buffer pixel whose
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
layout(set = 0, binding = 8) uniform sampler2D specularGbufTex;  // encodeSpecular(): F0 tint, strength

layout(location = 0) rayPayloadEXT PrimaryPayload payload;
layout(location = 1) rayPayloadEXT uint visible;


float lightVisibility(uint i, vec3 p, vec3 ng, inout uint rng) {
  vec3 origin, dir;
  float tMax;
  if (!lightShadowRay(i, p, ng, hitRayOffset(p), rng, origin, dir, tMax)) return 0.0;
  visible = 0u;
  traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | sceneRayFlags(),
              kMaskCastsShadow, 0, 0, 1, origin, 0.0, dir, tMax, 1);
  return float(visible);
}
void skipLightVisibility(inout uint rng) { skipLightShadowRay(rng); }

#include "lib/shading.glsl"

#include "lib/specular_path.glsl"

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  vec3 origin, dir, beta;
  bool glossy;
  vec4 result;
  uint rng;
  if (!specularFirstRay(px, origin, dir, beta, glossy, result, rng)) {
    imageStore(outSpecular, px, result);
    return;
  }
  vec3 radiance = vec3(0.0);
  for (uint bounce = 1u; bounce <= min(frame.maxSpecularBounces, kMaxSpecularBounces); ++bounce) {
    payload.t = -1.0;
    traceRayEXT(tlas, sceneRayFlags(), kMaskVisible | kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
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
    s.specular = gb.specular;
    s.ior = m.ior;
    s.ao = gb.albedo.a;
    s.emissive = gb.emissive.rgb;
    s.tracedWeight = tracedSpecular(s.roughness, s.transmission) ? 1.0 : 0.0;
    s.envOcclusion = 1.0;  // no AO at hits
    s.useIndirect = false;
    s.indirect = vec3(0.0);
    // A glossy lobe averages its hits over frames and pixels anyway: there one light picked by
    // importance (divided by its probability) stands in for the loop over all lights.
    radiance += beta * shadeSurface(s, true, glossy || frame.manyLights != 0u, rng);
    if (!tracedSpecular(s.roughness, s.transmission)) break;  // rough: fully shaded, the path ends
    scatter(dir, origin, beta, s.p, s.n, s.ng, entering, s.baseColor, s.metallic, s.transmission, m.ior, thinHit,
            gb.specular, rng);
    if (max(beta.r, max(beta.g, beta.b)) < 1e-3) break;
  }
  // Clamp fireflies of the stochastic glass paths to a bright but finite value before accumulation.
  imageStore(outSpecular, px, vec4(min(radiance, vec3(64.0)), 1.0));
}
