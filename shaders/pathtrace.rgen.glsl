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
#include "shared/vndf.h"
#include "lib/pt_lights.glsl"
#include "lib/pt_bsdf.glsl"
#include "shared/sheen.h"
#include "lib/layers.glsl"

// The reference: progressive unidirectional path tracing (docs/techniques.md §21), one sample per pixel per
// frame, accumulated as a running mean (and mean square, for the variance) in fp32. At every vertex,
// next-event estimation to every analytic light (sphere and sun lights by solid angle; more than
// kAllLights lights: one picked uniformly), to one point of the emissive triangles and to one
// environment direction, combined with BSDF sampling by multiple importance sampling (power
// heuristic); glass events are BSDF-sampled only (their emitter hits weigh 1). Radiance rays see
// shadow casters only: a light's visible shape (castsShadows false) is the analytic sphere light,
// hit by hitSphereLight(). Russian roulette from kRouletteDepth vertices; frame.maxDepth vertices.
layout(set = 0, binding = 1) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D prevMean;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D prevMoments;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D outMean;
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D outMoments;

layout(location = 0) rayPayloadEXT PrimaryPayload payload;
layout(location = 1) rayPayloadEXT uint visible;

const uint kPathTraceStream = 0x9A7E0u;
const uint kRouletteDepth = 3u;  // vertices before roulette: short paths keep their full weight
const uint kAllLights = 16u;     // up to this many analytic lights, each gets a shadow ray per vertex

float offsetFor(vec3 p) { return max(max(abs(p.x), max(abs(p.y), abs(p.z))), 1.0) * 1e-4; }

bool unoccluded(vec3 p, vec3 ng, vec3 dir, float dist) {
  float eps = offsetFor(p);
  visible = 0u;
  traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT | sceneRayFlags(),
              kMaskCastsShadow, 0, 0, 1, p + (dot(dir, ng) > 0.0 ? ng : -ng) * eps, 0.0, dir, max(dist - eps, 0.0), 1);
  return visible != 0u;
}

// Power heuristic (β = 2) for the strategy of density `a` against `b`.
float misWeight(float a, float b) {
  if (a <= 0.0) return 0.0;
  float r = b / a;
  return 1.0 / (1.0 + r * r);
}

float lightPickProbability() { return frame.lightCount <= kAllLights ? 1.0 : 1.0 / float(frame.lightCount); }

struct PathVertex {
  vec3 p, n, ng, v;
  SurfaceBsdf bsdf;
  float pSpec;
  float opaqueShare;  // 1 − the glass lobe's share: NEE estimates this part of the BSDF
  bool layered;       // the material has layers (lib/layers.glsl): `layers` holds them
  SurfaceLayers layers;
};

// Density with which BSDF sampling would have produced l (the opaque lobes).
float bsdfPdf(PathVertex x, vec3 l) {
  if (x.layered) return x.opaqueShare * layeredPdf(x.bsdf, x.layers, x.n, x.v, l);
  return x.opaqueShare * opaquePdf(x.bsdf, x.pSpec, x.n, x.v, l);
}

// f·cos for a light direction, 0 below either normal.
vec3 lightBsdf(PathVertex x, vec3 l) {
  if (dot(l, x.ng) <= 0.0) return vec3(0.0);
  if (x.layered) return evalLayeredCos(x.bsdf, x.layers, x.n, x.v, l);
  return evalBsdfCos(x.bsdf, x.n, x.v, l, 0.0);
}

vec3 analyticLight(PathVertex x, uint i, float pick, inout uint rng) {
  LightRecord light = loadLight(i);
  vec3 centreDir;
  float centreDist, dist;
  lightCentre(light, x.p, centreDir, centreDist);
  if (light.type != kLightDirectional && light.radius > 0.0 && centreDist <= light.radius) return vec3(0.0);
  vec3 l = sampleLightDirection(light, x.p, vec2(rnd(rng), rnd(rng)), dist);
  vec3 f = lightBsdf(x, l);
  if (all(equal(f, vec3(0.0))) || !unoccluded(x.p, x.ng, l, dist)) return vec3(0.0);
  float oneMinusCos = lightConeOneMinusCos(light, centreDist);
  if (oneMinusCos <= 0.0) {  // a delta light: no BSDF ray can hit it
    vec3 d;
    float dd;
    return f * lightIncident(light, x.p, d, dd) / pick;
  }
  float pdf = pick / (2.0 * kPi * oneMinusCos);
  return f * lightSurfaceRadiance(light, l, oneMinusCos) / pdf * misWeight(pdf, bsdfPdf(x, l));
}

