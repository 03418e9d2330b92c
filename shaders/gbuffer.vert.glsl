#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"

// Vertices are pulled by device address; draws are non-indexed over the index count.
// The draw comes from the culled list (render/passes/cull.cpp): gl_DrawID indexes drawIds, whose
// entry is the DrawRecord row.
layout(push_constant, scalar) uniform Push { GBufferDrawPush pc; };
layout(buffer_reference, scalar) readonly buffer DrawRecords { DrawRecord d[]; };
layout(buffer_reference, scalar) readonly buffer DrawIds { uint i[]; };

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec4 outTangent;
layout(location = 3) out vec2 outUv0;
layout(location = 4) out vec2 outUv1;
layout(location = 5) out vec3 outPrevWorldPos;  // for the motion vector
layout(location = 6) flat out uvec2 outDraw;  // instance, geometry (for the fragment shader)
layout(location = 7) out vec4 outColor;       // COLOR_0 (white without)

void main() {
  DrawRecord draw = DrawRecords(pc.records).d[DrawIds(pc.drawIds).i[gl_DrawID]];
  outDraw = uvec2(draw.instance, draw.geometry);
  InstanceRecord inst = Instances(frame.instances).i[draw.instance];
  GeometryRecord g = Geometries(frame.geometries).g[draw.geometry];
  uint index = Indices(g.indexAddress).i[gl_VertexIndex];
  Vertex v = Vertices(g.vertexAddress).v[index];
  vec4 world = inst.worldFromObject * vec4(v.position, 1.0);
  outWorldPos = world.xyz;
  // Deforming geometry moves within the instance too: last frame's position of this vertex.
  vec3 prevPosition = g.prevPositionAddress != 0ul ? Positions(g.prevPositionAddress).p[index] : v.position;
  outPrevWorldPos = (inst.prevWorldFromObject * vec4(prevPosition, 1.0)).xyz;
  outNormal = (inst.normalFromObject * vec4(v.normal, 0.0)).xyz;
  outTangent = vec4((inst.worldFromObject * vec4(v.tangent.xyz, 0.0)).xyz, v.tangent.w);
  outUv0 = v.uv0;
  outUv1 = v.uv1;
  outColor = vertexColor(g, index);
  gl_Position = frame.clipFromWorld * world;
}
