// Shading of a surface point by direct light, emission and environment: one function for the
// deferred lighting pass and for every hit of the specular bounce loop (docs/techniques.md §12).
// The includer defines `float lightVisibility(uint light, vec3 p, vec3 ng, inout uint rng)`:
// the lighting pass reads the traced shadow image, the bounce loop traces a shadow ray; and
// `void skipLightVisibility(inout uint rng)`, which draws the random numbers lightVisibility would
// have drawn without tracing (a light that cannot contribute keeps the path's later samples as
// they were).
// The clear coat and sheen (KHR_materials_clearcoat, _sheen) shade as the path tracer's layered
// BSDF does for direct light (lib/layer_lobes.glsl); their ambient, environment and indirect light
// is the untraced kind (the coat's reflection of the environment or the probes, not a traced ray).
// Needs lib/lights.glsl, lib/light_select.glsl, lib/brdf.glsl and lib/environment.glsl.
#ifndef RAYSTER_SHADING_GLSL
#define RAYSTER_SHADING_GLSL

#include "lib/specular_weight.glsl"
#include "shared/sheen.h"
#include "lib/layer_lobes.glsl"

struct ShadingInput {
  vec3 p;          // position
  vec3 n;          // shading normal (facing the viewer)
  vec3 ng;         // geometric normal (facing the viewer)
  vec3 v;          // towards the viewer
  vec3 baseColor;  // linear
  float metallic;
  float roughness;
  float transmission;
  vec4 specular;       // KHR_materials_specular: F0 tint and strength (GBufferValues::specular, decoded)
  float ior;           // for the dielectric F0 (the exact one: the G-buffer's emissive.a)
  float ao;            // the material's occlusion texture
  vec3 emissive;
  float tracedWeight;  // share of the specular light traced elsewhere (tracedSpecularWeight()); not added here
  float envOcclusion;  // ray-traced AO: scales ambient and environment light only, never direct light
  bool useIndirect;    // diffuse indirect light is `indirect` (RT one bounce), not ambient + SH environment
  vec3 indirect;       // irradiance E of the diffuse indirect light, when useIndirect
  bool useIndirectSpecular;  // the untraced specular light is indirectSpecular / π (probes), not the environment's
  vec3 indirectSpecular;     // irradiance E about the mirror direction reflect(−v, n)
  // The traced share's highlight of lights no traced ray can see — suns (their rays miss to the
  // environment) and every light without a visible shape (kLightVisibleShape: punctual lights of
  // glTF files and scene files) — added here: the G-buffer's surfaces (lighting, direct.rgen); not
  // the bounce loop's hits, where it would cost a shadow ray per mirror hit.
  bool sunHighlights;
  // And how much wider than the surface's own roughness that highlight is drawn (a GGX α added):
  // half the angle the shading normal turns across a pixel, so a highlight smaller than a pixel
  // (a mirror sphere's reflection of the sun) is spread over the pixel, not hit or missed by its
  // centre. 0 at the bounce loop's hits.
  float highlightWiden;
  // The layers (GBufferValues::coat, ::sheen; setLayers()): 0 factor and colour without them.
  float clearcoat;
  float coatRoughness;
  vec3 coatNormal;  // facing the viewer
  vec3 sheenColor;
  float sheenRoughness;
};

// The layers from GBufferValues::coat and ::sheen (or their G-buffer encoding, decodeLayers()).
void setLayers(inout ShadingInput s, vec4 coat, vec4 sheen) {
  s.clearcoat = coat.z;
  s.coatRoughness = coat.w;
  s.coatNormal = coat.z > 0.0 ? octDecode(coat.xy) : s.n;
  if (dot(s.coatNormal, s.v) < 0.0) s.coatNormal = reflect(s.coatNormal, s.ng);  // seen from behind: the shading normal's side
  s.sheenColor = sheen.rgb;
  s.sheenRoughness = sheen.a;
}

// Whether shadeSurface() reads s.indirect (a base with a diffuse share, a sheen) or
// s.indirectSpecular (the untraced specular share, a coat): a smooth metal or clear glass reads
// neither, so a caller can leave out the probe lookup (the specular loop's mirror and glass hits).
bool readsIrradiance(ShadingInput s) {
  return (s.metallic < 1.0 && s.transmission < 1.0) || any(greaterThan(s.sheenColor, vec3(0.0))) ||
         s.useIndirectSpecular || s.clearcoat > 0.0;
}

// What the base keeps of light it sends towards v under the layers: 1 − the coat's view Fresnel,
// times the sheen's albedo scaling at the view. Multiplies the traced specular light of the base
// the lighting pass adds to shadeSurface().
float coatKeep(ShadingInput s) { return 1.0 - coatViewFresnel(s.clearcoat, dot(s.coatNormal, s.v)); }
float sheenKeep(ShadingInput s) {
  float nv = max(dot(s.n, s.v), 1e-4);
  return sheenScale(s.sheenColor, s.sheenRoughness, nv, nv);
}
float underLayers(ShadingInput s) { return coatKeep(s) * sheenKeep(s); }

