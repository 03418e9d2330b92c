#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/surface.glsl"

layout(push_constant, scalar) uniform Push { uint instance; uint geometry; } pc;

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec4 outNormals;
layout(location = 1) out vec4 outAlbedo;
layout(location = 2) out vec4 outMaterial;
layout(location = 3) out vec4 outEmissive;
layout(location = 4) out uint outId;

void main() {
  InstanceRecord inst = Instances(frame.instances).i[pc.instance];
  GeometryRecord g = Geometries(frame.geometries).g[pc.geometry];
  MaterialRecord m = Materials(frame.materials).m[g.material];
  // The geometric normal from the triangle itself, exactly as the traced producer computes it.
  vec3 p0, p1, p2;
  trianglePositions(g, inst, uint(gl_PrimitiveID), p0, p1, p2);
  vec3 ng = cross(p1 - p0, p2 - p0);
  GBufferValues gb = evaluateSurface(m, inWorldPos, inNormal, ng, inUv, frame.cameraPosition.xyz);
  outNormals = gb.normals;
  outAlbedo = gb.albedo;
  outMaterial = gb.material;
  outEmissive = gb.emissive;
  outId = pc.instance;
}
