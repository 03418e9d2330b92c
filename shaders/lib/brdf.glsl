// GGX specular + Lambert diffuse, glTF metallic-roughness. One definition for every pass that shades.
#ifndef RAYSTER_BRDF_GLSL
#define RAYSTER_BRDF_GLSL

float ggxD(float nh, float a2) {
  float d = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d);
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

struct SurfaceBsdf {
  vec3 diffuse;  // albedo · (1 − metallic)
  vec3 f0;       // specular reflectance at normal incidence
  vec3 f90;      // at grazing incidence: 1, except for dielectrics with almost no reflectance
  float alpha;   // GGX α = roughness²
};

// Dielectrics reflect F0 = ((η − 1)/(η + 1))² at normal incidence (0.04 at η = 1.5); F90 fades to
// 0 with F0 below 0.02 (Filament), so η = 1 reflects nothing at any angle.
SurfaceBsdf makeBsdf(vec3 baseColor, float metallic, float roughness, float ior) {
  SurfaceBsdf s;
  s.diffuse = baseColor * (1.0 - metallic);
  float r0 = (ior - 1.0) / (ior + 1.0);
  float f0Dielectric = ior == 1.5 ? 0.04 : r0 * r0;  // the hybrid's constant, bit for bit
  s.f0 = mix(vec3(f0Dielectric), baseColor, metallic);
  s.f90 = mix(vec3(clamp(50.0 * f0Dielectric, 0.0, 1.0)), vec3(1.0), metallic);
  float r = clamp(roughness, 0.02, 1.0);        // a perfect mirror has no point-light highlight at all
  s.alpha = r * r;
  return s;
}
// The hybrid frame's dielectrics all use η = 1.5 (the G-buffer keeps only 7 bits of η).
SurfaceBsdf makeBsdf(vec3 baseColor, float metallic, float roughness) { return makeBsdf(baseColor, metallic, roughness, 1.5); }

// BRDF × cosine for light arriving from l. `alphaWiden` widens the lobe for lights of finite size
// (energy-conserving: GGX stays normalised), so a sphere light's highlight on a near-mirror has the
// light's size rather than a pin-point.
vec3 evalBsdfCos(SurfaceBsdf s, vec3 n, vec3 v, vec3 l, float alphaWiden) {
  float nl = dot(n, l);
  float nv = max(dot(n, v), 1e-4);
  if (nl <= 0.0) return vec3(0.0);
  vec3 h = normalize(v + l);
  float nh = max(dot(n, h), 0.0);
  float vh = max(dot(v, h), 0.0);
  float a = clamp(s.alpha + alphaWiden, s.alpha, 1.0);
  float a2 = a * a;
  vec3 f = fresnelSchlick(s.f0, s.f90, vh);
  vec3 spec = f * (ggxD(nh, a2) * smithV(nl, nv, a2));
  vec3 diff = (1.0 - f) * s.diffuse / kPi;
  return (diff + spec) * nl;
}

#endif
