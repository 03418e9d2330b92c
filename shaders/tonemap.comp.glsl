#version 460
#include "lib/common.glsl"

// HDR (already exposed: the sources are pre-exposed, lib/frame.glsl) → tonemap operator → exact sRGB → ±0.5 LSB dither → RGBA8 UNORM.
// The sRGB encoding happens here, once, and the target is UNORM (never an sRGB format too).
// render/tonemap_curves.cpp mirrors the operators for the unit tests: keep both in step.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1) uniform sampler2D hdrTex;
layout(set = 0, binding = 2, rgba8) uniform writeonly image2D outLdr;
layout(push_constant, scalar) uniform Push { TonemapPush pc; };

// Hill's fit of ACES RRT+ODT. Rows of the fit's matrices; mat3(rows) * v in HLSL equals
// v * mat3(rows) in GLSL.
const mat3 kAcesIn = mat3(vec3(0.59719, 0.35458, 0.04823), vec3(0.07600, 0.90834, 0.01566),
                          vec3(0.02840, 0.13383, 0.83777));
const mat3 kAcesOut = mat3(vec3(1.60475, -0.53108, -0.07367), vec3(-0.10208, 1.10813, -0.00605),
                           vec3(-0.00327, -0.07276, 1.07602));

vec3 acesFitted(vec3 c) {
  c = c * kAcesIn;
  c = (c * (c + 0.0245786) - 0.000090537) / (c * (0.983729 * c + 0.4329510) + 0.238081);
  return clamp(c * kAcesOut, 0.0, 1.0);
}

// Khronos PBR Neutral (KhronosGroup/ToneMapping, PBR_Neutral): F90 = 0.04 offset, compression
// from Ks = 0.8 − F90, desaturation speed Kd = 0.15 towards the compressed peak.
const float kF90 = 0.04;
const float kStartCompression = 0.8 - kF90;
const float kDesaturation = 0.15;

vec3 pbrNeutral(vec3 c) {
  float x = min(c.r, min(c.g, c.b));
  float offset = x < 2.0 * kF90 ? x - x * x / (4.0 * kF90) : kF90;
  c -= offset;
  float peak = max(c.r, max(c.g, c.b));
  if (peak < kStartCompression) return c;
  const float d = 1.0 - kStartCompression;
  float newPeak = 1.0 - d * d / (peak + d - kStartCompression);
  c *= newPeak / peak;
  float g = 1.0 - 1.0 / (kDesaturation * (peak - newPeak) + 1.0);
  return mix(c, vec3(newPeak), g);
}

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(id, pc.size))) return;
  vec3 hdr = max(texelFetch(hdrTex, ivec2(id), 0).rgb, vec3(0.0));
  vec3 ldr = linearToSrgb(pc.op == kTonemapNeutral ? pbrNeutral(hdr) : acesFitted(hdr));
  uint h = pcg(id.x + pcg(id.y + pcg(pc.seed)));
  float dither = (float(h >> 8) * (1.0 / 16777216.0) - 0.5) / 255.0;
  imageStore(outLdr, ivec2(id), vec4(clamp(ldr + dither * pc.dither, 0.0, 1.0), 1.0));
}
