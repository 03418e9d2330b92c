// Surface evaluation shared by both G-buffer producers (raster and traced primary rays), so they
// write identical values for the same surface point, and by every ray hit. Needs lib/textures.glsl.
#ifndef RAYSTER_SURFACE_GLSL
#define RAYSTER_SURFACE_GLSL

#include "lib/brdf.glsl"

// material.w packs what the bounce loop needs at the first interface: the index of refraction
// (1..3 in 7 bits) and whether the surface is thin-walled (no volume: KHR_materials_volume absent).
float packIor(float ior, bool thinWalled) {
  return (clamp(round((ior - 1.0) * 63.5), 0.0, 127.0) + (thinWalled ? 128.0 : 0.0)) / 255.0;
}
void unpackIor(float w, out float ior, out bool thinWalled) {
  float b = round(w * 255.0);
  thinWalled = b >= 128.0;
  ior = 1.0 + mod(b, 128.0) / 63.5;
}

struct GBufferValues {
  vec4 normals;   // xy: shading normal (oct), zw: geometric normal (oct)
  vec4 albedo;    // rgb: sRGB-encoded base colour, a: material ambient occlusion
  vec4 material;  // roughness, metallic, transmission, packIor(ior, thin-walled)
  vec4 emissive;  // rgb: linear radiance
  // KHR_materials_specular (lib/brdf.glsl dielectricSpecular()): rgb the dielectric F0 tint, a the
  // strength. Unencoded here, so ray hits use it exactly; the G-buffer stores encodeSpecular() of it.
  vec4 specular;
  // KHR_materials_clearcoat: xy the coat normal (oct, facing the viewer), z the factor (0: no coat),
  // w the roughness. KHR_materials_sheen: rgb the linear colour (0: no sheen), a the roughness.
  // The G-buffer stores encodeLayers() of both (lib/common.glsl).
  vec4 coat;
  vec4 sheen;
};

struct SurfacePoint {
  vec3 position;
  vec3 normal;           // interpolated shading normal (world)
  vec4 tangent;          // world tangent, w: bitangent sign
  vec3 geometricNormal;  // from the triangle (or the sphere)
  vec2 uv0;
  vec2 uv1;
  vec4 color;            // COLOR_0, interpolated (white without)
};

// The triangle's normal from its world positions, outward for counter-clockwise fronts: a mirroring
// instance (negative determinant) turns the world winding, so its cross product is flipped back.
vec3 windingNormal(InstanceRecord inst, vec3 p0, vec3 p1, vec3 p2) {
  vec3 n = cross(p1 - p0, p2 - p0);
  return determinant(mat3(inst.worldFromObject)) < 0.0 ? -n : n;
}

// World-space positions of triangle `primitive` of a geometry, transformed by its instance.
void trianglePositions(GeometryRecord g, InstanceRecord inst, uint primitive, out vec3 p0, out vec3 p1, out vec3 p2) {
  Indices idx = Indices(g.indexAddress);
  Vertices vtx = Vertices(g.vertexAddress);
  uint base = primitive * 3u;
  p0 = (inst.worldFromObject * vec4(vtx.v[idx.i[base + 0u]].position, 1.0)).xyz;
  p1 = (inst.worldFromObject * vec4(vtx.v[idx.i[base + 1u]].position, 1.0)).xyz;
  p2 = (inst.worldFromObject * vec4(vtx.v[idx.i[base + 2u]].position, 1.0)).xyz;
}

// Coverage of a surface point: base colour alpha × texture alpha × vertex colour alpha.
float materialAlpha(MaterialRecord m, vec2 uv0, vec2 uv1, float vertexAlpha) {
  return m.baseColor.a * SAMPLE_SLOT(m.baseColorTexture, uv0, uv1, vec4(1.0)).a * vertexAlpha;
}

