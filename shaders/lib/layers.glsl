// The material layers of KHR_materials_clearcoat, _sheen, _iridescence, _anisotropy and _dispersion
// (docs/materials.md): their values at a surface point, and the layered BSDF the path tracer
// evaluates and samples. The base is lib/brdf.glsl's model (Lambert + GGX), with its GGX lobe
// stretched by anisotropy and its Fresnel term replaced by the thin film's; sheen sits on the base
// (albedo scaling), the clear coat on both. A material without layers never comes here, so its
// paths are those of lib/pt_bsdf.glsl unchanged. Needs lib/brdf.glsl, lib/textures.glsl,
// lib/surface.glsl, shared/vndf.h, shared/sheen.h and lib/layer_lobes.glsl.
#ifndef RAYSTER_LAYERS_GLSL
#define RAYSTER_LAYERS_GLSL

#include "lib/layer_lobes.glsl"

struct SurfaceLayers {
  float clearcoat;   // 0: no coat
  float coatAlpha;   // GGX α of the coat
  vec3 coatNormal;   // world, facing the viewer
  vec3 sheenColor;   // 0: no sheen
  float sheenRoughness;
  float iridescence;  // 0: Schlick's Fresnel
  float filmIor;
  float filmThickness;  // nm
  float alphaT, alphaB;  // the base lobe's GGX α along anisoT and across it (equal: isotropic)
  vec3 anisoT, anisoB;   // world tangent frame of the base lobe, around the shading normal
  float dispersion;      // 20 / Abbe number
};

// The layers at a surface point. `ns` is the final shading normal (normal-mapped) and `nFace`
// the interpolated normal facing the viewer (the coat's normal without its own texture);
// `roughness` the base roughness the G-buffer values hold.
SurfaceLayers evaluateLayers(MaterialRecord m, SurfacePoint sp, vec3 ns, vec3 nFace, float roughness) {
  MaterialLayers l = LayersOf(m.layers).l;
  SurfaceLayers o;
  // A tangent frame around a normal: the vertex tangent where there is one.
  vec3 t = sp.tangent.xyz - ns * dot(ns, sp.tangent.xyz);
  vec3 b;
  bool hasTangent = dot(t, t) > 1e-12;
  if (hasTangent) {
    t = normalize(t);
    b = cross(ns, t) * (sp.tangent.w < 0.0 ? -1.0 : 1.0);
  } else {
    orthonormalBasis(ns, t, b);
  }

  float coatRoughness;
  o.clearcoat = coatAt(l, sp, nFace, o.coatNormal, coatRoughness);
  o.coatAlpha = max(coatRoughness * coatRoughness, 1e-4);
  vec4 sheen = sheenAt(l, sp);
  o.sheenColor = sheen.rgb;
  o.sheenRoughness = sheen.a;

  o.iridescence = clamp(l.iridescence * SAMPLE_SLOT(l.iridescenceTexture, sp.uv0, sp.uv1, vec4(1.0)).r, 0.0, 1.0);
  o.filmIor = l.iridescenceIor;
  o.filmThickness = l.iridescenceThicknessTexture.slot != kNoTexture
                        ? mix(l.iridescenceThicknessMin, l.iridescenceThicknessMax,
                              SAMPLE_SLOT(l.iridescenceThicknessTexture, sp.uv0, sp.uv1, vec4(1.0)).g)
                        : l.iridescenceThicknessMax;

  // Anisotropy: the direction (texture RG in [-1, 1]², default +x) turned by the rotation, the
  // strength × texture B; α along it widens towards 1 with strength², across it stays (the spec).
  vec3 at = SAMPLE_SLOT(l.anisotropyTexture, sp.uv0, sp.uv1, vec4(1.0, 0.5, 1.0, 1.0)).rgb;
  vec2 dir = at.xy * 2.0 - 1.0;
  dir = dot(dir, dir) > 1e-8 ? normalize(dir) : vec2(1.0, 0.0);
  float c = cos(l.anisotropyRotation), s = sin(l.anisotropyRotation);
  dir = vec2(c * dir.x - s * dir.y, s * dir.x + c * dir.y);
  float strength = clamp(l.anisotropyStrength * at.b, 0.0, 1.0);
  float r = clamp(roughness, 0.02, 1.0);
  float alpha = r * r;
  o.alphaB = alpha;
  o.alphaT = mix(alpha, 1.0, strength * strength);
  o.anisoT = normalize(t * dir.x + b * dir.y);
  o.anisoB = cross(ns, o.anisoT);
  o.dispersion = l.dispersion;
  return o;
}

