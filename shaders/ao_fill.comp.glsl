#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"

// Half-rate AO's other half (--ao-rate half, lib/ao_ray.glsl, docs/techniques.md §15): every pixel off
// this frame's checkerboard turn gets the mean of its 4-neighbours' visibility, all of which rt-ao
// traced this frame, counting those on the pixel's own surface (near its tangent plane): across a
// depth edge the background's or another object's openness would leak in. With none on its surface
// it takes the mean of all of them; the background (and AO off) stays 1. The temporal denoiser then
// sees each pixel traced every other frame and filled in between. In place, in layer
// frame.aoLayer: filled pixels read only traced ones.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 1, r16f) uniform image2DArray ao;
layout(set = 0, binding = 2) uniform sampler2D depthTex;
layout(set = 0, binding = 3) uniform sampler2D normalTex;

bool aoTurn(ivec2 px) { return ((px.x + px.y + int(frame.frameIndex)) & 1) == 0; }

vec3 positionAt(ivec2 px, float depth) {
  return worldFromDepth(frame.worldFromClip, (vec2(px) + 0.5) / vec2(frame.size), depth);
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), frame.size)) || aoTurn(px)) return;
  const int layer = int(frame.aoLayer);
  float depth = texelFetch(depthTex, px, 0).r;
  if (isBackground(depth) || (frame.effectFlags & kEffectAo) == 0u) {
    imageStore(ao, ivec3(px, layer), vec4(1.0));
    return;
  }
  vec3 p = positionAt(px, depth);
  vec3 n = octDecode(texelFetch(normalTex, px, 0).zw);  // the geometric normal: the surface's plane
  // Off the plane by more than this share of the distance to the camera: another surface.
  float tolerance = 0.02 * distance(p, frame.cameraPosition.xyz);
  const ivec2 kNeighbours[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
  float near = 0.0, nearCount = 0.0, all = 0.0, allCount = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 q = px + kNeighbours[k];
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), frame.size))) continue;
    float dq = texelFetch(depthTex, q, 0).r;
    if (isBackground(dq)) continue;
    float v = imageLoad(ao, ivec3(q, layer)).r;
    all += v;
    allCount += 1.0;
    if (abs(dot(n, positionAt(q, dq) - p)) <= tolerance) {
      near += v;
      nearCount += 1.0;
    }
  }
  float value = nearCount > 0.0 ? near / nearCount : allCount > 0.0 ? all / allCount : 1.0;
  imageStore(ao, ivec3(px, layer), vec4(value));
}
