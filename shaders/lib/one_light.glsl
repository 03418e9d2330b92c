// Direct light at a secondary hit from one light chosen in proportion to its importance
// (lib/light_select.glsl: exact over few lights, resampled candidates over many), divided by the
// probability of the pick; shared by the indirect rays (indirect.rgen) and the probe rays
// (probe_trace.rgen). The includer defines lightVisibility(i, p, ng, rng) (its shadow ray).
#ifndef RAYSTER_ONE_LIGHT_GLSL
#define RAYSTER_ONE_LIGHT_GLSL

// `tracedHit`: the ray goes on through this specular surface (a probe ray's specular chain) and
// sees the lights' visible shapes there, so only a light without one (a sun, a glTF punctual light:
// no kLightVisibleShape) keeps its specular lobe.
vec3 directFromOneLight(SurfaceBsdf bsdf, vec3 p, vec3 n, vec3 ng, vec3 v, bool tracedHit, inout uint rng) {
  float invPdf;
  uint chosen = selectLight(p, n, rng, invPdf);
  if (chosen >= frame.lightCount) return vec3(0.0);
  LightRecord light = loadLight(chosen);
  vec3 l;
  float dist;
  vec3 incident = lightIncident(light, p, l, dist);
  if (shadowRaysOn() && lightVisibility(chosen, p, ng, rng) == 0.0) return vec3(0.0);  // --shadows off: none
  float widen = light.type == kLightDirectional ? light.angularRadius : light.radius / max(dist, 1e-3);
  if (tracedHit && (light.flags & kLightVisibleShape) != 0u) bsdf.f0 = bsdf.f90 = vec3(0.0);
  return evalBsdfCos(bsdf, n, v, l, 0.5 * widen) * incident * invPdf;
}

vec3 directFromOneLight(SurfaceBsdf bsdf, vec3 p, vec3 n, vec3 ng, vec3 v, inout uint rng) {
  return directFromOneLight(bsdf, p, n, ng, v, false, rng);
}

#endif
