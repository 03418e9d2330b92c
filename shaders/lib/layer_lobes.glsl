// The clear-coat and sheen lobes of KHR_materials_clearcoat and KHR_materials_sheen
// (docs/materials.md), one definition for the path tracer's layered BSDF (lib/layers.glsl) and the
// hybrid's deferred shading (lib/shading.glsl). The coat is GGX with the F0 of η 1.5 on top of
// everything, which keeps 1 − its view Fresnel; the sheen is Charlie + Ashikhmin on the base, which
// keeps what the sheen's directional albedo leaves (albedo scaling). Needs lib/brdf.glsl and
// shared/sheen.h.
#ifndef RAYSTER_LAYER_LOBES_GLSL
#define RAYSTER_LAYER_LOBES_GLSL

const float kCoatF0 = 0.04;  // η 1.5 against air

float schlick1(float f0, float c) { return f0 + (1.0 - f0) * pow(1.0 - c, 5.0); }

// The share of light the coat reflects towards v (cv = n_coat·v): what lies under it keeps 1 − it.
float coatViewFresnel(float clearcoat, float cv) { return clearcoat * schlick1(kCoatF0, clamp(cv, 0.0, 1.0)); }

// The coat's f·cos for light from l; nc the coat normal, a2 its GGX α².
float coatCos(float clearcoat, float a2, vec3 nc, vec3 v, vec3 l) {
  float cl = dot(nc, l), cv = max(dot(nc, v), 1e-4);
  if (clearcoat <= 0.0 || cl <= 0.0) return 0.0;
  vec3 h = normalize(v + l);
  return clearcoat * schlick1(kCoatF0, max(dot(v, h), 0.0)) * ggxD(max(dot(nc, h), 0.0), a2) * smithV(cl, cv, a2) * cl;
}

// What the base keeps under the sheen, seen from v and from l (the smaller: reciprocal).
float sheenScale(vec3 sheenColor, float sheenRoughness, float nv, float nl) {
  float c = max(sheenColor.r, max(sheenColor.g, sheenColor.b));
  if (c <= 0.0) return 1.0;
  float e = max(min(sheenAlbedo(nv, sheenRoughness), 1.0), min(sheenAlbedo(nl, sheenRoughness), 1.0));
  return 1.0 - c * e;
}

// The sheen's f·cos for light from l (nl > 0), normalised where Ashikhmin's term would reflect more
// than arrives (shared/sheen.h).
vec3 sheenCos(vec3 sheenColor, float sheenRoughness, vec3 n, vec3 v, vec3 l) {
  float nl = dot(n, l), nv = max(dot(n, v), 1e-4);
  if (nl <= 0.0 || all(lessThanEqual(sheenColor, vec3(0.0)))) return vec3(0.0);
  vec3 h = normalize(v + l);
  float e = sheenAlbedo(nv, sheenRoughness);
  return sheenColor * charlieDistribution(max(dot(n, h), 0.0), sheenAlpha(sheenRoughness)) * ashikhminVisibility(nl, nv) *
         nl / max(e, 1.0);
}

#endif
