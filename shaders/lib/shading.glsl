// Shading of a surface point by direct light, emission and environment: one function for the
// deferred lighting pass and for every hit of the specular bounce loop (TECHNIQUES.md §10).
// The includer defines `float lightVisibility(uint light, vec3 p, vec3 ng, inout uint rng)`:
// the lighting pass reads the traced shadow image, the bounce loop traces a shadow ray.
// Needs lib/lights.glsl, lib/light_select.glsl, lib/brdf.glsl and lib/environment.glsl.
#ifndef RAYSTER_SHADING_GLSL
#define RAYSTER_SHADING_GLSL

// Surfaces this smooth, and all transmissive ones, get their specular light from traced rays
// (the bounce loop); rougher ones from the light sources and the environment map. Glossy
// reflections with VNDF sampling and a denoiser replace this split later (TECHNIQUES.md §11).
const float kMirrorRoughness = 0.1;

bool tracedSpecular(float roughness, float transmission) {
  return roughness <= kMirrorRoughness || transmission > 0.0;
}

struct ShadingInput {
  vec3 p;          // position
  vec3 n;          // shading normal (facing the viewer)
  vec3 ng;         // geometric normal (facing the viewer)
  vec3 v;          // towards the viewer
  vec3 baseColor;  // linear
  float metallic;
  float roughness;
  float transmission;
  float ao;
  vec3 emissive;
};

struct ShadingTerms {
  SurfaceBsdf bsdf;
  bool traced;  // specular from traced rays, not from the light sources
  vec3 fv;      // directional specular albedo (Fresnel at the view angle)
};

ShadingTerms shadingTerms(ShadingInput s) {
  ShadingTerms t;
  t.bsdf = makeBsdf(s.baseColor, s.metallic, s.roughness);
  // Transmitted light leaves through the specular path; what is left scatters diffusely.
  t.bsdf.diffuse *= 1.0 - s.transmission;
  t.traced = tracedSpecular(s.roughness, s.transmission);
  float nv = max(dot(s.n, s.v), 1e-4);
  t.fv = t.bsdf.f0 + (max(vec3(1.0 - s.roughness), t.bsdf.f0) - t.bsdf.f0) * pow(1.0 - nv, 5.0);
  return t;
}

// Light `i`'s direct contribution at s, shadowed by lightVisibility().
vec3 shadeLight(ShadingInput s, ShadingTerms t, uint i, inout uint rng) {
  LightRecord light = Lights(frame.lights).l[i];
  vec3 l;
  float dist;
  vec3 incident = lightIncident(light, s.p, l, dist);
  if (all(equal(incident, vec3(0.0)))) return vec3(0.0);
  float visibility = lightVisibility(i, s.p, s.ng, rng);
  if (visibility <= 0.0) return vec3(0.0);
  vec3 f;
  if (t.traced) {
    // The traced reflection already sees the light's visible shape: only the diffuse layer here.
    float nl = max(dot(s.n, l), 0.0);
    f = (1.0 - t.fv) * t.bsdf.diffuse / kPi * nl;
  } else {
    float widen = light.type == kLightDirectional ? light.angularRadius : light.radius / max(dist, 1e-3);
    f = evalBsdfCos(t.bsdf, s.n, s.v, l, 0.5 * widen);
  }
  return f * incident * visibility;
}

// Direct light from every light, or (frame.manyLights) from one light picked by importance and
// divided by the probability of the pick (lib/light_select.glsl).
vec3 shadeDirect(ShadingInput s, ShadingTerms t, inout uint rng) {
  vec3 radiance = vec3(0.0);
  if (frame.manyLights != 0u) {
    float invPdf;
    uint i = selectLight(s.p, s.n, rng, invPdf);
    if (i < frame.lightCount) radiance = shadeLight(s, t, i, rng) * invPdf;
  } else {
    for (uint i = 0u; i < frame.lightCount; ++i) radiance += shadeLight(s, t, i, rng);
  }
  return radiance;
}

// Everything at s. `direct`: false when the caller adds direct light itself (the lighting pass in
// many-light mode reads it from the denoised stochastic direct-light image).
vec3 shadeSurface(ShadingInput s, bool direct, inout uint rng) {
  ShadingTerms t = shadingTerms(s);
  SurfaceBsdf bsdf = t.bsdf;
  const bool traced = t.traced;
  vec3 fv = t.fv;
  vec3 radiance = s.emissive + frame.ambient.rgb * (bsdf.diffuse + (traced ? vec3(0.0) : bsdf.f0)) * s.ao;
  if (direct) radiance += shadeDirect(s, t, rng);
  // Unshadowed environment light until ray-traced AO exists: diffuse from the SH irradiance,
  // specular (for surfaces the bounce loop does not handle) along the mirror direction, blurred
  // towards the irradiance as roughness grows.
  if (frame.environmentKind != kEnvironmentBlack) {
    radiance += bsdf.diffuse * environmentIrradiance(s.n) / kPi * (1.0 - fv) * s.ao;
    if (!traced) {
      vec3 r = reflect(-s.v, s.n);
      vec3 specularEnv = mix(environmentRadiance(r), environmentIrradiance(r) / kPi, s.roughness);
      radiance += fv * specularEnv * s.ao;
    }
  }
  return radiance;
}

#endif
