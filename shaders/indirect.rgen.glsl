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
#include "lib/light_ray.glsl"

// One-bounce indirect diffuse from the G-buffer (docs/techniques.md §16): one cosine-weighted ray about
// the shading normal per pixel per frame. A hit is shaded with its emission, direct light from one
// light picked by importance (shadow ray, divided by the pick probability) and the environment's
// SH irradiance (no AO at hits); a miss sees the environment.
// Output (RGBA16F): rgb = E = π·L, one sample of the irradiance, demodulated (no albedo): lighting
// applies albedo/π·E. Rays see shadow casters only, so a light's visible shape (which the lighting
// pass already counts as direct light) is not counted again. Background and indirect off write 0.
// At quarter rate (--indirect-rate quarter) one pixel per 2×2 block, rotating over 4 frames;
// indirect_fill.comp gives the other three a depth- and normal-weighted mean of traced ones.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;
layout(set = 0, binding = 4, rgba16f) uniform writeonly image2D outIndirect;

layout(location = 0) rayPayloadEXT PrimaryPayload payload;
layout(location = 1) rayPayloadEXT uint visible;


// Direct light at a hit from one light chosen in proportion to its importance (lib/light_select.glsl:
// exact over few lights, resampled candidates over many), divided by the probability of the pick.
vec3 directFromOneLight(SurfaceBsdf bsdf, vec3 p, vec3 n, vec3 ng, vec3 v, inout uint rng) {
  float invPdf;
  uint chosen = selectLight(p, n, rng, invPdf);
  if (chosen >= frame.lightCount) return vec3(0.0);
  LightRecord light = loadLight(chosen);
  vec3 l;
  float dist;
  vec3 incident = lightIncident(light, p, l, dist);
  vec3 origin, dir;
  float tMax;
  if (!lightShadowRay(chosen, p, ng, hitRayOffset(p), rng, origin, dir, tMax)) return vec3(0.0);
  visible = 0u;
  traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | sceneRayFlags(),
              kMaskCastsShadow, 0, 0, 1, origin, 0.0, dir, tMax, 1);
  if (visible == 0u) return vec3(0.0);
  float widen = light.type == kLightDirectional ? light.angularRadius : light.radius / max(dist, 1e-3);
  return evalBsdfCos(bsdf, n, v, l, 0.5 * widen) * incident * invPdf;
}

#include "lib/indirect_ray.glsl"

void main() {
  ivec2 px = indirectPixel(gl_LaunchIDEXT.xy);  // at quarter rate, its 2×2 block's pixel of this frame
  vec3 origin, dir;
  vec4 value;
  uint rng;
  if (!indirectRay(px, origin, dir, value, rng)) {
    imageStore(outIndirect, px, value);
    return;
  }
  payload.t = -1.0;
  traceRayEXT(tlas, sceneRayFlags(), kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
  vec3 radiance;
  if (payload.t < 0.0) {
    radiance = environmentRadiance(dir);
  } else {
    SurfacePoint sp;
    MaterialRecord m;
    surfaceAtHit(payload, origin, dir, sp, m);
    GBufferValues gb = evaluateSurface(m, sp, origin);  // normals face the ray's origin
    vec3 hn = octDecode(gb.normals.xy), hng = octDecode(gb.normals.zw);
    SurfaceBsdf bsdf = makeBsdf(srgbToLinear(gb.albedo.rgb), gb.material.g, gb.material.r, gb.specular, m.ior);
    bsdf.diffuse *= 1.0 - gb.material.b;
    radiance = gb.emissive.rgb + directFromOneLight(bsdf, sp.position, hn, hng, -dir, rng);
    vec3 environmentDiffuse = environmentIrradiance(hn) + frame.ambient.rgb * kPi;
    radiance += bsdf.diffuse / kPi * environmentDiffuse * gb.albedo.a;
  }
  // E = π·L for a cosine-weighted sample; clamp rare fireflies to a bright but finite value.
  imageStore(outIndirect, px, vec4(min(kPi * radiance, vec3(256.0)), 1.0));
}
