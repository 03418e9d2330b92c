// Push-constant blocks shared by C++ and GLSL (docs/style.md §5): a shader declares
//   layout(push_constant, scalar) uniform Push { TaaPush pc; };
// and its pass pushes the same struct (graph::PassContext::push), whose size is checked against the
// block the SPIR-V declares (rhi/spirv_reflect.h). No literal sizes anywhere. The denoisers' blocks
// live in shared/denoise.h, culling's in shared/types.h (CullPush, HizPush).
#ifndef RAYSTER_SHARED_PUSH_H
#define RAYSTER_SHARED_PUSH_H

#include "types.h"  // relative: C++ includes shaders/shared/, GLSL shared/

#ifdef __cplusplus
namespace rayster::gpu {
#endif

// gbuffer.vert, gbuffer_sphere.vert: this list's draws (render/passes/cull.h).
struct GBufferDrawPush {
  uint64_t records;  // DrawRecord[]
  uint64_t drawIds;  // uint[]: the DrawRecord row of each indirect command of the list
};

// shadow_map.vert: one draw into one light view's tile.
struct ShadowMapPush {
  mat4 clipFromWorld;
  uint instance;
  uint geometry;
};
// shadow_sphere.vert / .frag: the same, and the light's ray for the exact sphere depth.
struct ShadowSpherePush {
  mat4 clipFromWorld;
  uint instance;
  uint geometry;
  vec4 light;  // xyz: position (w = 1, perspective) or travel direction (w = 0, orthographic)
};

// taa.comp
struct TaaPush {
  uvec2 size;
  uint flags;           // kTaaHistoryValid | kTaaMotion (render/passes/taa.cpp)
  float currentWeight;  // of the current frame, before the anti-firefly weights
};

// tonemap.comp
struct TonemapPush {
  uvec2 size;
  uint seed;     // of the ±0.5 LSB dither
  uint op;       // Tonemapper
  float dither;  // 1 on, 0 off
};

// raster_constants.comp
struct SizePush {
  uvec2 size;
};

#ifdef __cplusplus
static_assert(sizeof(GBufferDrawPush) == 16);
static_assert(sizeof(ShadowMapPush) == 72);
static_assert(sizeof(ShadowSpherePush) == 88);
static_assert(sizeof(TaaPush) == 16);
static_assert(sizeof(TonemapPush) == 20);
static_assert(sizeof(SizePush) == 8);
}  // namespace rayster::gpu
#endif

#endif
