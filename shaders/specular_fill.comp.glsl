#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/specular_weight.glsl"

// The half-rate glossy checkerboard's other half (lib/specular_weight.glsl, docs/techniques.md §13):
// every pixel specular.rgen left for this pass (alpha kHalfRateSkipped) becomes the mean of its
// 4-neighbours on a half-rate glossy surface, all of which traced this frame (it was their turn:
// specular.rgen skips a pixel only when it has one). In place: skipped pixels read only traced ones.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1, rgba16f) uniform image2D specular;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D materialTex;

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(specular);
  if (any(greaterThanEqual(px, size))) return;
  if (imageLoad(specular, px).a != kHalfRateSkipped) return;
  const ivec2 kNeighbours[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
  vec3 sum = vec3(0.0);
  float count = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 q = px + kNeighbours[k];
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    if (!halfRateGlossy(texelFetch(depthTex, q, 0).r, texelFetch(materialTex, q, 0))) continue;
    sum += imageLoad(specular, q).rgb;
    count += 1.0;
  }
  imageStore(specular, px, vec4(count > 0.0 ? sum / count : vec3(0.0), 1.0));
}