// Alpha test for MASK (cutoff) and BLEND (stochastic coverage against `u`, converging over frames).
bool alphaRejects(MaterialRecord m, vec2 uv0, vec2 uv1, float vertexAlpha, float u) {
  if ((m.flags & (kMaterialAlphaMask | kMaterialAlphaBlend)) == 0u) return false;
  float a = materialAlpha(m, uv0, uv1, vertexAlpha);
  return (m.flags & kMaterialAlphaMask) != 0u ? a < m.alphaCutoff : a <= u;
}

// Beer–Lambert (KHR_materials_volume): the share of light left after `distance` inside the volume.
vec3 volumeTransmittance(MaterialRecord m, float distance) {
  if (m.attenuationDistance >= 1e30) return vec3(1.0);
  vec3 sigma = -log(max(m.attenuationColor, vec3(1e-6))) / m.attenuationDistance;
  return exp(-sigma * distance);
}

layout(buffer_reference, scalar) readonly buffer LayersOf { MaterialLayers l; };

// KHR_materials_clearcoat at a surface point: the factor, the coat normal (its own normal texture
// on `nFace`, the interpolated normal facing the viewer) and the roughness.
float coatAt(MaterialLayers l, SurfacePoint sp, vec3 nFace, out vec3 nc, out float roughness) {
  float coat = clamp(l.clearcoat * SAMPLE_SLOT(l.clearcoatTexture, sp.uv0, sp.uv1, vec4(1.0)).r, 0.0, 1.0);
  roughness =
      clamp(l.clearcoatRoughness * SAMPLE_SLOT(l.clearcoatRoughnessTexture, sp.uv0, sp.uv1, vec4(1.0)).g, 0.0, 1.0);
  nc = nFace;
  if (l.clearcoatNormalTexture.slot != kNoTexture) {
    vec3 ct = sp.tangent.xyz - nFace * dot(nFace, sp.tangent.xyz);
    if (dot(ct, ct) > 1e-12) {
      ct = normalize(ct);
      vec3 cb = cross(nFace, ct) * (sp.tangent.w < 0.0 ? -1.0 : 1.0);
      vec3 tn = SAMPLE_SLOT(l.clearcoatNormalTexture, sp.uv0, sp.uv1, vec4(0.5, 0.5, 1.0, 1.0)).xyz * 2.0 - 1.0;
      tn.xy *= l.clearcoatNormalScale;
      nc = normalize(ct * tn.x + cb * tn.y + nFace * tn.z);
    }
  }
  return coat;
}

// KHR_materials_sheen at a surface point: rgb the linear colour, a the roughness.
vec4 sheenAt(MaterialLayers l, SurfacePoint sp) {
  vec3 color = l.sheenColor * SAMPLE_SLOT(l.sheenColorTexture, sp.uv0, sp.uv1, vec4(1.0)).rgb;
  float roughness = clamp(l.sheenRoughness * SAMPLE_SLOT(l.sheenRoughnessTexture, sp.uv0, sp.uv1, vec4(1.0)).a, 0.0, 1.0);
  return vec4(max(color, vec3(0.0)), roughness);
}

