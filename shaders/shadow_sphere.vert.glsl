#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"

// Analytic spheres in a shadow map: each sphere's bounding cube, seen from the light; the fragment
// shader intersects the exact sphere along the light's ray (shadow_sphere.frag).
layout(push_constant, scalar) uniform Push { ShadowSpherePush pc; };

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) flat out uint outSphere;

const uint kCubeIndices[36] = uint[36](0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                       2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5);

void main() {
  InstanceRecord inst = Instances(frame.instances).i[pc.instance];
  GeometryRecord g = Geometries(frame.geometries).g[pc.geometry];
  SphereRecord s = Spheres(g.vertexAddress).s[gl_InstanceIndex];
  uint corner = kCubeIndices[gl_VertexIndex];
  vec3 offset = vec3((corner & 1u) != 0u ? 1.0 : -1.0, (corner & 2u) != 0u ? 1.0 : -1.0, (corner & 4u) != 0u ? 1.0 : -1.0);
  vec4 world = inst.worldFromObject * vec4(s.center + offset * s.radius, 1.0);
  outWorldPos = world.xyz;
  outSphere = gl_InstanceIndex;
  gl_Position = pc.clipFromWorld * world;
}
