// TAA jitter (docs/techniques.md §18): Halton(2,3), period 16, within ±0.5 px, applied as an NDC shift.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "render/jitter.h"

namespace rayster::render {
namespace {

TEST(TaaJitter, HaltonSequence) {
  EXPECT_FLOAT_EQ(halton(1, 2), 0.5f);
  EXPECT_FLOAT_EQ(halton(2, 2), 0.25f);
  EXPECT_FLOAT_EQ(halton(3, 2), 0.75f);
  EXPECT_FLOAT_EQ(halton(1, 3), 1.0f / 3.0f);
  EXPECT_FLOAT_EQ(halton(5, 3), 2.0f / 3.0f + 1.0f / 9.0f);
}

TEST(TaaJitter, HalfPixelRangePeriodAndDistinctPositions) {
  for (uint32_t f = 0; f < kJitterPeriod; ++f) {
    const glm::vec2 px = jitterPixels(f);
    EXPECT_GE(px.x, -0.5f);
    EXPECT_LT(px.x, 0.5f);
    EXPECT_GE(px.y, -0.5f);
    EXPECT_LT(px.y, 0.5f);
    EXPECT_EQ(jitterPixels(f + kJitterPeriod), px) << "period " << kJitterPeriod;
    for (uint32_t g = 0; g < f; ++g) EXPECT_NE(jitterPixels(g), px);
  }
  // (2h − 1)/width in NDC is (h − 0.5) pixels, since one pixel spans 2/width.
  const glm::vec2 ndc = jitterNdc(3, 160, 120), px = jitterPixels(3);
  EXPECT_FLOAT_EQ(ndc.x * 160.0f / 2.0f, px.x);
  EXPECT_FLOAT_EQ(ndc.y * 120.0f / 2.0f, px.y);
}

TEST(TaaJitter, ShiftsNdcByTheOffsetAtEveryDepth) {
  glm::mat4 proj = glm::perspective(0.8f, 4.0f / 3.0f, 30.0f, 0.1f);
  proj[1][1] *= -1.0f;
  const glm::mat4 clip = proj * glm::lookAt(glm::vec3(0, 1, 5), glm::vec3(0), glm::vec3(0, 1, 0));
  const glm::vec2 j = jitterNdc(5, 160, 120);
  const glm::mat4 jittered = jitteredClipFromWorld(clip, j);
  for (glm::vec3 p : {glm::vec3(0.3f, 0.2f, 0.0f), glm::vec3(-2.0f, 1.0f, -10.0f)}) {
    const glm::vec4 a = clip * glm::vec4(p, 1.0f), b = jittered * glm::vec4(p, 1.0f);
    EXPECT_NEAR(b.x / b.w - a.x / a.w, j.x, 1e-6f);
    EXPECT_NEAR(b.y / b.w - a.y / a.w, j.y, 1e-6f);
    EXPECT_FLOAT_EQ(b.z / b.w, a.z / a.w) << "depth is not jittered";
  }
}

}  // namespace
}  // namespace rayster::render