vec3 nextEvent(PathVertex x, inout uint rng) {
  vec3 sum = vec3(0.0);
  uint count = frame.lightCount;
  if (count <= kAllLights) {
    for (uint i = 0u; i < count; ++i) sum += analyticLight(x, i, 1.0, rng);
  } else {
    sum += analyticLight(x, min(uint(rnd(rng) * float(count)), count - 1u), lightPickProbability(), rng);
  }
  if (frame.emissiveTriangleCount > 0u) {
    vec3 q, nq, le;
    sampleEmissive(vec3(rnd(rng), rnd(rng), rnd(rng)), x.p, q, nq, le);
    vec3 d = q - x.p;
    float dist = length(d);
    vec3 l = d / max(dist, 1e-12);
    float cosL = abs(dot(nq, l));
    vec3 f = lightBsdf(x, l);
    if (cosL > 1e-6 && any(greaterThan(f * le, vec3(0.0))) && unoccluded(x.p, x.ng, l, dist * (1.0 - 1e-3))) {
      float pdf = dist * dist / (frame.emissiveArea * cosL);
      sum += f * le / pdf * misWeight(pdf, bsdfPdf(x, l));
    }
  }
  if (frame.environmentCdfWidth > 0u) {
    float pdf;
    vec3 l = sampleEnvironment(vec2(rnd(rng), rnd(rng)), pdf);
    vec3 f = lightBsdf(x, l);
    if (pdf > 0.0 && any(greaterThan(f, vec3(0.0))) && unoccluded(x.p, x.ng, l, 1e30))
      sum += f * environmentRadiance(l) / pdf * misWeight(pdf, bsdfPdf(x, l));
  }
  return sum;
}

// What a ray that escapes the scene sees: the environment and the disks of sun lights, weighted
// against their light sampling (pdf: the BSDF density of the ray; 0 from the camera or glass).
vec3 escaped(vec3 dir, float pdf) {
  vec3 le = environmentRadiance(dir);
  if (pdf > 0.0 && frame.environmentCdfWidth > 0u) le *= misWeight(pdf, environmentPdf(dir));
  for (uint i = 0u; i < frame.lightCount; ++i) {
    LightRecord l = loadLight(i);
    if (l.type != kLightDirectional || l.angularRadius <= 0.0) continue;
    float oneMinusCos = lightConeOneMinusCos(l, 0.0);
    if (dot(dir, -normalize(l.direction)) < 1.0 - oneMinusCos) continue;
    float w = pdf > 0.0 ? misWeight(pdf, lightPickProbability() / (2.0 * kPi * oneMinusCos)) : 1.0;
    le += lightSurfaceRadiance(l, dir, oneMinusCos) * w;
  }
  return le;
}

