#include "rhi/upload.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "rhi/commands.h"
#include "rhi/context.h"

namespace rayster::rhi {
namespace {

// Large enough that a scene's thousands of small buffers share a few submissions, small enough
// that host-visible memory stays bounded (kUploadChunksInFlight of them at once); an upload larger
// than a chunk gets one of its own size.
constexpr VkDeviceSize kUploadChunkBytes = VkDeviceSize(64) << 20;
constexpr size_t kUploadChunksInFlight = 4;
// Copies into buffers start at multiples of this (the largest texel block and vertex alignment).
constexpr VkDeviceSize kStagingAlign = 16;

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

// The image for `desc` with its mip count and usage set for an upload.
Image createUploadImage(Context& ctx, ImageDesc& desc, bool generateMips, const char* name) {
  desc.mips = generateMips ? uint32_t(std::floor(std::log2(double(std::max(desc.width, desc.height))))) + 1 : 1;
  desc.usage |= VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                (desc.mips > 1 ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
  return Image(ctx, desc, name);
}

// Level 0 from the staging buffer, left in TRANSFER_DST_OPTIMAL.
void recordLevel0Copy(VkCommandBuffer cmd, VkImage image, const ImageDesc& desc, VkBuffer staging,
                      VkDeviceSize offset) {
  mipBarrier(cmd, image, 0, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE,
             0, kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkBufferImageCopy region{};
  region.bufferOffset = offset;
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {desc.width, desc.height, 1};
  vkCmdCopyBufferToImage(cmd, staging, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
}

// After recordLevel0Copy(): each further level a linear downsample of the previous one, on the
// stored (UNORM) values, as glTF viewers do (blits: the universal queue). Ends in
// SHADER_READ_ONLY_OPTIMAL.
void recordMipsAndFinish(VkCommandBuffer cmd, VkImage image, const ImageDesc& desc) {
  const uint32_t w = desc.width, h = desc.height;
  for (uint32_t m = 1; m < desc.mips; ++m) {
    mipBarrier(cmd, image, m - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, kTransfer,
               VK_ACCESS_2_TRANSFER_WRITE_BIT, kTransfer, VK_ACCESS_2_TRANSFER_READ_BIT);
    mipBarrier(cmd, image, m, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE,
               0, kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m - 1, 0, 1};
    blit.srcOffsets[1] = {int32_t(std::max(w >> (m - 1), 1u)), int32_t(std::max(h >> (m - 1), 1u)), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, 1};
    blit.dstOffsets[1] = {int32_t(std::max(w >> m, 1u)), int32_t(std::max(h >> m, 1u)), 1};
    vkCmdBlitImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                   &blit, VK_FILTER_LINEAR);
    mipBarrier(cmd, image, m - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
               kTransfer, 0, kShaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  }
  mipBarrier(cmd, image, desc.mips - 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
             kTransfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, kShaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

// Level 0 passes from the transfer queue's family to the universal one, staying in
// TRANSFER_DST_OPTIMAL: the release half (on the transfer queue) when `release`, else the acquire
// half (on the universal queue, after a semaphore wait for the release's submission).
void handOverLevel0(VkCommandBuffer cmd, VkImage image, const Context& ctx, bool release) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = release ? kTransfer : VK_PIPELINE_STAGE_2_NONE;
  b.srcAccessMask = release ? VK_ACCESS_2_TRANSFER_WRITE_BIT : 0;
  b.dstStageMask = release ? VK_PIPELINE_STAGE_2_NONE : kTransfer;
  b.dstAccessMask = release ? 0 : VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
  b.oldLayout = b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  b.srcQueueFamilyIndex = ctx.transferFamily();
  b.dstQueueFamilyIndex = ctx.queueFamily();
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

// Orders this command buffer's transfers before every command submitted after it on the queue
// (a barrier's second scope reaches later submissions).
void transfersBeforeLaterWork(VkCommandBuffer cmd) {
  VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  b.srcStageMask = kTransfer;
  b.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace

Image uploadImage(Context& ctx, ImageDesc desc, std::span<const std::byte> pixels, bool generateMips,
                  const char* name) {
  Image image = createUploadImage(ctx, desc, generateMips, name);
  Buffer staging(ctx, pixels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging");
  std::memcpy(staging.mapped(), pixels.data(), pixels.size());
  OneShot cmd(ctx);
  recordLevel0Copy(cmd, image.handle(), desc, staging.handle(), 0);
  recordMipsAndFinish(cmd, image.handle(), desc);
  cmd.submitAndWait();
  return image;
}

UploadBatch::UploadBatch(Context& ctx) : ctx_(ctx) {}

UploadBatch::~UploadBatch() { wait(); }

VkCommandBuffer UploadBatch::cmd() {
  if (!list_) {
    list_ = std::make_unique<CommandList>(ctx_);
    list_->begin();
  }
  return list_->handle();
}

UploadBatch::Staged UploadBatch::stage(size_t bytes) {
  const VkDeviceSize size = std::max<VkDeviceSize>(bytes, 16);
  if (!chunk_.handle() || used_ + size > chunk_.size()) {
    submit();
    // Bounded host memory: wait for the oldest chunk before a new one beyond the limit.
    if (inFlight_.size() >= kUploadChunksInFlight) {
      while (inFlight_.size() >= kUploadChunksInFlight) {
        ctx_.wait(inFlight_.front());
        inFlight_.pop_front();
      }
      ctx_.collectGarbage();  // frees the chunks those submissions read
    }
    chunk_ = Buffer(ctx_, std::max(kUploadChunkBytes, size), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload,
                    "staging");
    used_ = 0;
  }
  Staged s{chunk_.handle(), used_, static_cast<std::byte*>(chunk_.mapped()) + used_};
  used_ = (used_ + size + kStagingAlign - 1) / kStagingAlign * kStagingAlign;
  bytes_ += bytes;
  return s;
}

Buffer UploadBatch::buffer(std::span<const std::byte> bytes, VkBufferUsageFlags usage, const char* name) {
  const VkDeviceSize size = std::max<VkDeviceSize>(bytes.size(), 16);
  Buffer buffer(ctx_, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::GpuOnly, name);
  const Staged s = stage(bytes.size());
  if (!bytes.empty()) std::memcpy(s.mapped, bytes.data(), bytes.size());
  VkBufferCopy region{s.offset, 0, size};
  vkCmdCopyBuffer(cmd(), s.buffer, buffer.handle(), 1, &region);
  return buffer;
}

Image UploadBatch::image(ImageDesc desc, std::span<const std::byte> pixels, bool generateMips, const char* name) {
  Image image = createUploadImage(ctx_, desc, generateMips, name);
  const Staged s = stage(pixels.size());
  std::memcpy(s.mapped, pixels.data(), pixels.size());
  if (!ctx_.hasTransferQueue()) {
    recordLevel0Copy(cmd(), image.handle(), desc, s.buffer, s.offset);
    recordMipsAndFinish(cmd(), image.handle(), desc);
    return image;
  }
  // The copy on the transfer queue, which runs beside whatever the universal queue does (the
  // scene's BLAS builds); the mips where blits run.
  if (!transfer_) {
    transfer_ = std::make_unique<CommandList>(ctx_, Queue::Transfer);
    transfer_->begin();
    finish_ = std::make_unique<CommandList>(ctx_);
    finish_->begin();
  }
  recordLevel0Copy(transfer_->handle(), image.handle(), desc, s.buffer, s.offset);
  handOverLevel0(transfer_->handle(), image.handle(), ctx_, true);
  handOverLevel0(finish_->handle(), image.handle(), ctx_, false);
  recordMipsAndFinish(finish_->handle(), image.handle(), desc);
  return image;
}

uint64_t UploadBatch::submit() {
  if (list_) {
    transfersBeforeLaterWork(list_->handle());
    last_ = list_->submit();
    inFlight_.push_back(last_);
    ++submissions_;
    list_.reset();  // its pool is retired until the submission completes
  }
  if (transfer_) {
    const uint64_t copied = transfer_->submit();
    transfersBeforeLaterWork(finish_->handle());
    last_ = finish_->submitAfterTransfer(copied);
    inFlight_.push_back(last_);
    submissions_ += 2;
    // Retired at a universal value after the finishing submission, which waited for the copies.
    finish_.reset();
    transfer_.reset();
  }
  // The chunk in use is only ever appended to (its recorded copies may not have run yet), and it
  // is retired when a new one replaces it.
  return last_;
}

void UploadBatch::wait() {
  submit();
  if (last_) ctx_.wait(last_);
  inFlight_.clear();
  chunk_.reset();
  used_ = 0;
}

}  // namespace rayster::rhi
