// Shared by the denoisers: the compact surface image (written by surface.comp), reprojection with
// per-tap disocclusion tests (TECHNIQUES.md §2) and the à-trous edge-stopping weights (§12).
// Every input is read with texelFetch: no filtering hardware, so formats and layouts stay free.
#ifndef RAYSTER_DENOISE_GLSL
#define RAYSTER_DENOISE_GLSL

#include "shared/denoise.h"

// Surface texel (RGBA32UI): x linear view depth (float bits; 0 for sky), y its screen-space slope
// (|dz/dx| + |dz/dy| by one-sided differences), z oct shading normal (packSnorm2x16), w id.
struct Surface {
  float z;
  float zGrad;
  vec3 n;
  uint id;
};

Surface decodeSurface(uvec4 t) {
  Surface s;
  s.z = uintBitsToFloat(t.x);
  s.zGrad = uintBitsToFloat(t.y);
  s.n = octDecode(unpackSnorm2x16(t.z));
  s.id = t.w;
  return s;
}

bool isSky(Surface s) { return s.id == kBackgroundId; }

// May a previous-frame surface supply history to the current one?
bool sameSurface(Surface cur, Surface prev) {
  if (prev.id != cur.id) return false;
  float tolerance = kReprojectDepthRelative * cur.z + kReprojectDepthSlopes * max(cur.zGrad, prev.zGrad);
  return abs(cur.z - prev.z) <= tolerance && dot(cur.n, prev.n) >= kReprojectNormalDot;
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
    if (w <= 0.0 || !inside || !sameSurface(cur, decodeSurface(texelFetch(prevSurface, r.tap[k], 0)))) w = 0.0;
    r.w[k] = w;
    r.sum += w;
  }
  return r;
}

bool hasHistory(Reprojection r) { return r.sum >= kReprojectMinWeight; }

// B3-spline taps (1/16, 1/4, 3/8, 1/4, 1/16) for offsets −2..2.
float b3(int i) { return i == 0 ? 0.375 : (abs(i) == 1 ? 0.25 : 0.0625); }

// Depth and normal edge-stopping weight of neighbour q at offset `offset` pixels from p:
// w_z = exp(−|z_p − z_q| / (σz·|∇z·offset| + ε)), w_n = max(0, n_p·n_q)^σn.
float geometryWeight(Surface p, Surface q, vec2 offset) {
  float wz = exp(-abs(p.z - q.z) / (kSigmaDepth * p.zGrad * length(offset) + kDepthEpsilon));
  float wn = pow(max(0.0, dot(p.n, q.n)), kSigmaNormal);
  return wz * wn;
}


#endif
