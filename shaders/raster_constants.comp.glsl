#version 460
#include "lib/common.glsl"

// The raster mode's stand-ins for effects it does not compute: AO 1 (unoccluded) and a zero
// radiance image (no specular light yet, no indirect light).
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, r16f) uniform writeonly image2DArray outAo;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D outZero;
layout(push_constant, scalar) uniform Push { SizePush pc; };

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), pc.size))) return;
  imageStore(outAo, ivec3(px, 0), vec4(1.0));
  imageStore(outZero, px, vec4(0.0));
}
