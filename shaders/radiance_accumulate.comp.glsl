#version 460
#include "lib/common.glsl"

// Running mean of a radiance image over the frames of a static camera, in fp32 (history n holds
// the mean of n samples). Reads the previous history, writes the next: never in place.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D raw;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D history;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D outHistory;
layout(push_constant) uniform Push { uvec2 size; uint samples; uint pad; } pc;

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(id, pc.size))) return;
  vec4 fresh = imageLoad(raw, ivec2(id));
  vec4 mean = pc.samples == 0u ? fresh : mix(imageLoad(history, ivec2(id)), fresh, 1.0 / float(pc.samples + 1u));
  imageStore(outHistory, ivec2(id), mean);
}