// ---- the base specular lobe: anisotropic GGX with a thin-film Fresnel ----

float ggxAnisoD(vec3 h, float at, float ab) {
  float x = h.x / at, y = h.y / ab;
  float d = x * x + y * y + h.z * h.z;
  return 1.0 / (kPi * at * ab * d * d);
}
float smithLambdaAniso(vec3 w, float at, float ab) {
  float z2 = max(w.z * w.z, 1e-12);
  return 0.5 * (-1.0 + sqrt(1.0 + (at * at * w.x * w.x + ab * ab * w.y * w.y) / z2));
}
// The thin film's spectral response, integrated against the CIE matching functions in Fourier space
// with the Gaussian fits of Belcour and Barla (2017, §4), to linear Rec. 709.
vec3 filmSensitivity(float opd, vec3 shift) {
  float phase = 2.0 * kPi * opd * 1.0e-9;
  const vec3 val = vec3(5.4856e-13, 4.4201e-13, 5.2481e-13);
  const vec3 pos = vec3(1.6810e+06, 1.7953e+06, 2.2084e+06);
  const vec3 var = vec3(4.3278e+09, 9.3046e+09, 6.6121e+09);
  vec3 xyz = val * sqrt(2.0 * kPi * var) * cos(pos * phase + shift) * exp(-phase * phase * var);
  xyz.x += 9.7470e-14 * sqrt(2.0 * kPi * 4.5282e+09) * cos(2.2399e+06 * phase + shift.x) *
           exp(-4.5282e+09 * phase * phase);
  xyz /= 1.0685e-7;
  const mat3 xyzToRec709 = mat3(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108, -0.2040259, -0.4985314,
                                0.0415560, 1.0572252);
  return xyzToRec709 * xyz;
}

// Reflectance of air | film (η filmIor, `thickness` nm) | base (F0 f0) at cosθ = `c` (Belcour and
// Barla's Airy sum to second order, with Schlick at both interfaces as KHR_materials_iridescence
// describes). The path difference uses the angle inside the film.
vec3 thinFilmFresnel(float c, float filmIor, float thickness, vec3 f0) {
  float sin2 = (1.0 - c * c) / (filmIor * filmIor);
  if (sin2 >= 1.0) return vec3(1.0);  // total internal reflection in the film
  float c2 = sqrt(1.0 - sin2);
  float r12 = schlick1(pow((filmIor - 1.0) / (filmIor + 1.0), 2.0), c);
  float t121 = 1.0 - r12;
  vec3 sf0 = sqrt(clamp(f0, vec3(0.0), vec3(0.9999)));
  vec3 baseIor = (1.0 + sf0) / (1.0 - sf0);
  vec3 r1 = pow((baseIor - filmIor) / (baseIor + filmIor), vec3(2.0));
  vec3 r23 = r1 + (1.0 - r1) * pow(1.0 - c2, 5.0);
  float phi12 = filmIor < 1.0 ? kPi : 0.0;
  vec3 phi23 = vec3(baseIor.r < filmIor ? kPi : 0.0, baseIor.g < filmIor ? kPi : 0.0, baseIor.b < filmIor ? kPi : 0.0);
  vec3 phi = vec3(kPi - phi12) + phi23;
  float opd = 2.0 * filmIor * thickness * c2;
  vec3 r123 = clamp(r12 * r23, vec3(1e-5), vec3(0.9999));
  vec3 rs = t121 * t121 * r23 / (1.0 - r123);
  vec3 result = r12 + rs;
  vec3 cm = rs - t121;
  vec3 rr = sqrt(r123);
  for (int k = 1; k <= 2; ++k) {
    cm *= rr;
    result += cm * 2.0 * filmSensitivity(float(k) * opd, float(k) * phi);
  }
  return clamp(result, vec3(0.0), vec3(1.0));  // the second-order sum can overshoot; no film reflects more than arrives
}