vec3 tracePath(vec3 origin, vec3 dir, inout uint rng) {
  vec3 radiance = vec3(0.0), beta = vec3(1.0);
  int channel = -1;  // the colour channel a dispersive refraction picked for the path; -1: all
  float pdf = 0.0;  // density of the last BSDF sample; 0: the camera ray or a glass event (no MIS)
  for (uint depth = 0u;; ++depth) {
    payload.t = -1.0;
    traceRayEXT(tlas, sceneRayFlags(), kMaskCastsShadow, 0, 0, 0, origin, 0.0, dir, 1e30, 0);
    float tLight;
    uint li = hitSphereLight(origin, dir, payload.t < 0.0 ? 1e30 : payload.t, tLight);
    if (li < frame.lightCount) {
      LightRecord l = loadLight(li);
      float oneMinusCos = lightConeOneMinusCos(l, distance(origin, l.position));
      float w = pdf > 0.0 ? misWeight(pdf, lightPickProbability() / (2.0 * kPi * oneMinusCos)) : 1.0;
      return radiance + beta * lightSurfaceRadiance(l, dir, oneMinusCos) * w;
    }
    if (payload.t < 0.0) return radiance + beta * escaped(dir, pdf);

    SurfacePoint sp;
    MaterialRecord m;
    surfaceAtHit(payload, origin, dir, sp, m);
    bool entering = dot(dir, sp.geometricNormal) < 0.0;
    bool thin = m.thickness <= 0.0;
    if (!entering && !thin) beta *= volumeTransmittance(m, payload.t);
    GBufferValues gb = evaluateSurface(m, sp, origin);
    PathVertex x;
    x.p = sp.position;
    x.n = octDecode(gb.normals.xy);
    x.ng = octDecode(gb.normals.zw);
    x.v = -dir;

    vec3 emission = gb.emissive.rgb;
    if (any(greaterThan(emission, vec3(0.0)))) {
      float w = 1.0;
      bool listed = Geometries(frame.geometries).g[payload.geometry].kind == kGeometryTriangles;
      if (pdf > 0.0 && listed && frame.emissiveTriangleCount > 0u) {
        float cosL = abs(dot(normalize(sp.geometricNormal), dir));
        w = misWeight(pdf, payload.t * payload.t / max(frame.emissiveArea * cosL, 1e-12));
      }
      radiance += beta * emission * w;
    }
    // Unlit surfaces only emit (render/gpu_materials.cpp): the path ends there.
    if ((m.flags & kMaterialUnlit) != 0u) break;

    float metallic = gb.material.g, roughness = gb.material.r;
    float glassShare = gb.material.b * (1.0 - metallic);
    vec3 baseColor = srgbToLinear(gb.albedo.rgb);
    x.bsdf = makeBsdf(baseColor, metallic, roughness, gb.specular, m.ior);
    x.pSpec = specularProbability(x.bsdf, max(dot(x.n, x.v), 1e-4));
    x.opaqueShare = 1.0 - glassShare;
    x.layered = m.layers != 0ul;
    if (x.layered) {
      vec3 nFace = normalize(sp.normal);
      if (dot(nFace, x.ng) < 0.0) nFace = -nFace;
      x.layers = evaluateLayers(m, sp, x.n, nFace, roughness);
    }
    if (x.opaqueShare > 0.0) radiance += beta * x.opaqueShare * nextEvent(x, rng);
    if (depth + 1u >= frame.maxDepth) break;

    vec3 u = vec3(rnd(rng), rnd(rng), rnd(rng));
    vec3 next;
    if (rnd(rng) < glassShare) {
      // Dispersion (KHR_materials_dispersion): the path follows one colour channel from its first
      // dispersive glass on, picked uniformly (× 3 keeps the estimate unbiased).
      float ior = m.ior;
      if (x.layered && x.layers.dispersion > 0.0) {
        if (channel < 0) {
          channel = min(int(rnd(rng) * 3.0), 2);
          vec3 only = vec3(0.0);
          only[channel] = 3.0;
          beta *= only;
        }
        ior = dispersedIor(m.ior, x.layers.dispersion, channel);
      }
      vec3 weight;
      if (!sampleDielectric(x.n, x.v, roughness, ior, entering, thin, baseColor, gb.specular, u, next, weight)) break;
      beta *= weight;
      pdf = 0.0;
    } else if (x.layered) {
      next = sampleLayered(x.bsdf, x.layers, x.n, x.v, u);
      float p = layeredPdf(x.bsdf, x.layers, x.n, x.v, next);
      if (dot(next, x.ng) <= 0.0 || p <= 0.0) break;
      beta *= evalLayeredCos(x.bsdf, x.layers, x.n, x.v, next) / p;
      pdf = x.opaqueShare * p;
    } else {
      next = sampleOpaque(x.bsdf, x.pSpec, x.n, x.v, u);
      float p = opaquePdf(x.bsdf, x.pSpec, x.n, x.v, next);
      if (dot(next, x.ng) <= 0.0 || p <= 0.0) break;
      beta *= evalBsdfCos(x.bsdf, x.n, x.v, next, 0.0) / p;
      pdf = x.opaqueShare * p;
    }
    if (depth + 1u >= kRouletteDepth) {
      float survive = min(max(beta.r, max(beta.g, beta.b)), 0.95);
      if (rnd(rng) >= survive) break;
      beta /= survive;
    }
    origin = x.p + (dot(next, x.ng) > 0.0 ? x.ng : -x.ng) * offsetFor(x.p);
    dir = next;
  }
  return radiance;
}

void main() {
  ivec2 px = ivec2(gl_LaunchIDEXT.xy);
  uint rng = rngInit(uvec2(px), frame.frameIndex, frame.seed ^ kPathTraceStream);
  // A uniformly jittered position in the pixel: the mean is the box-filtered image.
  vec2 uv = (vec2(px) + vec2(rnd(rng), rnd(rng))) / vec2(gl_LaunchSizeEXT.xy);
  vec3 origin = frame.cameraPosition.xyz;
  vec3 dir = cameraRayDirection(frame.worldFromClip, uv, origin);
  vec3 c = tracePath(origin, dir, rng);
  if (any(isnan(c)) || any(isinf(c))) c = vec3(0.0);  // a degenerate sample must not poison the mean

  // Running mean and mean square over frame.frameIndex + 1 samples (fp32).
  float n = float(frame.frameIndex);
  vec3 mean = frame.frameIndex == 0u ? vec3(0.0) : imageLoad(prevMean, px).rgb;
  vec3 square = frame.frameIndex == 0u ? vec3(0.0) : imageLoad(prevMoments, px).rgb;
  mean += (c - mean) / (n + 1.0);
  square += (c * c - square) / (n + 1.0);
  imageStore(outMean, px, vec4(mean, 1.0));
  imageStore(outMoments, px, vec4(square, n + 1.0));
}
