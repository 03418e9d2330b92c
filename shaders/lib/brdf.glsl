// GGX specular + Lambert diffuse, glTF metallic-roughness. One definition for every pass that shades.
#ifndef RAYSTER_BRDF_GLSL
#define RAYSTER_BRDF_GLSL

float ggxD(float nh, float a2) {
  float d = nh * nh * (a2 - 1.0) + 1.0;  // >= a2: 0 only for a perfect mirror (a2 = 0) at nh = 1
  return a2 / (kPi * max(d * d, 1e-30));  // there 0 (the delta lobe no light direction hits), not 0/0
}
// Height-correlated Smith visibility term V = G / (4 n·l n·v) (Heitz 2014).
float smithV(float nl, float nv, float a2) {
  float gv = nl * sqrt(nv * nv * (1.0 - a2) + a2);
  float gl = nv * sqrt(nl * nl * (1.0 - a2) + a2);
  return 0.5 / max(gv + gl, 1e-7);
}
vec3 fresnelSchlick(vec3 f0, float vh) { return f0 + (1.0 - f0) * pow(1.0 - vh, 5.0); }
vec3 fresnelSchlick(vec3 f0, vec3 f90, float vh) { return f0 + (f90 - f0) * pow(1.0 - vh, 5.0); }

// Exact dielectric Fresnel reflectance for light arriving at cosine cosI from the side of index
// etaI onto etaT; 1 under total internal reflection.
float fresnelDielectric(float cosI, float etaI, float etaT) {
  float sinT = etaI / etaT * sqrt(max(0.0, 1.0 - cosI * cosI));
  if (sinT >= 1.0) return 1.0;
  float cosT = sqrt(max(0.0, 1.0 - sinT * sinT));
  float rs = (etaI * cosI - etaT * cosT) / (etaI * cosI + etaT * cosT);
  float rp = (etaI * cosT - etaT * cosI) / (etaI * cosT + etaT * cosI);
  return 0.5 * (rs * rs + rp * rp);
}

// Dielectrics reflect F0 = ((η − 1)/(η + 1))² at normal incidence (0.04 at η = 1.5, kept bit for
// bit: the constant every pass used before η was read per pixel).
float dielectricF0(float ior) {
  float r0 = (ior - 1.0) / (ior + 1.0);
  return ior == 1.5 ? 0.04 : r0 * r0;
}

// KHR_materials_specular's dielectric lobe from `specular` (rgb: the F0 tint t, a: the strength s;
// GBufferValues::specular) at index of refraction η: F0 = F0(η)·t·s, where evaluateSurface() made t
// = min(F0(η)·specularColor, 1)/F0(η), so F0 = min(F0(η)·specularColor, 1)·specular as the extension
// says, and F90 = s. F90 also fades to 0 with F0(η) below 0.02 (Filament), so η = 1 reflects nothing
// at any angle. Defaults (t = 1, s = 1) give F0(η) and the old F90 exactly.
void dielectricSpecular(vec4 specular, float ior, out vec3 f0, out float f90) {
  float f0Ior = dielectricF0(ior);
  f0 = f0Ior * specular.rgb * specular.a;
  f90 = clamp(50.0 * f0Ior, 0.0, 1.0) * specular.a;
}

// A glass interface under KHR_materials_specular: the exact Fresnel reflectance `f` at η remapped
// so that its value at normal incidence, F0(η), becomes the lobe's F0 and its grazing value 1
// becomes F90 — Schlick's blend, with the exact curve's own angular weight (f − F0(η))/(1 − F0(η)).
// Refraction takes what the largest channel leaves (the extension's max_value), so the caller picks
// reflection with probability max(F) and weights it F / max(F). Total internal reflection stays
// total; the default (t = 1, s = 1) returns f itself.
vec3 specularGlassFresnel(float f, float ior, vec4 specular) {
  if (f >= 1.0 || specular == vec4(1.0)) return vec3(f);
  vec3 f0;
  float f90;
  dielectricSpecular(specular, ior, f0, f90);
  float f0Ior = dielectricF0(ior);
  float w = clamp((f - f0Ior) / max(1.0 - f0Ior, 1e-6), 0.0, 1.0);
  return f0 + (vec3(f90) - f0) * w;
}

struct SurfaceBsdf {
  vec3 diffuse;  // albedo · (1 − metallic)
  vec3 f0;       // specular reflectance at normal incidence
  vec3 f90;      // at grazing incidence: 1 for metals, the dielectric lobe's F90 otherwise
  float alpha;   // GGX α = roughness²
  // The dielectric lobe's F0 (largest channel) and F90: the diffuse base under it keeps
  // 1 − Schlick(these) (KHR_materials_specular's max_value: a tinted F0 takes the same energy from
  // every channel of the diffuse layer; with a grey F0 this is the per-channel 1 − F).
  float diffuseF0, diffuseF90;
};

SurfaceBsdf makeBsdf(vec3 baseColor, float metallic, float roughness, vec3 dielectricF0, float dielectricF90) {
  SurfaceBsdf s;
  s.diffuse = baseColor * (1.0 - metallic);
  s.f0 = mix(dielectricF0, baseColor, metallic);
  s.f90 = mix(vec3(dielectricF90), vec3(1.0), metallic);
  s.diffuseF0 = max(dielectricF0.r, max(dielectricF0.g, dielectricF0.b));
  s.diffuseF90 = dielectricF90;
  float r = clamp(roughness, 0.02, 1.0);        // a perfect mirror has no point-light highlight at all
  s.alpha = r * r;
  return s;
}
// From a surface's `specular` (GBufferValues::specular) and η.
SurfaceBsdf makeBsdf(vec3 baseColor, float metallic, float roughness, vec4 specular, float ior) {
  vec3 f0;
  float f90;
  dielectricSpecular(specular, ior, f0, f90);
  return makeBsdf(baseColor, metallic, roughness, f0, f90);
}

// BRDF × cosine for light arriving from l. `alphaWiden` widens the lobe for lights of finite size
// (energy-conserving: GGX stays normalised), so a sphere light's highlight on a near-mirror has the
// light's size rather than a pin-point. evalSpecularCos: the specular lobe alone.
vec3 evalSpecularCos(SurfaceBsdf s, vec3 n, vec3 v, vec3 l, float alphaWiden) {
  float nl = dot(n, l);
  float nv = max(dot(n, v), 1e-4);
  if (nl <= 0.0) return vec3(0.0);
  vec3 h = normalize(v + l);
  float a = clamp(s.alpha + alphaWiden, s.alpha, 1.0);
  float a2 = a * a;
  return fresnelSchlick(s.f0, s.f90, max(dot(v, h), 0.0)) * (ggxD(max(dot(n, h), 0.0), a2) * smithV(nl, nv, a2)) * nl;
}

vec3 evalBsdfCos(SurfaceBsdf s, vec3 n, vec3 v, vec3 l, float alphaWiden) {
  float nl = dot(n, l);
  if (nl <= 0.0) return vec3(0.0);
  float vh = max(dot(v, normalize(v + l)), 0.0);
  vec3 diff = (1.0 - fresnelSchlick(vec3(s.diffuseF0), vec3(s.diffuseF90), vh)) * s.diffuse / kPi;
  return diff * nl + evalSpecularCos(s, n, v, l, alphaWiden);
}

#endif
