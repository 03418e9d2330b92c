#version 460
#include "lib/common.glsl"
#include "lib/denoise.glsl"

// The denoisers' view of the G-buffer, one RGBA32UI texel per pixel (lib/denoise.glsl): linear
// depth and its slope, the shading normal, the id. Kept a frame longer as a history, so every
// temporal pass tests disocclusion against the previous frame's surface.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D depthTex;  // D32 or R32F, reversed Z
layout(set = 0, binding = 1) uniform sampler2D normalTex;  // oct shading normal in .xy
layout(set = 0, binding = 2) uniform usampler2D idTex;
layout(set = 0, binding = 3, rgba32ui) uniform writeonly uimage2D outSurface;
layout(push_constant, scalar) uniform Push { SurfacePush pc; };

// Reversed-Z depth d of a [0,1] perspective with swapped planes: z = n·f / (n + d·(f − n)).
float linearDepth(ivec2 p) {
  float d = texelFetch(depthTex, p, 0).r;
  return pc.zNear * pc.zFar / (pc.zNear + d * (pc.zFar - pc.zNear));
}

bool onSurface(ivec2 p) {
  return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, ivec2(pc.size))) &&
         texelFetch(idTex, p, 0).r != kBackgroundId;
}

// One-sided differences along one axis; the smaller one, so a silhouette beside the pixel does not
// pass for a steep slope. 0 when neither neighbour is geometry.
float slope(ivec2 p, ivec2 axis, float z) {
  float g = 1.0e30;
  if (onSurface(p + axis)) g = min(g, abs(linearDepth(p + axis) - z));
  if (onSurface(p - axis)) g = min(g, abs(linearDepth(p - axis) - z));
  return g < 1.0e30 ? g : 0.0;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), pc.size))) return;
  uint id = texelFetch(idTex, p, 0).r;
  if (id == kBackgroundId) {
    imageStore(outSurface, p, uvec4(0u, 0u, packSnorm2x16(vec2(0.0)), kBackgroundId));
    return;
  }
  float z = linearDepth(p);
  float zGrad = slope(p, ivec2(1, 0), z) + slope(p, ivec2(0, 1), z);
  vec2 oct = texelFetch(normalTex, p, 0).xy;
  imageStore(outSurface, p, uvec4(floatBitsToUint(z), floatBitsToUint(zGrad), packSnorm2x16(oct), id));
}
