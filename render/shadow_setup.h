#pragma once
// Where the raster mode's shadow maps look from (CPU side): sun cascades fitted to splits of the
// camera frustum, one frustum per spot light, six cube faces per point or sphere light, each a
// tile of one depth atlas (shaders/shared/shadow_types.h).
#include <cstdint>
#include <vector>

#include "scene/scene.h"
#include "shaders/shared/shadow_types.h"

namespace rayster::render {

// Tunables of the shadow maps, each with its reason.
inline constexpr uint32_t kShadowTileSize = 512;     // texels per tile side: sharp at test sizes, cheap on lavapipe
inline constexpr uint32_t kShadowAtlasColumns = 8;   // tiles per atlas row
inline constexpr float kCascadeSplitLambda = 0.75f;  // practical split scheme: 0 uniform, 1 logarithmic
inline constexpr float kShadowPcfRadius = 1.5f;      // PCF radius in texels: a soft edge a few texels wide

struct ShadowAtlas {
  gpu::ShadowSetup setup{};
  uint32_t tileSize = kShadowTileSize;
  uint32_t columns = 1, rows = 1;  // atlas = columns × rows tiles (at least one, even when unused)
  // Atlas viewport of each view, in texels.
  struct Tile {
    uint32_t x, y;
  };
  std::vector<Tile> tiles;
  // Per view, where its rays come from: xyz the light's position (w = 1, perspective) or the
  // direction light travels (w = 0, orthographic); sphere impostors intersect along them.
  std::vector<glm::vec4> lightRays;
};

// Lays out the shadow views of the first `shadowLights` lights for this camera.
// `bounds`: the scene's world bounds (GpuScene::bounds; the overload without computes them).
ShadowAtlas planShadowAtlas(const scene::Scene& scene, scene::Aabb bounds, const scene::Camera& camera, float aspect,
                            uint32_t shadowLights);
inline ShadowAtlas planShadowAtlas(const scene::Scene& scene, const scene::Camera& camera, float aspect,
                                   uint32_t shadowLights) {
  return planShadowAtlas(scene, scene.bounds(), camera, aspect, shadowLights);
}

// View-space distances where the cascades end (practical split scheme between near and far).
std::vector<float> cascadeSplits(float nearPlane, float farPlane, uint32_t count, float lambda);

}  // namespace rayster::render
