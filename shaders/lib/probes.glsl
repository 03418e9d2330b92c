// Irradiance probes (shared/probes.h, docs/techniques.md §16b): indexing, ray directions, atlas
// addressing and the lookup of irradiance at a surface point from its eight surrounding probes with
// trilinear, back-face and Chebyshev visibility weights, in the finest cascade around it. The
// includer declares (unless it defines PROBES_NO_LOOKUP)
//   uniform sampler2D probeIrradianceTex;  // linear filtering, clamp
//   uniform sampler2D probeVisibilityTex;
//   uniform sampler2D probeDataTex;        // (probe, 0): offset and state (probe_classify.comp)
#ifndef RAYSTER_PROBES_GLSL
#define RAYSTER_PROBES_GLSL

// Probe i of the atlases is slot i % probesPerCascade() of cascade i / probesPerCascade(); a slot
// holds the lattice point whose coordinate is the slot's modulo counts (shared/probes.h).
uint probesPerCascade(ProbeGrid g) { return g.counts.x * g.counts.y * g.counts.z; }
uint probeCount(ProbeGrid g) { return probesPerCascade(g) * g.cascades; }
uint probeCascade(ProbeGrid g, uint i) { return i / probesPerCascade(g); }
// Cascade k's cells per coarsest cell on each axis (a power of two: 1 on an axis the coarsest
// spacing already resolves).
ivec3 probeScale(ProbeGrid g, uint k) {
  uint w = g.cascadeCells[k].x >> 24;
  return ivec3(1) << ivec3(w & 3u, (w >> 2) & 3u, (w >> 4) & 3u);
}
vec3 probeSpacing(ProbeGrid g, uint k) { return g.spacing / vec3(probeScale(g, k)); }
float probeMinSpacing(ProbeGrid g, uint k) {
  vec3 s = probeSpacing(g, k);
  return min(s.x, min(s.y, s.z));
}
ivec3 probeUnpackCell(uint w) { return ivec3(w & 0xffu, (w >> 8) & 0xffu, (w >> 16) & 0xffu); }
ivec3 probeWindow(ProbeGrid g, uint k) { return probeUnpackCell(g.cascadeCells[k].x); }

ivec3 probeSlotOffset(ProbeGrid g, uint k) {  // the window's cells modulo counts
  uint w = g.cascadeCells[k].y;
  return ivec3(w & 7u, (w >> 3) & 7u, (w >> 6) & 7u);
}
// When cascade k's window moved since the update before: by how many cells (else 0).
ivec3 probeWindowMove(ProbeGrid g, uint k) {
  uint w = g.cascadeCells[k].y >> 9;
  return ivec3(w & 31u, (w >> 5) & 31u, (w >> 10) & 31u) - 8;
}

// The window coordinate (0 .. counts − 1) of probe i in its cascade.
ivec3 probeWindowCoord(ProbeGrid g, uint i) {
  uint j = i % probesPerCascade(g);
  ivec3 n = ivec3(g.counts);
  ivec3 slot = ivec3(j % g.counts.x, (j / g.counts.x) % g.counts.y, j / (g.counts.x * g.counts.y));
  return (slot - probeSlotOffset(g, probeCascade(g, i)) + n) % n;
}
vec3 probeWorldPosition(ProbeGrid g, uint i) {
  uint k = probeCascade(g, i);
  return g.origin + vec3(probeWindow(g, k) + probeWindowCoord(g, i)) * probeSpacing(g, k);
}
// Window coordinate c of cascade k entered the window at this update (the window scrolled with the
// camera): the atlases and data of the update before hold another point's light in its slot.
bool probeFreshAt(ProbeGrid g, uint k, ivec3 c) {
  if ((g.cascadeCells[k].x & kProbeWindowMoved) == 0u) return false;
  ivec3 d = c + probeWindowMove(g, k);  // its place in the window before
  return any(lessThan(d, ivec3(0))) || any(greaterThanEqual(d, ivec3(g.counts)));
}
bool probeFresh(ProbeGrid g, uint i) { return probeFreshAt(g, probeCascade(g, i), probeWindowCoord(g, i)); }

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

// Where p lies in cascade k's window, in its cells (0 .. counts − 1 inside).
vec3 probeCascadePosition(ProbeGrid g, uint k, vec3 p) {
  return (p - g.origin) / probeSpacing(g, k) - vec3(probeWindow(g, k));
}

