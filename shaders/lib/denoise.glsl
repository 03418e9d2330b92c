// Shared by the denoisers: the compact surface image (written by surface.comp), reprojection with
// per-tap disocclusion tests (docs/techniques.md §2) and the à-trous edge-stopping weights (§14).
// Every input is read with texelFetch: no filtering hardware, so formats and layouts stay free.
#ifndef RAYSTER_DENOISE_GLSL
#define RAYSTER_DENOISE_GLSL

#include "shared/denoise.h"

// Surface texel (RG32UI, 8 B): x linear view depth (float bits; 0 for sky) with the sign bit set for
// a sharp surface (mirror or glass, roughness ≤ kSharpRoughness, which SVGF's à-trous neither
// filters nor takes as a neighbour: the flag rides on the guide every tap reads anyway), y bits 0–19 the oct
// shading normal (2 × snorm10), bits 20–31 the low 12 bits of the id. Precision: the depth stays
// fp32, since the depth weight's ε is 1e-4 absolute and coarser depths would cut planes along
// their rounding steps; 10-bit oct normals err by ≤ ~0.25°, far below the normal weight's
// half-width (cos^128 = 0.5 at ~8°: the weight moves by < 0.2 %) and the 25° reprojection test;
// the id only answers "same draw?", and draws 4096 apart that also touch on screen at the same
// depth and normal are the only pairs it confuses (the depth and normal tests still apply). The
// depth slope is not stored: loadSurface recomputes it from the 4 neighbours (bit-identical to
// storing it), and only the centre pixel of a filter and a reprojection tap that fails the cheap
// depth test need it.
struct Surface {
  float z;
  float zGrad;  // only from loadSurface (decodeSurface leaves 0)
  vec3 n;
  uint id;
  bool sharp;  // mirror or glass (never set on sky)
};

const uint kSurfaceSharpBit = 0x80000000u;  // in x: the sign of the (positive) depth

uvec2 encodeSurface(float z, vec2 oct, uint id, bool sharp) {
  uvec2 q = uvec2(ivec2(round(clamp(oct, -1.0, 1.0) * 511.0))) & 0x3FFu;
  return uvec2(floatBitsToUint(z) | (sharp ? kSurfaceSharpBit : 0u), q.x | (q.y << 10) | (id << 20));
}

Surface decodeSurface(uvec2 t) {
  Surface s;
  s.z = uintBitsToFloat(t.x & ~kSurfaceSharpBit);
  s.sharp = (t.x & kSurfaceSharpBit) != 0u;
  s.zGrad = 0.0;
  ivec2 q = ivec2(bitfieldExtract(int(t.y), 0, 10), bitfieldExtract(int(t.y), 10, 10));
  s.n = octDecode(clamp(vec2(q) / 511.0, -1.0, 1.0));
  s.id = t.x == 0u ? kBackgroundId : t.y >> 20;
  return s;
}

bool isSky(Surface s) { return s.id == kBackgroundId; }

// One-sided depth differences along one axis; the smaller one, so a silhouette beside the pixel
// does not pass for a steep slope. 0 when neither neighbour is geometry.
float surfaceSlope(usampler2D tex, ivec2 p, ivec2 axis, float z, uvec2 size) {
  float g = 1.0e30;
  for (int s = -1; s <= 1; s += 2) {
    ivec2 q = p + s * axis;
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(size)))) continue;
    uint bits = texelFetch(tex, q, 0).x & ~kSurfaceSharpBit;
    if (bits != 0u) g = min(g, abs(uintBitsToFloat(bits) - z));
  }
  return g < 1.0e30 ? g : 0.0;
}
// |dz/dx| + |dz/dy| of the surface at p.
float surfaceGradient(usampler2D tex, ivec2 p, float z, uvec2 size) {
  return surfaceSlope(tex, p, ivec2(1, 0), z, size) + surfaceSlope(tex, p, ivec2(0, 1), z, size);
}
// The surface at p with its depth slope (the centre of a filter).
Surface loadSurface(usampler2D tex, ivec2 p, uvec2 size) {
  Surface s = decodeSurface(texelFetch(tex, p, 0).xy);
  if (!isSky(s)) s.zGrad = surfaceGradient(tex, p, s.z, size);
  return s;
}