bool hasFilm(SurfaceLayers y) { return y.iridescence > 0.0 && y.filmThickness > 0.0; }

float max3(vec3 c) { return max(c.r, max(c.g, c.b)); }

// The base lobe's Fresnel term, and (`diffuseF`) the share of light the diffuse layer under it
// loses: Schlick of the largest channel as in lib/brdf.glsl. A film's reflectance is not monotonic
// in the angle as Schlick's is, so the half vector of a diffuse direction can see less of it than
// the specular lobe reflects towards the viewer: the diffuse layer then loses the film's largest
// channel at the half vector or at the view angle (`nv`), whichever is more, and the stack does
// not gain energy (Layers.NoLayerCreatesEnergyInAWhiteFurnace).
vec3 baseFresnel(SurfaceBsdf s, SurfaceLayers y, float vh, float nv, out float diffuseF) {
  vec3 f = fresnelSchlick(s.f0, s.f90, vh);
  diffuseF = fresnelSchlick(vec3(s.diffuseF0), vec3(s.diffuseF90), vh).x;
  if (!hasFilm(y)) return f;
  vec3 film = thinFilmFresnel(vh, y.filmIor, y.filmThickness, s.f0);
  float seen = max3(thinFilmFresnel(nv, y.filmIor, y.filmThickness, s.f0));
  diffuseF = mix(diffuseF, max(max3(film), seen), y.iridescence);
  return mix(f, film, y.iridescence);
}

vec3 toLobe(SurfaceLayers y, vec3 n, vec3 w) { return vec3(dot(w, y.anisoT), dot(w, y.anisoB), dot(w, n)); }

// ---- the layered BSDF ----

float coatFresnel(SurfaceLayers y, vec3 v) { return coatViewFresnel(y.clearcoat, dot(y.coatNormal, v)); }

// f·cos of the whole stack for light from l.
vec3 evalLayeredCos(SurfaceBsdf s, SurfaceLayers y, vec3 n, vec3 v, vec3 l) {
  float nl = dot(n, l);
  float nv = max(dot(n, v), 1e-4);
  vec3 f = vec3(0.0);
  if (nl > 0.0) {
    vec3 h = normalize(v + l);
    float vh = max(dot(v, h), 0.0);
    float diffuseF;
    vec3 fresnel = baseFresnel(s, y, vh, nv, diffuseF);
    vec3 diff = (1.0 - diffuseF) * s.diffuse / kPi * nl;
    vec3 lv = toLobe(y, n, v), ll = toLobe(y, n, l), lh = toLobe(y, n, h);
    float g2 = 1.0 / (1.0 + smithLambdaAniso(lv, y.alphaT, y.alphaB) + smithLambdaAniso(ll, y.alphaT, y.alphaB));
    vec3 spec = fresnel * ggxAnisoD(lh, y.alphaT, y.alphaB) * g2 / (4.0 * nv);
    f = (diff + spec) * sheenScale(y.sheenColor, y.sheenRoughness, nv, nl);
    f += sheenCos(y.sheenColor, y.sheenRoughness, n, v, l);
  }
  if (y.clearcoat > 0.0) {
    f *= 1.0 - coatFresnel(y, v);
    f += coatCos(y.clearcoat, y.coatAlpha * y.coatAlpha, y.coatNormal, v, l);
  }
  return f;
}

