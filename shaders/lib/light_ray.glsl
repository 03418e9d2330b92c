// The shadow ray towards light `i` from a point P (docs/techniques.md §9): a uniform sample of the
// light's solid angle, offset along the geometric normal. One definition for every pass that traces
// a shadow ray per shaded light (the bounce loop, many-light direct light, the indirect bounce) and
// for their raw-rate twins (raw_*.rgen), so both trace exactly the same rays. Needs lib/lights.glsl.
#ifndef RAYSTER_LIGHT_RAY_GLSL
#define RAYSTER_LIGHT_RAY_GLSL

// Offset of a ray leaving a traced hit at P: relative to P's magnitude (float precision).
float hitRayOffset(vec3 p) { return max(max(abs(p.x), max(abs(p.y), abs(p.z))), 1.0) * 1e-4; }

// False (no ray) when the sampled direction lies below the surface whose geometric normal is ng.
// `eps`: the offset along ng; the ray ends eps short of the sampled point on the light.
bool lightShadowRay(uint i, vec3 p, vec3 ng, float eps, inout uint rng, out vec3 origin, out vec3 dir,
                    out float tMax) {
  LightRecord light = loadLight(i);
  float dist;
  dir = sampleLightDirection(light, p, vec2(rnd(rng), rnd(rng)), dist);
  origin = p + ng * eps;
  tMax = max(dist - eps, 0.0);
  return dot(dir, ng) > 0.0;
}
// Draws what lightShadowRay draws, for a ray not traced.
void skipLightShadowRay(inout uint rng) {
  rnd(rng);
  rnd(rng);
}

#endif
