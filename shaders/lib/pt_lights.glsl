// Light sampling of the path tracer beyond lib/lights.glsl: solid-angle densities of sphere and sun
// lights (for MIS), BSDF rays hitting a sphere light, the emissive-triangle list
// (render/gpu_emissive.cpp) and the environment's 2D CDF (render/gpu_environment.cpp).
// Needs lib/lights.glsl, lib/environment.glsl, lib/textures.glsl and lib/surface.glsl.
#ifndef RAYSTER_PT_LIGHTS_GLSL
#define RAYSTER_PT_LIGHTS_GLSL

layout(buffer_reference, scalar) readonly buffer EmissiveTriangles { EmissiveTriangle t[]; };
layout(buffer_reference, scalar) readonly buffer Floats { float f[]; };

// 1 − cosθmax of the cone a light subtends from `dist` (stable for small lights); 0: a delta light.
float lightConeOneMinusCos(LightRecord l, float dist) {
  if (l.type == kLightDirectional) {
    float s = sin(0.5 * l.angularRadius);
    return 2.0 * s * s;
  }
  if (l.radius <= 0.0 || dist <= l.radius) return 0.0;
  float s2 = (l.radius / dist) * (l.radius / dist);
  return s2 / (1.0 + sqrt(max(0.0, 1.0 - s2)));
}

// Radiance of a light's visible surface (sphere or sun disk) seen along `dir` (towards the light),
// given the cone it subtends; spot lights keep their cone falloff.
vec3 lightSurfaceRadiance(LightRecord l, vec3 dir, float oneMinusCos) {
  if (l.type == kLightDirectional) return l.radiance / (2.0 * kPi * oneMinusCos);  // irradiance over the disk
  vec3 le = l.radiance / (kPi * l.radius * l.radius);  // intensity I of a uniform sphere = L·πR²
  if (l.type == kLightSpot) le *= smoothstep(l.cosOuter, l.cosInner, dot(-dir, normalize(l.direction)));
  return le;
}

// The nearest sphere light (radius > 0) along the ray before tMax; returns frame.lightCount if none.
uint hitSphereLight(vec3 origin, vec3 dir, float tMax, out float tHit) {
  uint hit = frame.lightCount;
  tHit = tMax;
  for (uint i = 0u; i < frame.lightCount; ++i) {
    LightRecord l = loadLight(i);
    if (l.type == kLightDirectional || l.radius <= 0.0) continue;
    vec3 o = origin - l.position;
    float b = dot(o, dir), c = dot(o, o) - l.radius * l.radius;
    float disc = b * b - c;
    if (c <= 0.0 || disc < 0.0) continue;  // inside a light, or missing it
    float t = -b - sqrt(disc);
    if (t > 0.0 && t < tHit) {
      tHit = t;
      hit = i;
    }
  }
  return hit;
}

// Emission of an emissive triangle at barycentrics w (as evaluateSurface() computes it): unlit
// materials emit their base colour × texture × vertex colour.
vec3 triangleEmission(EmissiveTriangle t, vec3 w) {
  MaterialRecord m = Materials(frame.materials).m[t.material];
  vec2 uv = t.uv0 * w.x + t.uv1 * w.y + t.uv2 * w.z;
  if ((m.flags & kMaterialUnlit) != 0u) {
    vec4 color = vertexColor(Geometries(frame.geometries).g[t.geometry], t.primitive, w);
    return frame.exposure * m.baseColor.rgb * SAMPLE_SLOT(m.baseColorTexture, uv, uv, vec4(1.0)).rgb * color.rgb;
  }
  return exposedEmission(m) * SAMPLE_SLOT(m.emissiveTexture, uv, uv, vec4(1.0)).rgb;
}

// A point uniformly on the emissive area: triangle by area (binary search of the CDF), then
// uniform barycentrics. Density over area 1 / frame.emissiveArea. `x`: the point it lights.
void sampleEmissive(vec3 u, vec3 x, out vec3 q, out vec3 nq, out vec3 emission) {
  EmissiveTriangles tris = EmissiveTriangles(frame.emissiveTriangles);
  uint lo = 0u, hi = frame.emissiveTriangleCount - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (tris.t[mid].cdf > u.x) hi = mid; else lo = mid + 1u;
  }
  EmissiveTriangle t = tris.t[lo];
  float su = sqrt(u.y);
  vec3 w = vec3(1.0 - su, su * (1.0 - u.z), su * u.z);
  q = t.p0 * w.x + t.p1 * w.y + t.p2 * w.z;
  nq = normalize(cross(t.p1 - t.p0, t.p2 - t.p0)) * t.frontSign;  // the front side
  emission = triangleEmission(t, w);
  // A single-sided emitter has no back face for rays (lib/ray_flags.glsl): it lights only its front.
  if ((Materials(frame.materials).m[t.material].flags & kMaterialCullsBackFaces) != 0u && dot(nq, x - q) <= 0.0)
    emission = vec3(0.0);
}

// Index of the first entry of the inclusive CDF f[base .. base + n) greater than u.
uint searchCdf(Floats f, uint base, uint n, float u) {
  uint lo = 0u, hi = n - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (f.f[base + mid] > u) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

// Solid-angle density of sampleEnvironment() for a world direction.
float environmentPdf(vec3 dir) {
  uint w = frame.environmentCdfWidth, h = frame.environmentCdfHeight;
  if (w == 0u) return 0.0;
  vec2 uv = equirectUv(rotateY(normalize(dir), -frame.environment.w));
  uint x = min(uint(uv.x * float(w)), w - 1u), y = min(uint(uv.y * float(h)), h - 1u);
  float p = Floats(frame.environmentCdf).f[y * w + x];
  // Uniform inside a cell in (u, v), and dω = 2π² sinθ du dv.
  return p * float(w * h) / (2.0 * kPi * kPi * max(sin(uv.y * kPi), 1e-6));
}

// A direction ∝ the environment's luminance (a cell from the 2D CDF, uniform in it); pdf over
// solid angle. The uniform-in-(u, v) cell makes the density 1/sinθ within it: environmentPdf().
vec3 sampleEnvironment(vec2 u, out float pdf) {
  uint w = frame.environmentCdfWidth, h = frame.environmentCdfHeight;
  Floats f = Floats(frame.environmentCdf);
  uint rowsBase = w * h, marginalBase = 2u * w * h;
  uint y = searchCdf(f, marginalBase, h, u.x);
  float rowLo = y == 0u ? 0.0 : f.f[marginalBase + y - 1u];
  float ry = clamp((u.x - rowLo) / max(f.f[marginalBase + y] - rowLo, 1e-12), 0.0, 1.0);
  uint x = searchCdf(f, rowsBase + y * w, w, u.y);
  float colLo = x == 0u ? 0.0 : f.f[rowsBase + y * w + x - 1u];
  float rx = clamp((u.y - colLo) / max(f.f[rowsBase + y * w + x] - colLo, 1e-12), 0.0, 1.0);
  // Reusing the remainders of the two searches as the position inside the cell.
  vec2 uv = vec2((float(x) + rx) / float(w), (float(y) + ry) / float(h));
  float phi = (uv.x - 0.5) * 2.0 * kPi, theta = uv.y * kPi;
  vec3 local = vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));  // equirectDirection()
  vec3 dir = rotateY(local, frame.environment.w);
  pdf = f.f[y * w + x] * float(w * h) / (2.0 * kPi * kPi * max(sin(theta), 1e-6));
  return dir;
}

#endif
