// Analytic spheres, shared by the intersection shader and the raster impostor, so both find the
// same surface point.
#ifndef RAYSTER_SPHERE_GLSL
#define RAYSTER_SPHERE_GLSL

// Nearest t in [tMin, tMax] where origin + t·dir meets the sphere, or -1. `dir` need not be unit.
float intersectSphere(vec3 center, float radius, vec3 origin, vec3 dir, float tMin, float tMax) {
  vec3 oc = origin - center;
  float a = dot(dir, dir);
  float b = dot(oc, dir);
  // Numerically robust discriminant (Ray Tracing Gems ch. 7): avoids cancellation far from the sphere.
  vec3 l = oc - (b / a) * dir;
  float disc = radius * radius - dot(l, l);
  if (disc < 0.0) return -1.0;
  float q = -b - sign(b) * sqrt(a * disc);
  float t0 = q / a, t1 = dot(oc, oc) - radius * radius;
  t1 = q != 0.0 ? t1 / q : t0;
  float tn = min(t0, t1), tf = max(t0, t1);
  if (tn >= tMin && tn <= tMax) return tn;
  if (tf >= tMin && tf <= tMax) return tf;
  return -1.0;
}

// Sphere surface attributes in object space: normal, equirect UV, tangent along +longitude.
void sphereAttributes(vec3 center, vec3 objectPos, out vec3 n, out vec2 uv, out vec4 tangent) {
  n = normalize(objectPos - center);
  uv = vec2(atan(n.x, -n.z) / (2.0 * kPi) + 0.5, acos(clamp(n.y, -1.0, 1.0)) / kPi);
  vec3 t = vec3(-n.z, 0.0, -n.x);
  tangent = vec4(dot(t, t) > 1e-12 ? normalize(t) : vec3(1.0, 0.0, 0.0), 1.0);
}

#endif
