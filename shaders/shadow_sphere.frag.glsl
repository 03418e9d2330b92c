#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/sphere.glsl"

layout(push_constant, scalar) uniform Push { ShadowSpherePush pc; };

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) flat in uint inSphere;

void main() {
  InstanceRecord inst = Instances(frame.instances).i[pc.instance];
  GeometryRecord g = Geometries(frame.geometries).g[pc.geometry];
  SphereRecord s = Spheres(g.vertexAddress).s[inSphere];
  vec3 dir = pc.light.w > 0.0 ? normalize(inWorldPos - pc.light.xyz) : normalize(pc.light.xyz);
  mat4 objectFromWorld = inverse(inst.worldFromObject);
  vec3 objDir = normalize((objectFromWorld * vec4(dir, 0.0)).xyz);
  // Start in front of the sphere: every point of its bounding cube is within √3 radii of the centre.
  vec3 objOrigin = (objectFromWorld * vec4(inWorldPos, 1.0)).xyz - objDir * (2.0 * s.radius);
  float t = intersectSphere(s.center, s.radius, objOrigin, objDir, 0.0, 1e30);
  if (t < 0.0) discard;
  vec4 clip = pc.clipFromWorld * (inst.worldFromObject * vec4(objOrigin + t * objDir, 1.0));
  gl_FragDepth = clip.z / clip.w;
}