// Cascade k's share of probeIrradiance2(): the eight probes of p's cell, each with its trilinear
// weight, a smooth back-face weight (probes behind the surface count little) and the Chebyshev
// bound of being visible from the probe's distance moments. Returns the sum of the weights (0:
// every probe there inactive or fresh). `single`: the grid has one cascade (a constant at every
// call: the compiler drops the window and slot arithmetic, which the H200 measured at 7 % of
// rt-specular in a small scene).
float probeCascadeIrradiance(ProbeGrid g, uint k, const bool single, vec3 p, vec3 n, vec3 v, bool withR, vec3 r,
                             out vec3 e, out vec3 er) {
  vec2 irradianceSize = vec2(textureSize(probeIrradianceTex, 0));
  vec2 visibilitySize = vec2(textureSize(probeVisibilityTex, 0));
  // Per cascade once (no division at all): its spacing, its window and the slot of its first probe.
  vec3 spacing = single ? g.spacing : probeSpacing(g, k);
  ivec3 counts = ivec3(g.counts);
  ivec3 window = single ? ivec3(0) : probeWindow(g, k), slotOffset = single ? ivec3(0) : probeSlotOffset(g, k);
  uint first = single ? 0u : k * probesPerCascade(g);
  vec3 biased = p + (n * g.normalBias + v * g.viewBias) * min(spacing.x, min(spacing.y, spacing.z));
  vec3 cellPos = clamp((biased - g.origin) / spacing - vec3(window), vec3(0.0), vec3(counts - 1));
  ivec3 base = min(ivec3(floor(cellPos)), counts - 2);
  vec3 alpha = clamp(cellPos - vec3(base), 0.0, 1.0);
  vec3 sum = vec3(0.0), sumR = vec3(0.0);
  float weightSum = 0.0;
  for (int i = 0; i < 8; ++i) {
    ivec3 offset = ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    ivec3 c = base + offset;  // in the window
    ivec3 slot = c;
    if (!single) {
      slot += slotOffset;
      slot -= mix(ivec3(0), counts, greaterThanEqual(slot, counts));  // (window + c) % counts
    }
    uint probe = first + uint(slot.x) + g.counts.x * (uint(slot.y) + g.counts.y * uint(slot.z));
    if (!single && probeFreshAt(g, k, c)) continue;  // its light is of another place until it is updated
    vec4 data = probeData(g, probe);
    if (data.w < 0.5) continue;  // inactive: inside geometry, or no surface near it
    vec3 probePos = g.origin + vec3(window + c) * spacing + data.xyz;
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
  return weightSum;
}

// Irradiance at p (shading normal n, direction to the viewer v) in the directions n (e) and r (er:
// probeIrradiance2 only, the mirror direction for the untraced specular light; one set of weights
// for both), from the finest cascade whose window holds p; within its last cell of the window's
// edge it fades into the next coarser one, and where its eight probes are all inactive the next
// coarser one lights p alone. The coarsest cascade holds the whole scene.
void probeIrradiance2(ProbeGrid g, vec3 p, vec3 n, vec3 v, bool withR, vec3 r, out vec3 e, out vec3 er) {
  if (g.cascades == 1u) {  // a small scene's one grid (measured faster on the H200 than the loop below)
    probeCascadeIrradiance(g, 0u, true, p, n, v, withR, r, e, er);
    return;
  }
  e = vec3(0.0);
  er = vec3(0.0);
  // The finest cascade whose window holds p, and its weight (1 inside, fading over the last cell).
  uint k = 0u;
  float w = 1.0;
  for (; k + 1u < g.cascades; ++k) {
    // The distance to the window's edges, in its cells; an edge on the coarsest grid's face does
    // not count (past it every cascade clamps alike: the margin between the bounds and the probes).
    vec3 c = probeCascadePosition(g, k, p);
    ivec3 cell = probeWindow(g, k), last = (ivec3(g.counts) - 1) * (probeScale(g, k) - 1);
    vec3 below = mix(c, vec3(1e9), equal(cell, ivec3(0)));
    vec3 above = mix(vec3(g.counts - 1u) - c, vec3(1e9), equal(cell, last));
    vec3 toEdge = min(below, above);
    w = clamp(min(toEdge.x, min(toEdge.y, toEdge.z)), 0.0, 1.0);
    if (w > 0.0) break;
  }
  if (k + 1u == g.cascades) w = 1.0;
  // It and, where it fades or has no active probe around p, the next coarser one.
  float remaining = 1.0;
  for (uint pass = 0u; pass < 2u && k < g.cascades && remaining > 0.0; ++pass, ++k) {
    if (pass == 1u) w = 1.0;  // the coarser cascade takes what the finer one left
    vec3 ek, erk;
    if (probeCascadeIrradiance(g, k, false, p, n, v, withR, r, ek, erk) <= 0.0) continue;
    e += remaining * w * ek;
    er += remaining * w * erk;
    remaining *= 1.0 - w;
  }
  if (remaining > 0.0 && remaining < 1.0) {  // the coarser had no probe to give: the finer one's share is all
    e /= 1.0 - remaining;
    er /= 1.0 - remaining;
  }
}

vec3 probeIrradiance(ProbeGrid g, vec3 p, vec3 n, vec3 v) {
  vec3 e, unused;
  probeIrradiance2(g, p, n, v, false, n, e, unused);
  return e;
}
#endif

#endif
