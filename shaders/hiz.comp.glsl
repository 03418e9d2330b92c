#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/hiz.glsl"

// One level of the depth pyramid: level 0 copies the G-buffer depth of the early phase (this
// frame's view and jitter), level k takes the MIN of the 2 × 2 texels of level k − 1 it covers
// (reversed Z: the farthest depth, so a tile's value is never nearer than any pixel under it).
// Never bilinear (docs/techniques.md §23).
layout(local_size_x = kHizGroupSize, local_size_y = kHizGroupSize) in;
layout(push_constant, scalar) uniform Push { HizPush pc; };
layout(set = 0, binding = 1) uniform sampler2D depthImage;

void main() {
  Hiz hiz = Hiz(pc.hiz);
  uvec2 size = frame.size;
  uvec2 s = hizLevelSize(size, pc.level);
  uvec2 p = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(p, s))) return;
  float depth;
  if (pc.level == 0u) {
    depth = texelFetch(depthImage, ivec2(p), 0).r;
  } else {
    uvec2 ps = hizLevelSize(size, pc.level - 1u);
    uint from = hizLevelOffset(size, pc.level - 1u);
    uvec2 q0 = 2u * p, q1 = min(q0 + 1u, ps - 1u);
    depth = min(min(hiz.d[from + q0.y * ps.x + q0.x], hiz.d[from + q0.y * ps.x + q1.x]),
                min(hiz.d[from + q1.y * ps.x + q0.x], hiz.d[from + q1.y * ps.x + q1.x]));
  }
  hiz.d[hizLevelOffset(size, pc.level) + p.y * s.x + p.x] = depth;
}