struct ShadingTerms {
  SurfaceBsdf bsdf;
  float w;  // share of the specular light traced elsewhere (s.tracedWeight)
  vec3 fv;  // directional specular albedo (Fresnel at the view angle)
  float fvDiffuse;  // the dielectric lobe's, largest channel: what the diffuse layer under it loses
  float coatKeep;   // 1 − the coat's view Fresnel: what everything under the coat keeps
  float sheenKeep;  // the sheen's albedo scaling at the view: what the base keeps of its ambient light
};

// Untraced specular light from the environment about the mirror direction r at a roughness: the
// GGX-prefiltered levels where they exist, else a blend of radiance and irradiance.
vec3 environmentSpecularOrBlend(vec3 r, float roughness) {
  return (frame.effectFlags & kEffectPrefilteredEnv) != 0u
             ? environmentSpecular(r, roughness)
             : mix(environmentRadiance(r), environmentIrradiance(r) / kPi, roughness);
}

// Fresnel at the view angle, blurred with roughness (its grazing rise fades as the lobe widens).
vec3 viewFresnel(vec3 f0, vec3 f90, float roughness, float nv) {
  return f0 + (max(f90 * (1.0 - roughness), f0) - f0) * pow(1.0 - nv, 5.0);
}

ShadingTerms shadingTerms(ShadingInput s) {
  ShadingTerms t;
  t.bsdf = makeBsdf(s.baseColor, s.metallic, s.roughness, s.specular, s.ior);
  // Transmitted light leaves through the specular path; what is left scatters diffusely.
  t.bsdf.diffuse *= 1.0 - s.transmission;
  t.w = s.tracedWeight;
  float nv = max(dot(s.n, s.v), 1e-4);
  t.fv = viewFresnel(t.bsdf.f0, t.bsdf.f90, s.roughness, nv);
  t.fvDiffuse = viewFresnel(vec3(t.bsdf.diffuseF0), vec3(t.bsdf.diffuseF90), s.roughness, nv).r;
  t.coatKeep = coatKeep(s);
  t.sheenKeep = sheenKeep(s);
  return t;
}

// Light `i`'s direct contribution at s, shadowed by lightVisibility().
vec3 shadeLight(ShadingInput s, ShadingTerms t, uint i, inout uint rng) {
  LightRecord light = loadLight(i);
  vec3 l;
  float dist;
  vec3 incident = lightIncident(light, s.p, l, dist);
  if (all(equal(incident, vec3(0.0)))) return vec3(0.0);
  // A traced reflection sees a light's visible shape: for its share only the diffuse layer here, and
  // the highlight of a light it cannot see (sunHighlights).
  float nl = max(dot(s.n, l), 0.0);
  vec3 f = t.w * (1.0 - t.fvDiffuse) * t.bsdf.diffuse / kPi * nl;
  float widen = light.type == kLightDirectional ? light.angularRadius : light.radius / max(dist, 1e-3);
  if (t.w < 1.0) f += (1.0 - t.w) * evalBsdfCos(t.bsdf, s.n, s.v, l, 0.5 * widen);
  if (t.w > 0.0 && s.sunHighlights && (light.flags & kLightVisibleShape) == 0u)
    f += t.w * evalSpecularCos(t.bsdf, s.n, s.v, l, 0.5 * widen + s.highlightWiden);
  // The layers, as lib/layers.glsl's evalLayeredCos stacks them: sheen on the base, the coat on
  // both. The coat's lobe is never traced: all of it is here, its highlight widened by the light.
  if (any(greaterThan(s.sheenColor, vec3(0.0)))) {
    float nv = max(dot(s.n, s.v), 1e-4);
    f = f * sheenScale(s.sheenColor, s.sheenRoughness, nv, max(nl, 0.0)) + sheenCos(s.sheenColor, s.sheenRoughness, s.n, s.v, l);
  }
  if (s.clearcoat > 0.0) {
    float a = clamp(s.coatRoughness * s.coatRoughness + 0.5 * widen, 1e-4, 1.0);
    f = f * t.coatKeep + coatCos(s.clearcoat, a * a, s.coatNormal, s.v, l);
  }
  // Mirror, metal and glass hits of the bounce loop have no untraced lobe: no shadow ray for them
  // (on whitted's glass bunny every bounce used to trace one for nothing).
  if (all(equal(f, vec3(0.0)))) {
    skipLightVisibility(rng);
    return vec3(0.0);
  }
  // --shadows off (--effects mirrors): no shadow ray, every light reaches what it faces.
  if (!shadowRaysOn()) return f * incident;
  float visibility = lightVisibility(i, s.p, s.ng, rng);
  if (visibility <= 0.0) return vec3(0.0);
  return f * incident * visibility;
}

