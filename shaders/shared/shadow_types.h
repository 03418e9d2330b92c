// Shadow maps of the raster mode (render/shadow_setup.h), shared by C++ and GLSL (docs/style.md §5).
// Every shadow view (a sun cascade, a spot light's frustum, a cube face of a point light) is one
// square tile of a single D32 atlas; depth is reversed (near 1, far 0) like the camera's.
#ifndef RAYSTER_SHARED_SHADOW_TYPES_H
#define RAYSTER_SHARED_SHADOW_TYPES_H

#ifdef __cplusplus
#include "shaders/shared/types.h"
namespace rayster::gpu {
#endif

RAYSTER_CONST uint kShadowCascades = 4u;
RAYSTER_CONST uint kMaxShadowViews = 6u * kMaxShadowLights;  // every light a cube
RAYSTER_CONST uint kShadowNone = 0u;                         // no shadow map: visibility 1
RAYSTER_CONST uint kShadowCascaded = 1u;                     // directional: kShadowCascades orthographic views
RAYSTER_CONST uint kShadowSpot = 2u;                         // one perspective view
RAYSTER_CONST uint kShadowCube = 3u;                         // six 90° perspective views (+X, -X, +Y, -Y, +Z, -Z)

struct ShadowView {
  mat4 clipFromWorld;  // the light's clip space, reversed Z
  vec4 tile;           // atlas uv of the tile: offset xy, scale zw
  float nearPlane;     // perspective: planes of the depth linearisation; orthographic: depth range
  float farPlane;
  float texelWorld;  // a texel's world size: orthographic absolute, perspective at unit distance
  uint perspective;  // 1: perspective, 0: orthographic
};

struct ShadowLight {
  uint kind;  // kShadow*
  uint firstView;
  uint pad0;
  uint pad1;
};

struct ShadowSetup {
  ShadowView views[kMaxShadowViews];
  ShadowLight lights[kMaxShadowLights];
  vec4 cascadeEnds;    // view depth (along the camera's forward axis) where each cascade ends
  vec4 cameraForward;  // xyz: unit forward axis of the camera
  vec2 atlasTexel;     // 1 / atlas size in texels
  float pcfRadius;     // filter radius in texels (soft edges)
  uint viewCount;
};

#ifdef __cplusplus
static_assert(sizeof(ShadowView) == 96);
static_assert(sizeof(ShadowLight) == 16);
static_assert(offsetof(ShadowSetup, lights) == 96 * kMaxShadowViews);
static_assert(sizeof(ShadowSetup) == 96 * kMaxShadowViews + 16 * kMaxShadowLights + 48);
}  // namespace rayster::gpu
#endif

#endif