// May the previous frame's surface at q supply history to the current one? Same id, normals
// within kReprojectNormalDot, |Δz| ≤ 1 % of z + 2 slopes (the larger of the two). The previous
// slope is only computed when the current one's tolerance is not enough (same answer: the
// tolerance only grows with it).
bool sameSurface(Surface cur, usampler2D prevTex, ivec2 q, uvec2 size) {
  Surface prev = decodeSurface(texelFetch(prevTex, q, 0).xy);
  if (prev.id != cur.id || dot(cur.n, prev.n) < kReprojectNormalDot) return false;
  float dz = abs(cur.z - prev.z);
  if (dz <= kReprojectDepthRelative * cur.z + kReprojectDepthSlopes * cur.zGrad) return true;
  float prevGrad = surfaceGradient(prevTex, q, prev.z, size);
  return dz <= kReprojectDepthRelative * cur.z + kReprojectDepthSlopes * max(cur.zGrad, prevGrad);
}

// Bilinear footprint of the previous frame at uv − motion: four taps and their weights, each
// weight already zero for a tap that is off-screen or fails the disocclusion tests. The caller
// renormalises by the sum; a sum below kReprojectMinWeight means "no history" (n = 0).
struct Reprojection {
  ivec2 tap[4];
  float w[4];
  float sum;
};

Reprojection reproject(usampler2D prevSurface, ivec2 px, vec2 motion, uvec2 size, Surface cur) {
  Reprojection r;
  // Previous pixel centre = pixel + 0.5 − mv·size; its bilinear taps start half a texel lower.
  vec2 pos = vec2(px) + 0.5 - motion * vec2(size) - 0.5;
  ivec2 base = ivec2(floor(pos));
  vec2 f = pos - vec2(base);
  r.sum = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 o = ivec2(k & 1, k >> 1);
    r.tap[k] = base + o;
    float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    bool inside = all(greaterThanEqual(r.tap[k], ivec2(0))) && all(lessThan(r.tap[k], ivec2(size)));
    if (w <= 0.0 || !inside || !sameSurface(cur, prevSurface, r.tap[k], size)) w = 0.0;
    r.w[k] = w;
    r.sum += w;
  }
  return r;
}

bool hasHistory(Reprojection r) { return r.sum >= kReprojectMinWeight; }

// B3-spline taps (1/16, 1/4, 3/8, 1/4, 1/16) for offsets −2..2.
float b3(int i) { return i == 0 ? 0.375 : (abs(i) == 1 ? 0.25 : 0.0625); }

// Depth and normal edge-stopping weight of neighbour q (p from loadSurface) at offset `offset` pixels from p:
// w_z = exp(−|z_p − z_q| / (σz·|∇z·offset| + ε)), w_n = max(0, n_p·n_q)^σn.
float geometryWeight(Surface p, Surface q, vec2 offset) {
  float wz = exp(-abs(p.z - q.z) / (kSigmaDepth * p.zGrad * length(offset) + kDepthEpsilon));
  float wn = pow(max(0.0, dot(p.n, q.n)), kSigmaNormal);
  return wz * wn;
}

// The same weights split for the à-trous loops, which run them 24 times per pixel: the transcendental
// functions were most of their cost. w_n = max(0, n_p·n_q)^128 by seven squarings (σn = 2^7); the
// depth weight as its exponent with the reciprocal from atrousDepthScales(), so the caller folds it
// and the value weight into one exp().
float normalWeight(Surface p, Surface q) {
  float c = max(0.0, dot(p.n, q.n));
  for (int k = 0; k < kSigmaNormalLog2; ++k) c *= c;
  return c;
}
// 1 / (σz·|∇z|·|offset| + ε) for the five tap distances of a 5×5 kernel at `step`, indexed by
// atrousDistanceIndex(i, j): |(i, j)| = 1, √2, 2, √5, √8.
void atrousDepthScales(Surface p, int step, out float scales[5]) {
  const float lengths[5] = float[5](1.0, 1.41421356, 2.0, 2.23606798, 2.82842712);
  for (int k = 0; k < 5; ++k) scales[k] = 1.0 / (kSigmaDepth * p.zGrad * float(step) * lengths[k] + kDepthEpsilon);
}
int atrousDistanceIndex(int i, int j) {
  int d = i * i + j * j;  // 1, 2, 4, 5 or 8
  return d == 1 ? 0 : d == 2 ? 1 : d == 4 ? 2 : d == 5 ? 3 : 4;
}
float depthExponent(Surface p, Surface q, float scale) { return abs(p.z - q.z) * scale; }


#endif
