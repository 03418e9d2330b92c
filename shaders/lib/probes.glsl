// Irradiance probes (shared/probes.h, docs/techniques.md §16b): indexing, ray directions, atlas
// addressing and the lookup of irradiance at a surface point from its eight surrounding probes with
// trilinear, back-face and Chebyshev visibility weights. The includer declares (unless it defines
// PROBES_NO_LOOKUP)
//   uniform sampler2D probeIrradianceTex;  // linear filtering, clamp
//   uniform sampler2D probeVisibilityTex;
//   uniform sampler2D probeDataTex;        // (probe, 0): offset and state (probe_classify.comp)
#ifndef RAYSTER_PROBES_GLSL
#define RAYSTER_PROBES_GLSL

uint probeCount(ProbeGrid g) { return g.counts.x * g.counts.y * g.counts.z; }

ivec3 probeCoord(ProbeGrid g, uint i) {
  return ivec3(i % g.counts.x, (i / g.counts.x) % g.counts.y, i / (g.counts.x * g.counts.y));
}
uint probeIndex(ProbeGrid g, ivec3 c) { return uint(c.x) + g.counts.x * (uint(c.y) + g.counts.y * uint(c.z)); }
vec3 probePosition(ProbeGrid g, ivec3 c) { return g.origin + vec3(c) * g.spacing; }

vec3 rotateByQuaternion(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }

// Ray r of n: a spherical Fibonacci point set (evenly spread directions), rotated by the frame's
// random rotation so the probes see new directions every frame.
vec3 probeRayDirection(ProbeGrid g, uint r) {
  const float goldenAngle = 2.39996322972865332;
  float z = 1.0 - (2.0 * float(r) + 1.0) / float(g.raysPerProbe);
  float radius = sqrt(max(0.0, 1.0 - z * z));
  float phi = float(r) * goldenAngle;
  return rotateByQuaternion(g.rotation, vec3(radius * cos(phi), radius * sin(phi), z));
}

// Octahedral coordinates of a tile texel, including the border: texel (x, y) of a tile with
// `interior` texels per side (x, y in 0 .. interior+1; 1 .. interior are the interior), in [-1, 1]²,
// folded back across the square's edges (the octahedral map's edge (1, v) is the edge (1, −v)).
vec2 probeTexelOct(ivec2 texel, uint interior) {
  vec2 e = (vec2(texel) - 0.5) / float(interior) * 2.0 - 1.0;
  if (abs(e.x) > 1.0) {
    e.x = sign(e.x) * 2.0 - e.x;
    e.y = -e.y;
  }
  if (abs(e.y) > 1.0) {
    e.y = sign(e.y) * 2.0 - e.y;
    e.x = -e.x;
  }
  return e;
}

ivec2 probeTileOrigin(ProbeGrid g, uint probe, uint interior) {
  return ivec2(probe % g.tilesPerRow, probe / g.tilesPerRow) * int(interior + 2u);
}

// Where direction `dir` of probe `probe` is in an atlas (uv, for filtered reads).
vec2 probeAtlasUv(ProbeGrid g, uint probe, vec3 dir, uint interior, vec2 atlasSize) {
  vec2 o = octEncode(normalize(dir)) * 0.5 + 0.5;
  return (vec2(probeTileOrigin(g, probe, interior)) + 1.0 + o * float(interior)) / atlasSize;
}

#ifndef PROBES_NO_LOOKUP
// A probe's relocation offset (xyz) and state (w: 1 active, 0 inactive), from probe_classify.comp.
vec4 probeData(ProbeGrid g, uint probe) {
  return (g.flags & kProbeDataValid) != 0u ? texelFetch(probeDataTex, ivec2(probe, 0), 0) : vec4(0.0, 0.0, 0.0, 1.0);
}

// Irradiance at p (shading normal n, direction to the viewer v) from the eight probes of its grid
// cell, in the directions n (e) and r (er: probeIrradiance2 only, the mirror direction for the
// untraced specular light; one set of weights for both). Each probe counts with its trilinear
// weight, a smooth back-face weight (probes behind the surface count little) and the Chebyshev
// bound of being visible from the probe's distance moments.
void probeIrradiance2(ProbeGrid g, vec3 p, vec3 n, vec3 v, bool withR, vec3 r, out vec3 e, out vec3 er) {
  vec2 irradianceSize = vec2(textureSize(probeIrradianceTex, 0));
  vec2 visibilitySize = vec2(textureSize(probeVisibilityTex, 0));
  float minSpacing = min(g.spacing.x, min(g.spacing.y, g.spacing.z));
  vec3 biased = p + (n * g.normalBias + v * g.viewBias) * minSpacing;
  vec3 cellPos = clamp((biased - g.origin) / g.spacing, vec3(0.0), vec3(g.counts - 1u));
  ivec3 base = min(ivec3(floor(cellPos)), ivec3(g.counts) - 2);
  vec3 alpha = clamp(cellPos - vec3(base), 0.0, 1.0);
  vec3 sum = vec3(0.0), sumR = vec3(0.0);
  float weightSum = 0.0;
  for (int i = 0; i < 8; ++i) {
    ivec3 offset = ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    ivec3 c = base + offset;
    uint probe = probeIndex(g, c);
    vec4 data = probeData(g, probe);
    if (data.w < 0.5) continue;  // inactive: inside geometry, or no surface near it
    vec3 probePos = probePosition(g, c) + data.xyz;
    vec3 trilinear = mix(1.0 - alpha, alpha, vec3(offset));
    float weight = trilinear.x * trilinear.y * trilinear.z;
    vec3 toProbe = normalize(probePos - p);
    float facing = (dot(toProbe, n) + 1.0) * 0.5;
    weight *= facing * facing + 0.2;
    vec3 fromProbe = biased - probePos;
    float distance = length(fromProbe);
    vec2 moments = texture(probeVisibilityTex, probeAtlasUv(g, probe, fromProbe, kProbeVisibilityTexels, visibilitySize)).rg;
    if (distance > moments.x) {
      float variance = abs(moments.y - moments.x * moments.x);
      float d = distance - moments.x;
      float chebyshev = variance / (variance + d * d);
      weight *= max(chebyshev * chebyshev * chebyshev, 0.0);
    }
    weight = max(weight, 1e-6);
    // Crush tiny weights (they would tint the result without adding light).
    if (weight < 0.2) weight *= weight * weight / (0.04);
    sum += weight * texture(probeIrradianceTex, probeAtlasUv(g, probe, n, kProbeIrradianceTexels, irradianceSize)).rgb;
    if (withR)
      sumR += weight * texture(probeIrradianceTex, probeAtlasUv(g, probe, r, kProbeIrradianceTexels, irradianceSize)).rgb;
    weightSum += weight;
  }
  e = weightSum > 0.0 ? sum / weightSum : vec3(0.0);
  er = weightSum > 0.0 ? sumR / weightSum : vec3(0.0);
}

vec3 probeIrradiance(ProbeGrid g, vec3 p, vec3 n, vec3 v) {
  vec3 e, unused;
  probeIrradiance2(g, p, n, v, false, n, e, unused);
  return e;
}
#endif

#endif
