#version 460
#include "lib/common.glsl"

// Running mean of shadow visibility over the frames of a static camera: history n holds the mean
// of n samples. Reads the previous history, writes the next (ping-pong, never in place), in fp32.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1, r16f) uniform readonly image2DArray rawVisibility;
layout(set = 0, binding = 2, r32f) uniform readonly image2DArray history;
layout(set = 0, binding = 3, r32f) uniform writeonly image2DArray outHistory;
layout(push_constant) uniform Push { uvec2 size; uint layers; uint samples; } pc;  // samples already in history

void main() {
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= pc.size.x || id.y >= pc.size.y || id.z >= pc.layers) return;
  ivec3 p = ivec3(id);
  float fresh = imageLoad(rawVisibility, p).r;
  float mean = pc.samples == 0u ? fresh : mix(imageLoad(history, p).r, fresh, 1.0 / float(pc.samples + 1u));
  imageStore(outHistory, p, vec4(mean));
}