// Direct light from every light, or (`onePick`) from one light picked by importance and divided by
// the probability of the pick (lib/light_select.glsl): one shadow ray whatever the light count.
vec3 shadeDirect(ShadingInput s, ShadingTerms t, bool onePick, inout uint rng) {
  vec3 radiance = vec3(0.0);
  if (onePick) {
    float invPdf;
    uint i = selectLight(s.p, s.n, rng, invPdf);
    if (i < frame.lightCount) radiance = shadeLight(s, t, i, rng) * invPdf;
  } else {
    for (uint i = 0u; i < frame.lightCount; ++i) radiance += shadeLight(s, t, i, rng);
  }
  return radiance;
}
// One pick in many-light mode (frame.manyLights), else every light.
vec3 shadeDirect(ShadingInput s, ShadingTerms t, inout uint rng) {
  return shadeDirect(s, t, frame.manyLights != 0u, rng);
}

// Everything at s. `direct`: false when the caller adds direct light itself (the lighting pass in
// many-light mode reads it from the denoised stochastic direct-light image).
// `onePick`: direct light from one importance-picked light (shadeDirect()).
vec3 shadeSurface(ShadingInput s, bool direct, bool onePick, inout uint rng) {
  ShadingTerms t = shadingTerms(s);
  SurfaceBsdf bsdf = t.bsdf;
  const float w = t.w;
  float fd = t.fvDiffuse;
  float occlusion = s.ao * s.envOcclusion;

  // Uniform ambient radiance stands in for indirect light: the traced indirect replaces its diffuse part.
  vec3 ambientReflectance = (s.useIndirect ? vec3(0.0) : bsdf.diffuse) + (1.0 - w) * bsdf.f0;
  vec3 radiance = frame.ambient.rgb * ambientReflectance * occlusion;
  // Diffuse: from the traced indirect rays (their misses see the environment, so the SH term would
  // count it twice), else the SH irradiance scaled by AO. Specular (the untraced share) along the
  // mirror direction, blurred towards the irradiance as roughness grows, scaled by AO.
  if (s.useIndirect) radiance += bsdf.diffuse * s.indirect / kPi * (1.0 - fd) * s.ao;
  if (s.useIndirectSpecular) {
    // The probes see the room as well as the sky: their irradiance about r over π is the cosine-
    // weighted radiance around the mirror direction, a rough lobe's blur. The probes are too far
    // apart to see a contact shadow (a sphere on a floor), so AO scales it as it scaled the
    // environment's.
    if (w < 1.0) radiance += (1.0 - w) * t.fv * s.indirectSpecular / kPi * occlusion;
    if (!s.useIndirect && frame.environmentKind != kEnvironmentBlack)
      radiance += bsdf.diffuse * environmentIrradiance(s.n) / kPi * (1.0 - fd) * occlusion;
  } else if (frame.environmentKind != kEnvironmentBlack) {
    if (!s.useIndirect) radiance += bsdf.diffuse * environmentIrradiance(s.n) / kPi * (1.0 - fd) * occlusion;
    if (w < 1.0) {
      radiance += (1.0 - w) * t.fv * environmentSpecularOrBlend(reflect(-s.v, s.n), s.roughness) * occlusion;
    }
  }
  // The base's ambient, environment and indirect light under the layers, and theirs: the sheen's
  // (a broad lobe: the diffuse light's radiance times its albedo) and the coat's reflection (the
  // probes' about the mirror direction, else the environment's at the coat's roughness).
  radiance *= t.coatKeep * t.sheenKeep;
  if (any(greaterThan(s.sheenColor, vec3(0.0)))) {
    float nv = max(dot(s.n, s.v), 1e-4);
    vec3 e = s.sheenColor * min(sheenAlbedo(nv, s.sheenRoughness), 1.0);
    vec3 around = s.useIndirect ? s.indirect / kPi * s.ao
                                : (frame.ambient.rgb + (frame.environmentKind != kEnvironmentBlack
                                                            ? environmentIrradiance(s.n) / kPi
                                                            : vec3(0.0))) * occlusion;
    radiance += t.coatKeep * e * around;
  }
  if (s.clearcoat > 0.0) {
    float fc = 1.0 - t.coatKeep;
    vec3 coatLight = frame.ambient.rgb;
    if (s.useIndirectSpecular)
      coatLight += s.indirectSpecular / kPi;
    else if (frame.environmentKind != kEnvironmentBlack)
      coatLight += environmentSpecularOrBlend(reflect(-s.v, s.coatNormal), s.coatRoughness);
    radiance += fc * coatLight * occlusion;
  }
  radiance += s.emissive;
  if (direct) radiance += shadeDirect(s, t, onePick, rng);
  return radiance;
}

vec3 shadeSurface(ShadingInput s, bool direct, inout uint rng) {
  return shadeSurface(s, direct, frame.manyLights != 0u, rng);
}

#endif
