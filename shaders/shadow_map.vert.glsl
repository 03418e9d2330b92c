#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"

// Depth-only view of the scene from a light (render/passes/shadow_maps.cpp): one tile of the atlas.
layout(push_constant, scalar) uniform Push { ShadowMapPush pc; };

void main() {
  InstanceRecord inst = Instances(frame.instances).i[pc.instance];
  GeometryRecord g = Geometries(frame.geometries).g[pc.geometry];
  uint index = Indices(g.indexAddress).i[gl_VertexIndex];
  Vertex v = Vertices(g.vertexAddress).v[index];
  gl_Position = pc.clipFromWorld * (inst.worldFromObject * vec4(v.position, 1.0));
}
