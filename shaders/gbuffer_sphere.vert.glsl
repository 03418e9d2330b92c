#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"

// Raster impostors for analytic spheres: each sphere's bounding cube is drawn (36 vertices, one
// instance per sphere) and the fragment shader intersects the exact sphere.
// The draw comes from the culled list (render/passes/cull.cpp): gl_DrawID indexes drawIds, whose
// entry is the DrawRecord row.
layout(push_constant, scalar) uniform Push { GBufferDrawPush pc; };
layout(buffer_reference, scalar) readonly buffer DrawRecords { DrawRecord d[]; };
layout(buffer_reference, scalar) readonly buffer DrawIds { uint i[]; };

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) flat out uint outSphere;
layout(location = 2) flat out uvec2 outDraw;  // instance, geometry (for the fragment shader)

const uint kCubeIndices[36] = uint[36](0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                       2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5);

void main() {
  DrawRecord draw = DrawRecords(pc.records).d[DrawIds(pc.drawIds).i[gl_DrawID]];
  outDraw = uvec2(draw.instance, draw.geometry);
  InstanceRecord inst = Instances(frame.instances).i[draw.instance];
  GeometryRecord g = Geometries(frame.geometries).g[draw.geometry];
  SphereRecord s = Spheres(g.vertexAddress).s[gl_InstanceIndex];
  uint corner = kCubeIndices[gl_VertexIndex];
  vec3 offset = vec3((corner & 1u) != 0u ? 1.0 : -1.0, (corner & 2u) != 0u ? 1.0 : -1.0, (corner & 4u) != 0u ? 1.0 : -1.0);
  vec4 world = inst.worldFromObject * vec4(s.center + offset * s.radius, 1.0);
  outWorldPos = world.xyz;
  outSphere = gl_InstanceIndex;
  gl_Position = frame.clipFromWorld * world;
}
