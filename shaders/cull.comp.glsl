#version 460
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lib/hiz.glsl"

// GPU culling (TECHNIQUES.md §20): one invocation per draw. A draw whose object-space box lies
// wholly outside one clip plane is dropped, and so is one wholly behind the depth pyramid when the
// pyramid holds this very view; the rest are appended to their list (triangles or spheres) as a
// VkDrawIndirectCommand plus the DrawRecord row gl_DrawID finds them by.
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

// Occlusion against the previous frame's depth pyramid, used only when that frame saw the same
// view (equal unjittered clipFromWorld and size; the host also requires a static scene without
// stochastic coverage): then its depth is this frame's up to the sub-pixel jitter, which the
// one-pixel margin covers, and the test is exact — no popping. A moving camera culls by frustum
// only (the two-phase scheme of §20 would lift that).
bool occluded(mat4 clipFromObject, vec3 lo, vec3 hi) {
  Hiz hiz = Hiz(pc.hiz);
  if (hiz.h.valid == 0u || hiz.h.size != frame.size || hiz.h.clipFromWorld != frame.unjitteredClipFromWorld)
    return false;
  vec2 ndcMin = vec2(1e30), ndcMax = vec2(-1e30);
  float nearest = 0.0;  // reversed Z: the box's largest depth
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
  // The finest level where the rectangle spans at most 2 × 2 texels; read all four.
  uint level = 0u;
  while (level + 1u < hiz.h.levels && any(greaterThan((p1 >> level) - (p0 >> level), ivec2(1)))) ++level;
  uvec2 size = hizLevelSize(frame.size, level);
  uint offset = hizLevelOffset(frame.size, level);
  uvec2 t0 = uvec2(p0 >> level), t1 = uvec2(p1 >> level);
  float farthest = min(min(hiz.d[offset + t0.y * size.x + t0.x], hiz.d[offset + t0.y * size.x + t1.x]),
                       min(hiz.d[offset + t1.y * size.x + t0.x], hiz.d[offset + t1.y * size.x + t1.x]));
  return nearest < farthest;
}

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (id >= pc.drawCount) return;
  DrawRecord d = DrawRecords(pc.records).d[id];
  if (pc.flags != 0u) {
    InstanceRecord inst = Instances(frame.instances).i[d.instance];
    mat4 clipFromObject = frame.clipFromWorld * inst.worldFromObject;
    if ((pc.flags & kCullFrustum) != 0u && outsideFrustum(clipFromObject, d.aabbMin, d.aabbMax)) return;
    if ((pc.flags & kCullOcclusion) != 0u && occluded(clipFromObject, d.aabbMin, d.aabbMax)) return;
  }
  bool spheres = (d.flags & kDrawSpheres) != 0u;
  uint list = spheres ? 1u : 0u;
  uint slot = atomicAdd(DrawCounts(pc.counts).n[list], 1u);
  // Sphere sets draw one 36-vertex box per sphere (instances); triangles their index count.
  DrawCommand command = DrawCommand(d.count, 1u, 0u, 0u);
  if (spheres) command = DrawCommand(36u, d.count, 0u, 0u);
  DrawCommands(pc.commands).c[list * pc.drawCount + slot] = command;
  DrawIds(pc.drawIds).i[list * pc.drawCount + slot] = id;
}
