#version 460
#include "lib/common.glsl"
#include "lib/denoise.glsl"

// The denoisers' view of the G-buffer, one RG32UI texel per pixel (lib/denoise.glsl): linear depth,
// the shading normal, the id, and the sharp flag (roughness ≤ kSharpRoughness) in the depth's sign
// bit; the depth slope is recomputed by its readers. Kept a frame longer
// as a history, so every temporal pass tests disocclusion against the previous frame's surface.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D depthTex;  // D32 or R32F, reversed Z
layout(set = 0, binding = 1) uniform sampler2D normalTex;  // oct shading normal in .xy
layout(set = 0, binding = 2) uniform usampler2D idTex;
layout(set = 0, binding = 3, rg32ui) uniform writeonly uimage2D outSurface;
layout(set = 0, binding = 4) uniform sampler2D materialTex;  // .r perceptual roughness
layout(push_constant, scalar) uniform Push { SurfacePush pc; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), pc.size))) return;
  uint id = texelFetch(idTex, p, 0).r;
  if (id == kBackgroundId) {
    imageStore(outSurface, p, uvec4(0u));
    return;
  }
  // Reversed-Z depth d of a [0,1] perspective with swapped planes: z = n·f / (n + d·(f − n)).
  float d = texelFetch(depthTex, p, 0).r;
  float z = pc.zNear * pc.zFar / (pc.zNear + d * (pc.zFar - pc.zNear));
  bool sharp = texelFetch(materialTex, p, 0).r <= kSharpRoughness;
  imageStore(outSurface, p, uvec4(encodeSurface(z, texelFetch(normalTex, p, 0).xy, id, sharp), 0u, 0u));
}
