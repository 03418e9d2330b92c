// rhi::pickTransferFamily(): the queue family textures are copied on beside the universal queue
// (rhi/upload.h). Only a copy engine qualifies: a family that transfers but neither draws nor
// computes, copying images of any size. Lavapipe has none (its one family does everything), so
// uploads there stay on the universal queue; the H200's NVIDIA driver has one.
#include <vector>

#include <gtest/gtest.h>

#include "rhi/context.h"

namespace rayster::rhi {
namespace {

VkQueueFamilyProperties family(VkQueueFlags flags, uint32_t count, uint32_t granularity = 1) {
  VkQueueFamilyProperties f{};
  f.queueFlags = flags;
  f.queueCount = count;
  f.minImageTransferGranularity = {granularity, granularity, granularity};
  return f;
}

constexpr VkQueueFlags kUniversal = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT | VK_QUEUE_TRANSFER_BIT;

TEST(TransferQueue, PicksTheCopyEngineOfAnNvidiaLikeDevice) {
  const std::vector<VkQueueFamilyProperties> families = {
      family(kUniversal, 16), family(VK_QUEUE_TRANSFER_BIT | VK_QUEUE_SPARSE_BINDING_BIT, 2),
      family(VK_QUEUE_COMPUTE_BIT | VK_QUEUE_TRANSFER_BIT, 8), family(VK_QUEUE_VIDEO_DECODE_BIT_KHR, 1)};
  EXPECT_EQ(pickTransferFamily(families, 0), 1u);
}

TEST(TransferQueue, NoneWhereOneFamilyDoesEverything) {
  EXPECT_EQ(pickTransferFamily({family(kUniversal, 1)}, 0), UINT32_MAX) << "lavapipe";
  // An async-compute family is no copy engine: it would compete with the BLAS builds.
  EXPECT_EQ(pickTransferFamily({family(kUniversal, 1), family(VK_QUEUE_COMPUTE_BIT | VK_QUEUE_TRANSFER_BIT, 4)}, 0),
            UINT32_MAX);
}

TEST(TransferQueue, SkipsFamiliesThatCannotCopyEveryImageSize) {
  const std::vector<VkQueueFamilyProperties> families = {family(kUniversal, 1), family(VK_QUEUE_TRANSFER_BIT, 1, 8),
                                                         family(VK_QUEUE_TRANSFER_BIT, 0),
                                                         family(VK_QUEUE_TRANSFER_BIT, 1)};
  EXPECT_EQ(pickTransferFamily(families, 0), 3u) << "8x8 granularity and no queues are skipped";
}

}  // namespace
}  // namespace rayster::rhi
