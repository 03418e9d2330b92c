// Shadow-map planning of the raster mode (render/shadow_setup.h): cascade splits, view counts per
// light kind, atlas tiles, and that every view sees what it should.
#include <gtest/gtest.h>

#include "render/shadow_setup.h"
#include "scene/loader.h"

namespace rayster::render {
namespace {

TEST(ShadowSetup, CascadeSplitsIncreaseToFar) {
  const std::vector<float> ends = cascadeSplits(0.1f, 100.0f, 4, kCascadeSplitLambda);
  ASSERT_EQ(ends.size(), 4u);
  for (size_t i = 1; i < ends.size(); ++i) EXPECT_GT(ends[i], ends[i - 1]);
  EXPECT_GT(ends[0], 0.1f);
  EXPECT_FLOAT_EQ(ends.back(), 100.0f);
  // Logarithmic-leaning: the first cascade is much shorter than a uniform quarter.
  EXPECT_LT(ends[0], 25.0f);
}

glm::vec3 project(const gpu::ShadowView& v, glm::vec3 p) {
  const glm::vec4 c = v.clipFromWorld * glm::vec4(p, 1.0f);
  return glm::vec3(c) / c.w;
}

TEST(ShadowSetup, PointLightGetsSixFacesAndSunFourCascades) {
  auto scene = scene::loadScene("builtin:whitted");
  ASSERT_TRUE(scene.ok());
  const scene::Camera& cam = scene->cameras.front();
  const ShadowAtlas atlas = planShadowAtlas(*scene, cam, 4.0f / 3.0f, gpu::kMaxShadowLights);
  uint32_t expected = 0;
  for (size_t i = 0; i < std::min<size_t>(scene->lights.size(), gpu::kMaxShadowLights); ++i) {
    const scene::Light& l = scene->lights[i];
    const gpu::ShadowLight& sl = atlas.setup.lights[i];
    EXPECT_EQ(sl.firstView, expected);
    if (l.type == scene::LightType::Directional) {
      EXPECT_EQ(sl.kind, gpu::kShadowCascaded);
      expected += gpu::kShadowCascades;
    } else if (l.type == scene::LightType::Point) {
      EXPECT_EQ(sl.kind, gpu::kShadowCube);
      // The point one unit along each axis lands in the middle of its face, in front of the light.
      const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
      for (int f = 0; f < 6; ++f) {
        const glm::vec3 ndc = project(atlas.setup.views[sl.firstView + f], l.position + axes[f]);
        EXPECT_NEAR(ndc.x, 0.0f, 1e-4f);
        EXPECT_NEAR(ndc.y, 0.0f, 1e-4f);
        EXPECT_GT(ndc.z, 0.0f);  // reversed Z: inside the frustum, off the far plane
        EXPECT_LT(ndc.z, 1.0f);
      }
      expected += 6;
    } else {
      expected += 1;
    }
  }
  EXPECT_EQ(atlas.setup.viewCount, expected);
  ASSERT_EQ(atlas.tiles.size(), expected);
  for (size_t i = 0; i < atlas.tiles.size(); ++i)
    for (size_t j = i + 1; j < atlas.tiles.size(); ++j)
      EXPECT_FALSE(atlas.tiles[i].x == atlas.tiles[j].x && atlas.tiles[i].y == atlas.tiles[j].y);
  EXPECT_LE(atlas.tiles.back().x + atlas.tileSize, atlas.columns * atlas.tileSize);
  EXPECT_LE(atlas.tiles.back().y + atlas.tileSize, atlas.rows * atlas.tileSize);
}

TEST(ShadowSetup, CascadesCoverTheCameraTarget) {
  auto scene = scene::loadScene("builtin:spheres");
  ASSERT_TRUE(scene.ok());
  const scene::Camera& cam = scene->cameras.front();
  const ShadowAtlas atlas = planShadowAtlas(*scene, cam, 4.0f / 3.0f, gpu::kMaxShadowLights);
  for (size_t i = 0; i < scene->lights.size() && i < gpu::kMaxShadowLights; ++i) {
    if (atlas.setup.lights[i].kind != gpu::kShadowCascaded) continue;
    // Every scene-bounds point is inside the depth range of every cascade (casters outside the
    // slice still cast), and the camera target is inside some cascade's square.
    const scene::Aabb b = scene->bounds();
    bool targetCovered = false;
    for (uint32_t c = 0; c < gpu::kShadowCascades; ++c) {
      const gpu::ShadowView& v = atlas.setup.views[atlas.setup.lights[i].firstView + c];
      for (int k = 0; k < 8; ++k) {
        const glm::vec3 corner{k & 1 ? b.max.x : b.min.x, k & 2 ? b.max.y : b.min.y, k & 4 ? b.max.z : b.min.z};
        const float z = project(v, corner).z;
        EXPECT_GE(z, 0.0f);
        EXPECT_LE(z, 1.0f);
      }
      const glm::vec3 t = project(v, cam.target);
      targetCovered |= std::abs(t.x) <= 1.0f && std::abs(t.y) <= 1.0f;
    }
    EXPECT_TRUE(targetCovered);
    return;
  }
  GTEST_SKIP() << "builtin:spheres has no sun";
}

}  // namespace
}  // namespace rayster::render
