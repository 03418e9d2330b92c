// Surface evaluation shared by both G-buffer producers (raster and traced primary rays), so they
// write identical values for the same surface point.
#ifndef RAYSTER_SURFACE_GLSL
#define RAYSTER_SURFACE_GLSL

struct GBufferValues {
  vec4 normals;   // xy: shading normal (oct), zw: geometric normal (oct)
  vec4 albedo;    // rgb: sRGB-encoded base colour, a: material AO
  vec4 material;  // roughness, metallic, transmission, flags
  vec4 emissive;  // rgb: linear radiance
};

// World-space positions of triangle `primitive` of a geometry, transformed by its instance.
void trianglePositions(GeometryRecord g, InstanceRecord inst, uint primitive, out vec3 p0, out vec3 p1, out vec3 p2) {
  Indices idx = Indices(g.indexAddress);
  Vertices vtx = Vertices(g.vertexAddress);
  uint base = primitive * 3u;
  p0 = (inst.worldFromObject * vec4(vtx.v[idx.i[base + 0u]].position, 1.0)).xyz;
  p1 = (inst.worldFromObject * vec4(vtx.v[idx.i[base + 1u]].position, 1.0)).xyz;
  p2 = (inst.worldFromObject * vec4(vtx.v[idx.i[base + 2u]].position, 1.0)).xyz;
}

// Both normals face the viewer: the geometric normal from the triangle, the shading normal flipped
// with it, so back faces of double-sided surfaces shade like front faces.
GBufferValues evaluateSurface(MaterialRecord m, vec3 worldPos, vec3 shadingNormal, vec3 geometricNormal,
                              vec2 uv, vec3 cameraPos) {
  vec3 ng = normalize(geometricNormal);
  vec3 ns = normalize(shadingNormal);
  vec3 toCamera = cameraPos - worldPos;
  if (dot(ng, toCamera) < 0.0) ng = -ng;
  if (dot(ns, ng) < 0.0) ns = -ns;
  GBufferValues o;
  o.normals = vec4(octEncode(ns), octEncode(ng));
  o.albedo = vec4(linearToSrgb(m.baseColor.rgb), 1.0);
  o.material = vec4(m.roughness, m.metallic, 0.0, 0.0);
  o.emissive = vec4(m.emissive, 0.0);
  return o;
}

#endif
