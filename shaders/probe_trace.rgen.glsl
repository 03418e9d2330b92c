#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/ray_flags.glsl"
#include "lib/lights.glsl"
#include "lib/light_select.glsl"
#include "lib/light_ray.glsl"
#include "lib/textures.glsl"
#include "lib/surface.glsl"
#include "lib/sphere.glsl"
#include "lib/primary_payload.glsl"
#include "lib/hit_surface.glsl"
#include "lib/brdf.glsl"
#include "lib/environment.glsl"
#include "lib/specular_weight.glsl"
#include "lib/specular_scatter.glsl"
#include "shared/probes.h"

// Probe rays (gi-probe-trace, docs/techniques.md §16b): launch (raysPerProbe, probes). Ray r of
// probe i leaves the probe in a rotated spherical-Fibonacci direction; a hit is shaded with its
// emission, direct light from one light picked by importance (shadow ray) and, once the atlases
// hold light, the probes' own irradiance at the hit (one more bounce every frame: multiple
// bounces); a mirror reflects the ray on (up to kProbeSpecularEvents times). A miss sees the
// environment. A hit on the back of a face records a negative distance
// (−0.2 t), which the classifier reads (the probe may be inside geometry); on a single-sided
// surface it also records no light.
// Output (RGBA16F, texel (r, i)): outRays rgb the radiance (pre-exposed), a the hit distance;
// outBounceRays rgb the share of that radiance that came through the probes (the bounce atlas).
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D outRays;
layout(set = 0, binding = 6, rgba16f) uniform writeonly image2D outBounceRays;
layout(set = 0, binding = 3) uniform sampler2D probeIrradianceTex;  // the frame before's (kProbeHistoryValid)
layout(set = 0, binding = 4) uniform sampler2D probeVisibilityTex;
layout(set = 0, binding = 5) uniform sampler2D probeDataTex;
layout(push_constant, scalar) uniform Push { ProbeGrid grid; };

layout(location = 0) rayPayloadEXT PrimaryPayload payload;
layout(location = 1) rayPayloadEXT uint visible;

#include "lib/probes.glsl"

float lightVisibility(uint i, vec3 p, vec3 ng, inout uint rng) {
  vec3 origin, dir;
  float tMax;
  if (!lightShadowRay(i, p, ng, hitRayOffset(p), rng, origin, dir, tMax)) return 0.0;
  visible = 0u;
  traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | sceneRayFlags(),
              kMaskCastsShadow, 0, 0, 1, origin, 0.0, dir, tMax, 1);
  return float(visible);
}

#include "lib/one_light.glsl"

const uint kProbeStream = 0x9e3779b9u;

// Mirror hits (opaque, at most kMirrorRoughness rough) the probe rays reflect off (docs/techniques.md
// §16b): at most this many, then the next hit is shaded (or the ray ends in the environment). Glass
// ends the ray: followed, it spread the light it focuses over the probes' cells.
const uint kProbeSpecularEvents = 3u;

void main() {
  uint r = gl_LaunchIDEXT.x, probe = gl_LaunchIDEXT.y;
  // A probe that just entered its cascade's window has no offset yet (its data is another point's).
  vec3 origin = probeWorldPosition(grid, probe) + (probeFresh(grid, probe) ? vec3(0.0) : probeData(grid, probe).xyz);
  vec3 dir = probeRayDirection(grid, r);
  uint rng = rngInit(uvec2(r, probe), frame.frameIndex, frame.seed ^ kProbeStream);
  // The first segment's hit decides the distance (the visibility moments, the classifier); the
  // radiance follows mirrors: a diffuse wall beside one sees the light it sends, and after a
  // reflection a light's visible shape too (light → mirror → probe: no direct-light estimate
  // carries that path).
  vec3 radiance = vec3(0.0), bounce = vec3(0.0), beta = vec3(1.0);
  float distance = grid.maxDistance;
  bool backFace = false;
  for (uint event = 0u; event <= kProbeSpecularEvents; ++event) {
    payload.t = -1.0;
    // Casters only at first, as the indirect rays: a light's visible shape is direct light, counted already.
    uint mask = event == 0u ? kMaskCastsShadow : kMaskVisible | kMaskCastsShadow;
    traceRayEXT(tlas, sceneRayFlags(), mask, 0, 0, 0, origin, 0.0, dir, grid.maxDistance, 0);
    if (payload.t < 0.0) {
      radiance += beta * environmentRadiance(dir);
      break;
    }
    SurfacePoint sp;
    MaterialRecord m;
    surfaceAtHit(payload, origin, dir, sp, m);
    // The back of a face (by its winding): the probe may be inside geometry, which the classifier
    // reads from a negative distance. A single-sided surface sends no light back; a double-sided
    // one is shaded as usual (a thin wall or leaf seen from behind).
    bool back = dot(sp.geometricNormal, dir) > 0.0;
    if (event == 0u) {
      distance = payload.t;
      backFace = back;
    }
    if (back && (m.flags & kMaterialDoubleSided) == 0u) break;
    GBufferValues gb = evaluateSurface(m, sp, origin);  // normals face the ray
    vec3 hn = octDecode(gb.normals.xy), hng = octDecode(gb.normals.zw);
    float roughness = gb.material.r, transmission = gb.material.b;
    SurfaceBsdf bsdf = makeBsdf(srgbToLinear(gb.albedo.rgb), gb.material.g, roughness, gb.specular, m.ior);
    bsdf.diffuse *= 1.0 - transmission;
    bool goesOn = roughness <= kMirrorRoughness && transmission <= 0.0 && event < kProbeSpecularEvents;
    radiance += beta * (gb.emissive.rgb + directFromOneLight(bsdf, sp.position, hn, hng, -dir, goesOn, rng));
    // A mirror (a metal: no diffuse share) reads no probes; its reflection goes on instead.
    if ((grid.flags & kProbeHistoryValid) != 0u && any(greaterThan(bsdf.diffuse, vec3(0.0))))
      bounce += beta * bsdf.diffuse / kPi * probeIrradiance(grid, sp.position, hn, -dir) * gb.albedo.a *
                grid.historyScale;
    if (!goesOn) break;
    scatter(dir, origin, beta, sp.position, hn, hng, true, srgbToLinear(gb.albedo.rgb), gb.material.g, 0.0, m.ior,
            true, gb.specular, rng);  // an opaque mirror: the Fresnel-weighted reflection
    if (max(beta.r, max(beta.g, beta.b)) < 1e-3) break;
  }
  // A firefly clamp on the whole (bright but finite, its hue kept), the bounce share scaled with it.
  vec3 total = max(radiance, vec3(0.0)) + max(bounce, vec3(0.0));
  float scale = 256.0 / max(256.0, max(total.r, max(total.g, total.b)));
  bounce = max(bounce, vec3(0.0)) * scale;
  vec4 result = vec4(total * scale, backFace ? -0.2 * distance : distance);
  imageStore(outRays, ivec2(r, probe), result);
  imageStore(outBounceRays, ivec2(r, probe), vec4(bounce, 0.0));
}
