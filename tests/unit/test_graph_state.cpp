#include <optional>
#include <ostream>

#include <gtest/gtest.h>

#include "graph/resource_state.h"

namespace rayster::graph {

bool operator==(const Barrier& a, const Barrier& b) {
  return a.srcStages == b.srcStages && a.dstStages == b.dstStages && a.srcAccess == b.srcAccess &&
         a.dstAccess == b.dstAccess && a.oldLayout == b.oldLayout && a.newLayout == b.newLayout;
}

void PrintTo(const Barrier& b, std::ostream* os) {
  *os << std::hex << "{src 0x" << b.srcStages << "/0x" << b.srcAccess << " -> dst 0x" << b.dstStages << "/0x"
      << b.dstAccess << std::dec << ", layout " << b.oldLayout << " -> " << b.newLayout << "}";
}

namespace {

constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags2 kRt = VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR;
constexpr VkPipelineStageFlags2 kFs = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
constexpr VkPipelineStageFlags2 kNone = VK_PIPELINE_STAGE_2_NONE;
constexpr VkAccessFlags2 kSr = VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
constexpr VkAccessFlags2 kSw = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
constexpr VkAccessFlags2 kSampled = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
constexpr VkImageLayout kUndef = VK_IMAGE_LAYOUT_UNDEFINED;
constexpr VkImageLayout kGeneral = VK_IMAGE_LAYOUT_GENERAL;
constexpr VkImageLayout kReadOnly = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
constexpr bool kImage = true;
constexpr bool kBuffer = false;

std::optional<Barrier> barrier(VkPipelineStageFlags2 src, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dst,
                               VkAccessFlags2 dstAccess, VkImageLayout oldLayout = kUndef,
                               VkImageLayout newLayout = kUndef) {
  return Barrier{src, dst, srcAccess, dstAccess, oldLayout, newLayout};
}

TEST(GraphState, FirstWriteTransitionsFromUndefined) {
  ResourceState s;
  EXPECT_EQ(transition(s, Use::StorageWriteCompute, kImage), barrier(kNone, 0, kCs, kSw, kUndef, kGeneral));
  EXPECT_EQ(s.layout, kGeneral);
  EXPECT_TRUE(s.contentsValid);
}

TEST(GraphState, WriteToInvalidContentsDiscards) {
  // e.g. an aliased transient whose memory held another resource: the old layout is meaningless.
  ResourceState s{.layout = kGeneral, .contentsValid = false};
  EXPECT_EQ(transition(s, Use::ColorAttachment, kImage),
            barrier(kNone, 0, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, kUndef,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL));
}

TEST(GraphState, RawComputeToCompute) {
  ResourceState s;
  transition(s, Use::StorageWriteCompute, kImage);
  EXPECT_EQ(transition(s, Use::StorageReadCompute, kImage), barrier(kCs, kSw, kCs, kSr, kGeneral, kGeneral));
}

TEST(GraphState, RawRaygenStorageToSampledCompute) {
  ResourceState s;
  EXPECT_EQ(transition(s, Use::StorageWriteRayTracing, kImage), barrier(kNone, 0, kRt, kSw, kUndef, kGeneral));
  EXPECT_EQ(transition(s, Use::SampledCompute, kImage), barrier(kRt, kSw, kCs, kSampled, kGeneral, kReadOnly));
}

TEST(GraphState, ComputeRaygenComputeChain) {
  ResourceState s;
  EXPECT_EQ(transition(s, Use::StorageWriteCompute, kImage), barrier(kNone, 0, kCs, kSw, kUndef, kGeneral));
  EXPECT_EQ(transition(s, Use::StorageReadRayTracing, kImage), barrier(kCs, kSw, kRt, kSr, kGeneral, kGeneral));
  // Write-after-read: waiting for the raygen readers also orders the compute write before it.
  EXPECT_EQ(transition(s, Use::StorageWriteRayTracing, kImage), barrier(kRt, 0, kRt, kSw, kGeneral, kGeneral));
  EXPECT_EQ(transition(s, Use::SampledCompute, kImage), barrier(kRt, kSw, kCs, kSampled, kGeneral, kReadOnly));
  EXPECT_EQ(transition(s, Use::SampledCompute, kImage), std::nullopt);
}

TEST(GraphState, WarSampledThenStorageWrite) {
  ResourceState s{.layout = kReadOnly, .contentsValid = true};  // an imported texture
  EXPECT_EQ(transition(s, Use::SampledCompute, kImage), std::nullopt);
  EXPECT_EQ(transition(s, Use::StorageWriteCompute, kImage), barrier(kCs, 0, kCs, kSw, kReadOnly, kGeneral));
}

TEST(GraphState, WawBuffer) {
  ResourceState s;
  EXPECT_EQ(transition(s, Use::StorageWriteCompute, kBuffer), std::nullopt);
  EXPECT_EQ(transition(s, Use::StorageWriteRayTracing, kBuffer), barrier(kCs, kSw, kRt, kSw));
  EXPECT_EQ(transition(s, Use::StorageReadWriteRayTracing, kBuffer), barrier(kRt, kSw, kRt, kSr | kSw));
}

TEST(GraphState, ReadAfterReadNeedsNoBarrier) {
  ResourceState s;
  transition(s, Use::StorageWriteCompute, kImage);
  ASSERT_TRUE(transition(s, Use::SampledCompute, kImage));
  EXPECT_EQ(transition(s, Use::SampledCompute, kImage), std::nullopt);

  ResourceState imported{.contentsValid = true};
  EXPECT_EQ(transition(imported, Use::StorageReadCompute, kBuffer), std::nullopt);
  EXPECT_EQ(transition(imported, Use::StorageReadRayTracing, kBuffer), std::nullopt);
}

TEST(GraphState, SecondReaderInNewStageGetsItsOwnBarrier) {
  ResourceState s;
  transition(s, Use::StorageWriteCompute, kBuffer);
  EXPECT_EQ(transition(s, Use::StorageReadCompute, kBuffer), barrier(kCs, kSw, kCs, kSr));
  EXPECT_EQ(transition(s, Use::StorageReadCompute, kBuffer), std::nullopt);
  EXPECT_EQ(transition(s, Use::StorageReadRayTracing, kBuffer), barrier(kCs, kSw, kRt, kSr));
  EXPECT_EQ(transition(s, Use::StorageReadRayTracing, kBuffer), std::nullopt);
  EXPECT_EQ(transition(s, Use::StorageReadCompute, kBuffer), std::nullopt);
  // The next write waits for every reader; the write they read was already made available.
  EXPECT_EQ(transition(s, Use::StorageWriteCompute, kBuffer), barrier(kCs | kRt, 0, kCs, kSw));
}

TEST(GraphState, SecondReaderAfterLayoutTransitionChainsThroughIt) {
  ResourceState s;
  transition(s, Use::StorageWriteRayTracing, kImage);
  ASSERT_TRUE(transition(s, Use::SampledCompute, kImage));
  // The transition completed before compute; a fragment reader waits on compute, not on raygen.
  EXPECT_EQ(transition(s, Use::SampledFragment, kImage), barrier(kCs, 0, kFs, kSampled, kReadOnly, kReadOnly));
  EXPECT_EQ(transition(s, Use::SampledCompute, kImage), std::nullopt);
  EXPECT_EQ(transition(s, Use::StorageWriteCompute, kImage), barrier(kCs | kFs, 0, kCs, kSw, kReadOnly, kGeneral));
}

TEST(GraphState, ColorAttachmentToSampledCompute) {
  ResourceState s;
  transition(s, Use::ColorAttachment, kImage);
  EXPECT_EQ(transition(s, Use::SampledCompute, kImage),
            barrier(VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, kCs,
                    kSampled, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kReadOnly));
}

TEST(GraphState, DepthAttachmentToSampledCompute) {
  ResourceState s;
  const VkPipelineStageFlags2 tests =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  transition(s, Use::DepthAttachment, kImage);
  EXPECT_EQ(transition(s, Use::SampledCompute, kImage),
            barrier(tests, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, kCs, kSampled,
                    VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kReadOnly));
}

TEST(GraphState, BufferRawHasNoLayout) {
  ResourceState s;
  EXPECT_EQ(transition(s, Use::TransferDst, kBuffer), std::nullopt);
  const auto b = transition(s, Use::UniformRead, kBuffer);
  ASSERT_TRUE(b);
  EXPECT_EQ(b->oldLayout, kUndef);
  EXPECT_EQ(b->newLayout, kUndef);
  EXPECT_EQ(b->srcStages, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
  EXPECT_EQ(b->srcAccess, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  EXPECT_EQ(b->dstStages, VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | kFs | kCs | kRt);
  EXPECT_EQ(b->dstAccess, VK_ACCESS_2_UNIFORM_READ_BIT);
  EXPECT_EQ(s.layout, kUndef);
}

TEST(GraphState, TransferDstToHostRead) {
  ResourceState s;
  transition(s, Use::TransferDst, kBuffer);
  EXPECT_EQ(transition(s, Use::HostRead, kBuffer),
            barrier(VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                    VK_ACCESS_2_HOST_READ_BIT));
}

// GPU culling: a compute pass writes draw commands and counts that vkCmdDrawIndirectCount reads,
// and clears them with a transfer first.
TEST(GraphState, ComputeWriteToIndirectRead) {
  ResourceState s;
  transition(s, Use::TransferDst, kBuffer);
  EXPECT_EQ(transition(s, Use::StorageReadWriteCompute, kBuffer),
            barrier(VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, kCs,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT));
  EXPECT_EQ(transition(s, Use::IndirectRead, kBuffer),
            barrier(kCs, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                    VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT));
  // The next frame's clear must wait for this frame's indirect reads (write after read).
  const auto war = transition(s, Use::TransferDst, kBuffer);
  ASSERT_TRUE(war);
  EXPECT_EQ(war->srcStages, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT);
  EXPECT_EQ(war->dstStages, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
}

TEST(GraphState, TransferImageLayouts) {
  ResourceState s;
  EXPECT_EQ(transition(s, Use::TransferDst, kImage),
            barrier(kNone, 0, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, kUndef,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL));
  EXPECT_EQ(transition(s, Use::TransferSrc, kImage),
            barrier(VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
}

TEST(GraphState, AccelStructBuildThenTrace) {
  ResourceState s;
  const VkPipelineStageFlags2 build = VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR;
  const VkAccessFlags2 asRead = VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR;
  const VkAccessFlags2 asWrite = VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
  EXPECT_EQ(transition(s, Use::AccelStructBuildWrite, kBuffer), std::nullopt);
  EXPECT_EQ(transition(s, Use::AccelStructRead, kBuffer), barrier(build, asWrite, kRt, asRead));
  // Next frame's refit reads the structure too, so it waits for the tracer and the last build.
  EXPECT_EQ(transition(s, Use::AccelStructBuildWrite, kBuffer), barrier(build | kRt, asWrite, build, asRead | asWrite));
}

// Mirrors the image-only / buffer-only split that accessInfo asserts on.
bool appliesTo(Use use, bool isImage) {
  const bool imageOnly = use <= Use::SampledFragment;
  const bool bufferOnly = (use >= Use::UniformRead && use <= Use::IndexRead) || use >= Use::AccelStructBuildWrite;
  return isImage ? !bufferOnly : !imageOnly;
}

TEST(GraphState, EveryPairOfUsesGivesAWellFormedBarrier) {
  constexpr int kUses = int(Use::IndirectRead) + 1;
  for (bool isImage : {true, false}) {
    for (int first = 0; first < kUses; ++first) {
      for (int second = 0; second < kUses; ++second) {
        if (!appliesTo(Use(first), isImage) || !appliesTo(Use(second), isImage)) continue;
        ResourceState s;
        transition(s, Use(first), isImage);
        const auto b = transition(s, Use(second), isImage);
        const auto info = accessInfo(Use(second), isImage);
        if (!b) {
          // Only a read may skip its barrier: every write follows a write or a read here.
          EXPECT_FALSE(info.writes) << useName(Use(first)) << " -> " << useName(Use(second));
          continue;
        }
        EXPECT_NE(b->dstStages, 0u) << useName(Use(first)) << " -> " << useName(Use(second));
        EXPECT_NE(b->srcStages, 0u) << useName(Use(first)) << " -> " << useName(Use(second));
        if (!isImage) {
          EXPECT_EQ(b->oldLayout, b->newLayout);
        }
      }
    }
  }
}

TEST(GraphStateDeathTest, WrongResourceKindAsserts) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(accessInfo(Use::SampledCompute, kBuffer), "images only");
  EXPECT_DEATH(accessInfo(Use::IndexRead, kImage), "buffers only");
}

}  // namespace
}  // namespace rayster::graph
