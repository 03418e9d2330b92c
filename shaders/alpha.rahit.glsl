#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/textures.glsl"
#include "lib/surface.glsl"

// Alpha testing for MASK and BLEND triangles, and back-face rejection for the single-sided
// triangles of meshes that mix sidedness (render/gpu_scene.cpp), shared by every ray type (it never
// touches the payload). Opaque geometry is built OPAQUE and never runs this shader.
hitAttributeEXT vec2 bary;

void main() {
  InstanceRecord inst = Instances(frame.instances).i[gl_InstanceCustomIndexEXT];
  GeometryRecord g = Geometries(frame.geometries).g[inst.firstGeometry + gl_GeometryIndexEXT];
  MaterialRecord m = Materials(frame.materials).m[g.material];
  if ((m.flags & kMaterialCullsBackFaces) != 0u && gl_HitKindEXT == gl_HitKindBackFacingTriangleEXT) ignoreIntersectionEXT;
  Indices idx = Indices(g.indexAddress);
  Vertices vtx = Vertices(g.vertexAddress);
  uint base = uint(gl_PrimitiveID) * 3u;
  Vertex v0 = vtx.v[idx.i[base]], v1 = vtx.v[idx.i[base + 1u]], v2 = vtx.v[idx.i[base + 2u]];
  vec3 w = vec3(1.0 - bary.x - bary.y, bary.x, bary.y);
  vec2 uv0 = v0.uv0 * w.x + v1.uv0 * w.y + v2.uv0 * w.z;
  vec2 uv1 = v0.uv1 * w.x + v1.uv1 * w.y + v2.uv1 * w.z;
  // Stochastic coverage for BLEND: a fresh number per ray and primitive, so it converges over frames.
  uint rng = rngInit(gl_LaunchIDEXT.xy, frame.frameIndex ^ pcg(uint(gl_PrimitiveID) + gl_LaunchIDEXT.z * 7919u),
                     frame.seed ^ kAlphaStream);
  float vertexAlpha = vertexColor(g, uint(gl_PrimitiveID), w).a;
  if (alphaRejects(m, uv0, uv1, vertexAlpha, rnd(rng))) ignoreIntersectionEXT;
}
