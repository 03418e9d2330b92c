// Shader binding table layout from device properties (no GPU): lavapipe and NVIDIA report different
// handle and base alignments, and a layout valid for one may be invalid for the other.
#include <cstdint>
#include <ostream>

#include <gtest/gtest.h>

#include "rhi/rt_pipeline.h"

namespace rayster::rhi {
namespace {

struct Props {
  const char* name;
  uint32_t handleSize, handleAlignment, baseAlignment;
};

void PrintTo(const Props& p, std::ostream* os) {
  *os << p.name << " (handle " << p.handleSize << ", align " << p.handleAlignment << ", base " << p.baseAlignment
      << ")";
}

class SbtLayoutTest : public ::testing::TestWithParam<Props> {};

// Checks every rule vkCmdTraceRaysKHR imposes on the regions built from this layout (see
// RayTracingPipeline::trace: raygen is passed with stride = size = raygenSize; miss and hit with
// stride = `stride`).
void checkLayout(const Props& p, uint32_t missCount, uint32_t hitCount) {
  SCOPED_TRACE(::testing::Message() << p.name << " miss " << missCount << " hit " << hitCount);
  const SbtLayout l = computeSbtLayout(p.handleSize, p.handleAlignment, p.baseAlignment, missCount, hitCount);

  EXPECT_EQ(l.handleSize, p.handleSize);
  // stride: handleSize rounded up to the handle alignment, i.e. the smallest such multiple.
  EXPECT_EQ(l.stride % p.handleAlignment, 0u);
  EXPECT_GE(l.stride, p.handleSize);
  EXPECT_LT(l.stride, p.handleSize + p.handleAlignment);

  // Every region starts at a multiple of shaderGroupBaseAlignment (the buffer base is aligned too).
  EXPECT_EQ(l.raygenOffset % p.baseAlignment, 0u);
  EXPECT_EQ(l.missOffset % p.baseAlignment, 0u);
  EXPECT_EQ(l.hitOffset % p.baseAlignment, 0u);

  // Raygen is a single record whose size equals its stride (VUID-vkCmdTraceRaysKHR-size-04023):
  // raygenSize is used as both, so it must be a valid record stride holding one handle.
  EXPECT_GE(l.raygenSize, p.handleSize);
  EXPECT_GE(l.raygenSize, l.stride);
  EXPECT_EQ(l.raygenSize % p.handleAlignment, 0u);
  EXPECT_LE(l.raygenSize, 4096u) << "beyond the smallest maxShaderGroupStride devices report";

  // Regions hold their records and do not overlap.
  EXPECT_GE(l.missSize, missCount * l.stride);
  EXPECT_GE(l.hitSize, hitCount * l.stride);
  if (missCount == 0) {
    EXPECT_EQ(l.missSize, 0u) << "an empty miss region must be omitted";
  }
  if (hitCount == 0) {
    EXPECT_EQ(l.hitSize, 0u) << "an empty hit region must be omitted";
  }
  EXPECT_GE(l.missOffset, l.raygenOffset + l.raygenSize);
  EXPECT_GE(l.hitOffset, l.missOffset + l.missSize);
  EXPECT_GE(l.totalSize, l.hitOffset + l.hitSize);
  // No waste beyond alignment padding.
  EXPECT_LT(l.missSize, missCount * l.stride + p.baseAlignment);
  EXPECT_LT(l.hitSize, hitCount * l.stride + p.baseAlignment);
  EXPECT_LT(l.totalSize, l.stride * (1 + missCount + hitCount) + 3 * p.baseAlignment);

  // The last record written (RayTracingPipeline puts records at offset + i * stride) stays inside.
  if (missCount) {
    EXPECT_LE(l.missOffset + (missCount - 1) * l.stride + l.handleSize, l.hitOffset);
  }
  if (hitCount) {
    EXPECT_LE(l.hitOffset + (hitCount - 1) * l.stride + l.handleSize, l.totalSize);
  }
}

TEST_P(SbtLayoutTest, RegionsAreAlignedSizedAndDisjoint) {
  for (uint32_t miss : {0u, 1u, 2u, 3u, 7u})
    for (uint32_t hit : {0u, 1u, 2u, 5u}) checkLayout(GetParam(), miss, hit);
}

INSTANTIATE_TEST_SUITE_P(Devices, SbtLayoutTest,
                         ::testing::Values(Props{"lavapipe", 32, 32, 32}, Props{"nvidia", 32, 32, 64},
                                           Props{"wide", 48, 64, 128}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(SbtLayout, LavapipeExact) {
  const SbtLayout l = computeSbtLayout(32, 32, 32, 2, 3);
  EXPECT_EQ(l.stride, 32u);
  EXPECT_EQ(l.raygenOffset, 0u);
  EXPECT_EQ(l.raygenSize, 32u);
  EXPECT_EQ(l.missOffset, 32u);
  EXPECT_EQ(l.missSize, 64u);
  EXPECT_EQ(l.hitOffset, 96u);
  EXPECT_EQ(l.hitSize, 96u);
  EXPECT_EQ(l.totalSize, 192u);
}

TEST(SbtLayout, NvidiaBaseAlignmentPadsRegions) {
  const SbtLayout l = computeSbtLayout(32, 32, 64, 1, 3);
  EXPECT_EQ(l.stride, 32u);  // records within a region stay tightly packed
  EXPECT_EQ(l.raygenSize, 64u);
  EXPECT_EQ(l.missOffset, 64u);
  EXPECT_EQ(l.missSize, 64u);
  EXPECT_EQ(l.hitOffset, 128u);
  EXPECT_EQ(l.hitSize, 128u);
  EXPECT_EQ(l.totalSize, 256u);
}

TEST(SbtLayout, HandleSmallerThanAlignment) {
  const SbtLayout l = computeSbtLayout(48, 64, 128, 2, 1);
  EXPECT_EQ(l.stride, 64u);
  EXPECT_EQ(l.raygenSize, 128u);
  EXPECT_EQ(l.missOffset, 128u);
  EXPECT_EQ(l.missSize, 128u);
  EXPECT_EQ(l.hitOffset, 256u);
  EXPECT_EQ(l.hitSize, 128u);
  EXPECT_EQ(l.totalSize, 384u);
}

}  // namespace
}  // namespace rayster::rhi
