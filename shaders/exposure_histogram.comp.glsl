#version 460
#include "lib/common.glsl"
#include "shared/exposure.h"

// The luminance histograms of the frame's HDR image (after TAA, before the tonemap), in the scene's
// own units: each pixel's Rec. 709 luminance divided by the pre-exposure it was rendered with, in
// log2 bins (shared/exposure.h). A surface pixel counts as the luminance an 18 % grey surface would
// have in its place (its luminance × 0.18 / its albedo's): the meter reads the light falling on the
// scene, as an incident-light meter does, so white marble stays white and black cloth black instead
// of both turning grey. Background pixels count as they are, in the second histogram.
// One shared-memory histogram pair per 16×16 tile, added into the frame's once per bin. The host
// turns it into the next frame's exposure (render/exposure.cpp).
layout(local_size_x = 16, local_size_y = 16) in;
layout(set = 0, binding = 1) uniform sampler2D hdrTex;
layout(set = 0, binding = 2) uniform sampler2D depthTex;   // G-buffer depth, reversed Z: 0 where the ray escaped
layout(set = 0, binding = 3) uniform sampler2D albedoTex;  // G-buffer base colour, sRGB-encoded
layout(set = 0, binding = 4, std430) buffer Histogram { uint bins[]; };  // surfaces, then background

const vec3 kRec709 = vec3(0.2126, 0.7152, 0.0722);
const float kGrey = 0.18;
const float kMinAlbedo = 0.04;  // darker surfaces count as this: their few photons are mostly noise
layout(push_constant, scalar) uniform Push { ExposurePush pc; };

shared uint tile[kExposureHistograms * kExposureBins];

void main() {
  uint local = gl_LocalInvocationIndex;  // 256 invocations, 256 bins per histogram
  for (uint h = 0u; h < kExposureHistograms; ++h) tile[h * kExposureBins + local] = 0u;
  barrier();
  uvec2 id = gl_GlobalInvocationID.xy;
  if (all(lessThan(id, pc.size))) {
    vec3 c = texelFetch(hdrTex, ivec2(id), 0).rgb;
    float luminance = dot(max(c, vec3(0.0)), kRec709) * pc.invExposure;
    uint histogram = texelFetch(depthTex, ivec2(id), 0).r > 0.0 ? 0u : 1u;
    if (histogram == 0u) {
      float albedo = dot(srgbToLinear(texelFetch(albedoTex, ivec2(id), 0).rgb), kRec709);
      luminance *= kGrey / max(albedo, kMinAlbedo);
    }
    atomicAdd(tile[histogram * kExposureBins + exposureBin(luminance)], 1u);
  }
  barrier();
  for (uint h = 0u; h < kExposureHistograms; ++h) {
    uint n = tile[h * kExposureBins + local];
    if (n > 0u) atomicAdd(bins[h * kExposureBins + local], n);
  }
}