// Lobe choice: the coat by its Fresnel share (at least a quarter of its factor: a smooth coat's
// reflection is sharp, so it is sampled more often than its energy alone says), then the base's
// specular or cosine lobe (sheen and diffuse share the cosine lobe).
float coatProbability(SurfaceLayers y, vec3 v) {
  return y.clearcoat > 0.0 ? clamp(max(coatFresnel(y, v), 0.25 * y.clearcoat), 0.05, 0.9) : 0.0;
}
float layeredSpecularProbability(SurfaceBsdf s, SurfaceLayers y, float nv) {
  float fs = luminance(fresnelSchlick(s.f0, s.f90, nv));
  float fd = luminance(s.diffuse) * (1.0 - fs) + luminance(y.sheenColor);
  if (fd <= 0.0) return 1.0;
  if (fs <= 0.0) return 0.0;
  return clamp(fs / (fs + fd), 0.1, 0.9);
}

float layeredPdf(SurfaceBsdf s, SurfaceLayers y, vec3 n, vec3 v, vec3 l) {
  float pCoat = coatProbability(y, v);
  float nv = max(dot(n, v), 1e-4);
  float pSpec = layeredSpecularProbability(s, y, nv);
  float pdf = 0.0;
  float nl = dot(n, l);
  if (nl > 0.0) {
    vec3 h = normalize(v + l);
    vec3 lv = toLobe(y, n, v), lh = toLobe(y, n, h);
    float g1 = 1.0 / (1.0 + smithLambdaAniso(lv, y.alphaT, y.alphaB));
    float spec = g1 * ggxAnisoD(lh, y.alphaT, y.alphaB) / (4.0 * nv);
    pdf = pSpec * spec + (1.0 - pSpec) * nl / kPi;
  }
  pdf *= 1.0 - pCoat;
  if (pCoat > 0.0) {
    vec3 nc = y.coatNormal;
    float cl = dot(nc, l), cv = max(dot(nc, v), 1e-4);
    if (cl > 0.0) {
      vec3 h = normalize(v + l);
      pdf += pCoat * smithG1(cv, y.coatAlpha) * ggxDistribution(max(dot(nc, h), 0.0), y.coatAlpha) / (4.0 * cv);
    }
  }
  return pdf;
}

vec3 sampleLayered(SurfaceBsdf s, SurfaceLayers y, vec3 n, vec3 v, vec3 u) {
  float pCoat = coatProbability(y, v);
  if (u.z < pCoat) {
    vec3 t, b;
    orthonormalBasis(y.coatNormal, t, b);
    vec3 vt = normalize(vec3(dot(v, t), dot(v, b), max(dot(v, y.coatNormal), 1e-4)));
    vec3 h = sampleGgxVndf(vt, y.coatAlpha, u.xy);
    vec3 r = reflect(-vt, h);
    return t * r.x + b * r.y + y.coatNormal * r.z;
  }
  float z = (u.z - pCoat) / (1.0 - pCoat);
  if (z >= layeredSpecularProbability(s, y, max(dot(n, v), 1e-4))) return cosineSampleHemisphere(n, u.xy);
  vec3 vt = toLobe(y, n, v);
  vt.z = max(vt.z, 1e-4);
  vec3 h = sampleGgxVndfAniso(normalize(vt), y.alphaT, y.alphaB, u.xy);
  vec3 r = reflect(-normalize(vt), h);
  return y.anisoT * r.x + y.anisoB * r.y + n * r.z;
}

// ---- dispersion ----

// η at one of the Fraunhofer lines that define the Abbe number (C 656.3 nm, d 587.6, F 486.1 for
// red, green and blue): η(λ) = η_d + (η_d − 1)/V · (523655/λ² − 1.5168) (the extension's formula).
float dispersedIor(float ior, float dispersion, int channel) {
  if (dispersion <= 0.0 || channel < 0) return ior;
  const vec3 lambda = vec3(656.3, 587.6, 486.1);
  float l = lambda[channel];
  return max(ior + (ior - 1.0) * dispersion / 20.0 * (523655.0 / (l * l) - 1.5168), 1.0);
}

#endif
