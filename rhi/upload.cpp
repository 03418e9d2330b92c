#include "rhi/upload.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "rhi/commands.h"
#include "rhi/context.h"

namespace rayster::rhi {
namespace {

void mipBarrier(VkCommandBuffer cmd, VkImage image, uint32_t mip, VkImageLayout from, VkImageLayout to,
                VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 1, 0, 1};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

constexpr VkPipelineStageFlags2 kTransfer = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
constexpr VkPipelineStageFlags2 kShaders = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;

}  // namespace

Image uploadImage(Context& ctx, ImageDesc desc, std::span<const std::byte> pixels, bool generateMips,
                  const char* name) {
  const uint32_t w = desc.width, h = desc.height;
  desc.mips = generateMips ? uint32_t(std::floor(std::log2(double(std::max(w, h))))) + 1 : 1;
  desc.usage |= VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                (desc.mips > 1 ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
  Image image(ctx, desc, name);
  Buffer staging(ctx, pixels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging");
  std::memcpy(staging.mapped(), pixels.data(), pixels.size());

  OneShot cmd(ctx);
  mipBarrier(cmd, image.handle(), 0, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
             VK_PIPELINE_STAGE_2_NONE, 0, kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {w, h, 1};
  vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  // Each level is a linear downsample of the previous one, on the stored (UNORM) values, as glTF
  // viewers do.
  for (uint32_t m = 1; m < desc.mips; ++m) {
    mipBarrier(cmd, image.handle(), m - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
               kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, kTransfer, VK_ACCESS_2_TRANSFER_READ_BIT);
    mipBarrier(cmd, image.handle(), m, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_2_NONE, 0, kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m - 1, 0, 1};
    blit.srcOffsets[1] = {int32_t(std::max(w >> (m - 1), 1u)), int32_t(std::max(h >> (m - 1), 1u)), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
    blit.dstOffsets[1] = {int32_t(std::max(w >> m, 1u)), int32_t(std::max(h >> m, 1u)), 1};
    vkCmdBlitImage(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.handle(),
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    mipBarrier(cmd, image.handle(), m - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kTransfer, 0, kShaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  }
  mipBarrier(cmd, image.handle(), desc.mips - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, kShaders,
             VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  cmd.submitAndWait();
  return image;
}

}  // namespace rayster::rhi