// Both normals face the viewer: the geometric normal from the triangle, the shading normal flipped
// with it, so back faces of double-sided surfaces shade like front faces.
GBufferValues evaluateSurface(MaterialRecord m, SurfacePoint sp, vec3 cameraPos) {
  vec3 ng = normalize(sp.geometricNormal);
  vec3 ns = normalize(sp.normal);
  if (dot(ng, cameraPos - sp.position) < 0.0) ng = -ng;
  if (dot(ns, ng) < 0.0) ns = -ns;

  vec4 base = m.baseColor * SAMPLE_SLOT(m.baseColorTexture, sp.uv0, sp.uv1, vec4(1.0)) * sp.color;
  GBufferValues o;
  if ((m.flags & kMaterialUnlit) != 0u) {
    // Unlit (render/gpu_materials.cpp): the base colour is emitted radiance; nothing scatters.
    o.normals = vec4(octEncode(ns), octEncode(ng));
    o.albedo = vec4(0.0, 0.0, 0.0, 1.0);
    o.material = vec4(1.0, 0.0, 0.0, packIor(m.ior, true));  // rough: no pass traces its reflection
    o.emissive = vec4(base.rgb * frame.exposure, m.ior);  // emitted light is pre-exposed (lib/frame.glsl)
    o.specular = vec4(0.0);
    o.coat = vec4(octEncode(ns), 0.0, 0.0);
    o.sheen = vec4(0.0);
    return o;
  }
  const vec3 nFace = ns;  // the interpolated normal, before the normal texture: the coat's own
  vec4 mr = SAMPLE_SLOT(m.metallicRoughnessTexture, sp.uv0, sp.uv1, vec4(1.0));
  float roughness = clamp(m.roughness * mr.g, 0.0, 1.0);
  float metallic = clamp(m.metallic * mr.b, 0.0, 1.0);
  if (m.normalTexture.slot != kNoTexture) {
    vec3 t = sp.tangent.xyz - ns * dot(ns, sp.tangent.xyz);
    if (dot(t, t) > 1e-12) {
      t = normalize(t);
      vec3 b = cross(ns, t) * (sp.tangent.w < 0.0 ? -1.0 : 1.0);
      vec3 tn = SAMPLE_SLOT(m.normalTexture, sp.uv0, sp.uv1, vec4(0.5, 0.5, 1.0, 1.0)).xyz * 2.0 - 1.0;
      tn.xy *= m.normalScale;
      ns = normalize(t * tn.x + b * tn.y + ns * tn.z);
    }
  }
  float ao = 1.0 + m.occlusionStrength * (SAMPLE_SLOT(m.occlusionTexture, sp.uv0, sp.uv1, vec4(1.0)).r - 1.0);
  vec3 emissive = exposedEmission(m) * SAMPLE_SLOT(m.emissiveTexture, sp.uv0, sp.uv1, vec4(1.0)).rgb;
  // KHR_materials_specular: the F0 tint t = min(F0(η)·colour, 1)/F0(η) (at η = 1, F0(η) = 0 and the
  // tint is moot: keep the colour, bounded by the encoding's range).
  float strength = m.specular * SAMPLE_SLOT(m.specularTexture, sp.uv0, sp.uv1, vec4(1.0)).a;
  vec3 color = m.specularColor * SAMPLE_SLOT(m.specularColorTexture, sp.uv0, sp.uv1, vec4(1.0)).rgb;
  float f0Ior = dielectricF0(m.ior);
  vec3 tint = f0Ior > 0.0 ? min(f0Ior * color, vec3(1.0)) / f0Ior : min(color, vec3(128.0));

  o.normals = vec4(octEncode(ns), octEncode(ng));
  o.albedo = vec4(linearToSrgb(base.rgb), ao);
  // KHR_materials_volume's thickness (and its texture) is for rasterisers that cannot measure a
  // volume; rays measure it, so only "thin-walled or not" (thickness 0) matters here.
  float transmission = m.transmission * SAMPLE_SLOT(m.transmissionTexture, sp.uv0, sp.uv1, vec4(1.0)).r;
  o.material = vec4(roughness, metallic, transmission, packIor(m.ior, m.thickness <= 0.0));
  o.emissive = vec4(emissive, m.ior);  // the exact ior (fp16): material.a holds only 7 bits of it
  o.specular = vec4(tint, clamp(strength, 0.0, 1.0));
  o.coat = vec4(octEncode(nFace), 0.0, 0.0);
  o.sheen = vec4(0.0);
  if (m.layers != 0ul) {
    MaterialLayers l = LayersOf(m.layers).l;
    vec3 nc;
    float coatRoughness;
    float coat = coatAt(l, sp, nFace, nc, coatRoughness);
    if (coat > 0.0) o.coat = vec4(octEncode(nc), coat, coatRoughness);
    o.sheen = sheenAt(l, sp);
  }
  return o;
}

#endif
