#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/hiz.glsl"

// Two-phase GPU culling (docs/techniques.md §23, render/passes/cull.h): one invocation per draw, run
// twice a frame. A draw whose object-space box lies wholly outside one clip plane is dropped (and
// marked invisible). The early phase appends the rest that were visible last frame; the late phase
// tests every frustum-visible draw against the pyramid of the early phase's depth, records the
// result as next frame's visibility, and appends those visible now that the early phase skipped.
// Each appended draw becomes a VkDrawIndirectCommand plus the DrawRecord row gl_DrawID finds it by.
layout(local_size_x = kCullGroupSize) in;
layout(push_constant, scalar) uniform Push { CullPush pc; };

struct DrawCommand {
  uint vertexCount;
  uint instanceCount;
  uint firstVertex;
  uint firstInstance;
};
layout(buffer_reference, scalar) readonly buffer DrawRecords { DrawRecord d[]; };
layout(buffer_reference, scalar) writeonly buffer DrawCommands { DrawCommand c[]; };
layout(buffer_reference, scalar) writeonly buffer DrawIds { uint i[]; };
layout(buffer_reference, scalar) buffer DrawCounts { uint n[]; };
layout(buffer_reference, scalar) buffer DrawVisibility { uint v[]; };

// The 8 corners against the planes of the clip volume, in homogeneous form (-w <= x, y <= w,
// 0 <= z <= w with reversed Z: near at depth 1), which stays exact for corners behind the eye. The
// jittered clipFromWorld is the one rasterised, so the test is exact for this frame's pixels.
bool outsideFrustum(mat4 clipFromObject, vec3 lo, vec3 hi) {
  uint allOutside = 0x3Fu;
  for (uint k = 0u; k < 8u; ++k) {
    vec3 p = vec3((k & 1u) != 0u ? hi.x : lo.x, (k & 2u) != 0u ? hi.y : lo.y, (k & 4u) != 0u ? hi.z : lo.z);
    vec4 c = clipFromObject * vec4(p, 1.0);
    uint out6 = (c.x < -c.w ? 1u : 0u) | (c.x > c.w ? 2u : 0u) | (c.y < -c.w ? 4u : 0u) |
                (c.y > c.w ? 8u : 0u) | (c.z < 0.0 ? 16u : 0u) | (c.z > c.w ? 32u : 0u);
    allOutside &= out6;
  }
  return allOutside != 0u;
}

// Occlusion against this frame's pyramid of the early phase's depth. That depth was rasterised
// with this frame's jittered clipFromWorld, the matrix the box is projected with here, so no jitter
// margin is needed; and it is a subset of the frame's final depth, so a box behind it stays hidden:
// no popping. The box's screen rectangle (grown by a pixel for rounding) is looked up at the finest
// level where it spans at most 4 × 4 texels, all of them read (at 2 × 2 the texels reach up to twice
// as far past the rectangle, and a box beside a small window in an occluder stays visible); the box
// is hidden when its nearest depth (reversed Z: the largest) lies behind the farthest depth there.
bool occluded(mat4 clipFromObject, vec3 lo, vec3 hi) {
  Hiz hiz = Hiz(pc.hiz);
  vec2 ndcMin = vec2(1e30), ndcMax = vec2(-1e30);
  float nearest = 0.0;
  for (uint k = 0u; k < 8u; ++k) {
    vec3 p = vec3((k & 1u) != 0u ? hi.x : lo.x, (k & 2u) != 0u ? hi.y : lo.y, (k & 4u) != 0u ? hi.z : lo.z);
    vec4 c = clipFromObject * vec4(p, 1.0);
    if (c.w <= 1e-6) return false;  // reaches the eye plane: no screen rectangle
    vec3 ndc = c.xyz / c.w;
    ndcMin = min(ndcMin, ndc.xy);
    ndcMax = max(ndcMax, ndc.xy);
    nearest = max(nearest, ndc.z);
  }
  if (nearest >= 1.0) return false;
  ivec2 last = ivec2(frame.size) - 1;
  ivec2 p0 = clamp(ivec2(floor((ndcMin * 0.5 + 0.5) * vec2(frame.size))) - 1, ivec2(0), last);
  ivec2 p1 = clamp(ivec2(floor((ndcMax * 0.5 + 0.5) * vec2(frame.size))) + 1, ivec2(0), last);
  uint levels = hizLevels(frame.size);
  uint level = 0u;
  while (level + 1u < levels && any(greaterThan((p1 >> level) - (p0 >> level), ivec2(int(kHizFootprint) - 1)))) ++level;
  uvec2 size = hizLevelSize(frame.size, level);
  uint offset = hizLevelOffset(frame.size, level);
  uvec2 t0 = uvec2(p0 >> level), t1 = uvec2(p1 >> level);
  float farthest = 1.0;
  for (uint y = t0.y; y <= t1.y; ++y)
    for (uint x = t0.x; x <= t1.x; ++x) farthest = min(farthest, hiz.d[offset + y * size.x + x]);
  return nearest < farthest;
}

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (id >= pc.drawCount) return;
  DrawRecord d = DrawRecords(pc.records).d[id];
  bool late = (pc.flags & kCullLate) != 0u;
  if ((pc.flags & kCullFrustum) != 0u) {
    DrawVisibility visibility = DrawVisibility(pc.visibility);
    InstanceRecord inst = Instances(frame.instances).i[d.instance];
    mat4 clipFromObject = frame.clipFromWorld * inst.worldFromObject;
    if (outsideFrustum(clipFromObject, d.aabbMin, d.aabbMax)) {
      if (!late) visibility.v[id] = 0u;
      return;
    }
    bool drawnEarly = visibility.v[id] != 0u;  // the early phase leaves frustum-visible rows alone
    if (late) {
      bool visible = !occluded(clipFromObject, d.aabbMin, d.aabbMax);
      visibility.v[id] = visible ? 1u : 0u;
      if (!visible || drawnEarly) return;
    } else if (!drawnEarly) {
      return;  // left to the late phase
    }
  }
  bool spheres = (d.flags & kDrawSpheres) != 0u;
  uint list = (late ? 2u : 0u) + (spheres ? 1u : 0u);
  uint slot = atomicAdd(DrawCounts(pc.counts).n[list], 1u);
  // Sphere sets draw one 36-vertex box per sphere (instances); triangles their index count.
  DrawCommand command = DrawCommand(d.count, 1u, 0u, 0u);
  if (spheres) command = DrawCommand(36u, d.count, 0u, 0u);
  DrawCommands(pc.commands).c[list * pc.drawCount + slot] = command;
  DrawIds(pc.drawIds).i[list * pc.drawCount + slot] = id;
}
