#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"

// Vertices are pulled by device address; draws are non-indexed over the index count.
layout(push_constant, scalar) uniform Push { uint instance; uint geometry; } pc;

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec4 outTangent;
layout(location = 3) out vec2 outUv0;
layout(location = 4) out vec2 outUv1;
layout(location = 5) out vec3 outPrevWorldPos;  // for the motion vector

void main() {
  InstanceRecord inst = Instances(frame.instances).i[pc.instance];
  GeometryRecord g = Geometries(frame.geometries).g[pc.geometry];
  uint index = Indices(g.indexAddress).i[gl_VertexIndex];
  Vertex v = Vertices(g.vertexAddress).v[index];
  vec4 world = inst.worldFromObject * vec4(v.position, 1.0);
  outWorldPos = world.xyz;
  outPrevWorldPos = (inst.prevWorldFromObject * vec4(v.position, 1.0)).xyz;
  outNormal = (inst.normalFromObject * vec4(v.normal, 0.0)).xyz;
  outTangent = vec4((inst.worldFromObject * vec4(v.tangent.xyz, 0.0)).xyz, v.tangent.w);
  outUv0 = v.uv0;
  outUv1 = v.uv1;
  gl_Position = frame.clipFromWorld * world;
}
