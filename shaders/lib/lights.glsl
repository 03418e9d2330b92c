// Light sampling and evaluation shared by the shadow pass and lighting.
#ifndef RAYSTER_LIGHTS_GLSL
#define RAYSTER_LIGHTS_GLSL

// Direction and distance from P towards a light's centre (directional: towards the sun).
void lightCentre(LightRecord l, vec3 p, out vec3 dir, out float dist) {
  if (l.type == kLightDirectional) {
    dir = -normalize(l.direction);
    dist = 1e30;
  } else {
    vec3 d = l.position - p;
    dist = length(d);
    dir = d / dist;
  }
}

// A direction towards a uniformly sampled point of the light's solid angle (docs/techniques.md §9):
// the cone a sphere subtends, the sun's angular cone, or the centre for a hard point light.
// `dist` is the distance to travel before reaching the light's surface.
vec3 sampleLightDirection(LightRecord l, vec3 p, vec2 u, out float dist) {
  vec3 axis;
  float centreDist;
  lightCentre(l, p, axis, centreDist);
  float cosMax;
  if (l.type == kLightDirectional) {
    cosMax = cos(l.angularRadius);
  } else {
    if (l.radius <= 0.0 || centreDist <= l.radius) {
      dist = centreDist;
      return axis;
    }
    float s = l.radius / centreDist;
    cosMax = sqrt(max(0.0, 1.0 - s * s));
  }
  float cosTheta = 1.0 - u.x * (1.0 - cosMax);
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * kPi * u.y;
  vec3 t, b;
  orthonormalBasis(axis, t, b);
  vec3 dir = normalize(t * (cos(phi) * sinTheta) + b * (sin(phi) * sinTheta) + axis * cosTheta);
  if (l.type == kLightDirectional) {
    dist = 1e30;
  } else {
    // Distance along `dir` to the sphere's near surface.
    float bq = dot(dir, axis) * centreDist;
    float disc = bq * bq - (centreDist * centreDist - l.radius * l.radius);
    dist = bq - sqrt(max(disc, 0.0));
  }
  return dir;
}

// Unshadowed incident radiance scale from the light at P along its centre direction.
vec3 lightIncident(LightRecord l, vec3 p, out vec3 dir, out float dist) {
  lightCentre(l, p, dir, dist);
  if (l.type == kLightDirectional) return l.radiance;
  // Inside a sphere light the inverse square law has no meaning: clamp at its surface.
  float d = max(dist, max(l.radius, 1e-3));
  vec3 e = l.radiance / (d * d);
  if (l.type == kLightSpot) {
    float cd = dot(-dir, normalize(l.direction));
    e *= smoothstep(l.cosOuter, l.cosInner, cd);
  }
  return e;
}

#endif
