// BSDF sampling of the path tracer. The opaque lobes are lib/brdf.glsl's evalBsdfCos() (Lambert
// diffuse + GGX specular, the hybrid's own model), sampled by a mixture of GGX VNDF reflection
// (shared/vndf.h) and cosine-weighted diffuse with a density MIS can evaluate; glass (transmission)
// is the rough or smooth dielectric interface: VNDF microfacet normal, reflect with the exact
// Fresnel probability else refract (Walter et al. 2007), weight G2/G1. Needs lib/brdf.glsl,
// lib/light_select.glsl (luminance) and shared/vndf.h.
#ifndef RAYSTER_PT_BSDF_GLSL
#define RAYSTER_PT_BSDF_GLSL

// Below this α the glass interface is a perfect (delta) one.
const float kSmoothAlpha = 1e-4;

// Probability of sampling the specular lobe: its share of the directional albedo at the view angle,
// kept within [0.1, 0.9] while both lobes exist so neither is starved.
float specularProbability(SurfaceBsdf b, float nv) {
  float fs = luminance(fresnelSchlick(b.f0, b.f90, nv));
  float fd = luminance(b.diffuse) * (1.0 - fs);
  if (fd <= 0.0) return 1.0;
  if (fs <= 0.0) return 0.0;
  return clamp(fs / (fs + fd), 0.1, 0.9);
}

// Solid-angle density of sampleOpaque() for direction l.
float opaquePdf(SurfaceBsdf b, float pSpec, vec3 n, vec3 v, vec3 l) {
  float nl = dot(n, l);
  if (nl <= 0.0) return 0.0;
  vec3 h = normalize(v + l);
  float nv = max(dot(n, v), 1e-4);
  // VNDF density of H is G1(V)·(V·H)·D(H)/(N·V); of L, that / (4 V·H).
  float specular = smithG1(nv, b.alpha) * ggxDistribution(max(dot(n, h), 0.0), b.alpha) / (4.0 * nv);
  return pSpec * specular + (1.0 - pSpec) * nl / kPi;
}

vec3 toWorld(vec3 t, vec3 b, vec3 n, vec3 d) { return t * d.x + b * d.y + n * d.z; }

// A direction from the opaque lobes (u.z picks the lobe).
vec3 sampleOpaque(SurfaceBsdf b, float pSpec, vec3 n, vec3 v, vec3 u) {
  if (u.z >= pSpec) return cosineSampleHemisphere(n, u.xy);
  vec3 t, bt;
  orthonormalBasis(n, t, bt);
  vec3 vt = normalize(vec3(dot(v, t), dot(v, bt), max(dot(v, n), 1e-4)));
  vec3 h = sampleGgxVndf(vt, b.alpha, u.xy);
  return toWorld(t, bt, n, reflect(-vt, h));
}

// The glass interface: `n` faces v; `entering` from outside the volume (the winding); thin walls
// transmit unbent. False when the sample leaves on the wrong side (the path ends). The weight is
// f·cos/pdf: G2/G1 (1 for smooth glass), × `tint` for transmission; KHR_materials_specular's
// `specular` tints and scales the reflection (specularGlassFresnel(), lib/brdf.glsl).
bool sampleDielectric(vec3 n, vec3 v, float roughness, float ior, bool entering, bool thin, vec3 tint, vec4 specular,
                      vec3 u, out vec3 l, out vec3 weight) {
  float etaI = (entering || thin) ? 1.0 : ior, etaT = (entering || thin) ? ior : 1.0;
  float alpha = roughness * roughness;
  vec3 t, bt;
  orthonormalBasis(n, t, bt);
  vec3 vt = normalize(vec3(dot(v, t), dot(v, bt), max(dot(v, n), 1e-4)));
  vec3 ht = alpha > kSmoothAlpha ? sampleGgxVndf(vt, alpha, u.xy) : vec3(0.0, 0.0, 1.0);
  vec3 h = toWorld(t, bt, n, ht);
  float f = fresnelDielectric(clamp(dot(v, h), 0.0, 1.0), etaI, etaT);
  vec3 fr = specularGlassFresnel(f, ior, specular);
  float pr = max(fr.r, max(fr.g, fr.b));
  weight = vec3(1.0);
  if (u.z < pr) {
    weight = fr / pr;
    l = reflect(-v, h);
    if (dot(l, n) <= 0.0) return false;
  } else {
    l = thin ? -v : refract(-v, h, etaI / etaT);
    if (dot(l, l) == 0.0 || dot(l, n) >= 0.0) return false;
    weight = tint;
  }
  l = normalize(l);
  if (alpha > kSmoothAlpha) weight *= smithG2OverG1(vt.z, abs(dot(l, n)), alpha);
  return true;
}

#endif
