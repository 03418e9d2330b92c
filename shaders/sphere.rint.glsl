#version 460
#extension GL_EXT_ray_tracing : require
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/sphere.glsl"

// Analytic spheres (AABB geometry): reports the nearest hit in the ray's interval, in object space
// (t is the same parameter as in world space).
hitAttributeEXT vec2 unused;

void main() {
  InstanceRecord inst = Instances(frame.instances).i[gl_InstanceCustomIndexEXT];
  GeometryRecord g = Geometries(frame.geometries).g[inst.firstGeometry + gl_GeometryIndexEXT];
  SphereRecord s = Spheres(g.vertexAddress).s[gl_PrimitiveID];
  float t = intersectSphere(s.center, s.radius, gl_ObjectRayOriginEXT, gl_ObjectRayDirectionEXT, gl_RayTminEXT,
                            gl_RayTmaxEXT);
  if (t >= 0.0) {
    unused = vec2(0.0);
    reportIntersectionEXT(t, 0u);
  }
}
