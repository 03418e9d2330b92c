#include "app/viewer/presenter.h"

#include <cstring>

#include <imgui.h>
#include <imgui_impl_vulkan.h>

#include "rhi/context.h"
#include "rhi/vk_check.h"

namespace rayster::app {
namespace {

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
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
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

bool isBgr(VkFormat f) { return f == VK_FORMAT_B8G8R8A8_UNORM || f == VK_FORMAT_B8G8R8A8_SRGB; }

}  // namespace

Presenter::Presenter(rhi::Context& ctx, VkExtent2D size, bool vsync)
    : ctx_(ctx), swapchain_(ctx, size, vsync), commands_(ctx) {
  // The UI draws over the blitted frame: load it, keep it in the attachment layout (barriers
  // around the pass are explicit, below).
  VkAttachmentDescription color{};
  color.format = swapchain_.format();
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.colorAttachmentCount = 1;
  sub.pColorAttachments = &ref;
  VkRenderPassCreateInfo rci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  rci.attachmentCount = 1;
  rci.pAttachments = &color;
  rci.subpassCount = 1;
  rci.pSubpasses = &sub;
  VK_CHECK(vkCreateRenderPass(ctx.device(), &rci, nullptr, &uiPass_));
  createFramebuffers();
}

Presenter::~Presenter() {
  ctx_.waitIdle();
  destroyFramebuffers();
  vkDestroyRenderPass(ctx_.device(), uiPass_, nullptr);
}

void Presenter::createFramebuffers() {
  const VkExtent2D e = swapchain_.extent();
  for (uint32_t i = 0; i < swapchain_.imageCount(); ++i) {
    VkImageView view = swapchain_.view(i);
    VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fci.renderPass = uiPass_;
    fci.attachmentCount = 1;
    fci.pAttachments = &view;
    fci.width = e.width;
    fci.height = e.height;
    fci.layers = 1;
    VkFramebuffer fb;
    VK_CHECK(vkCreateFramebuffer(ctx_.device(), &fci, nullptr, &fb));
    framebuffers_.push_back(fb);
  }
}

void Presenter::destroyFramebuffers() {
  for (VkFramebuffer fb : framebuffers_) vkDestroyFramebuffer(ctx_.device(), fb, nullptr);
  framebuffers_.clear();
}

void Presenter::resize(VkExtent2D size, bool vsync) {
  ctx_.waitIdle();
  destroyFramebuffers();
  swapchain_.recreate(size, vsync);
  createFramebuffers();
}

bool Presenter::present(const rhi::Image& rendered, ImDrawData* ui, Image8* capture, const Image8* shown) {
  uint32_t index = 0;
  if (!swapchain_.acquire(index)) return false;
  const VkImage target = swapchain_.image(index);
  const VkExtent2D e = swapchain_.extent();
  VkCommandBuffer cmd = commands_.begin();
  if (shown) {
    const rhi::ImageDesc desc{
        VK_FORMAT_R8G8B8A8_UNORM, uint32_t(shown->width), uint32_t(shown->height), 1,
        VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT};
    if (!shownImage_ || !(shownImage_.desc() == desc)) shownImage_ = rhi::Image(ctx_, desc, "debug-view");
    if (!shownStaging_ || shownStaging_.size() < shown->rgba.size())
      shownStaging_ = rhi::Buffer(ctx_, shown->rgba.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, rhi::MemoryUsage::Upload,
                                  "debug-view-staging");
    std::memcpy(shownStaging_.mapped(), shown->rgba.data(), shown->rgba.size());
    imageBarrier(cmd, shownImage_.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {desc.width, desc.height, 1};
    vkCmdCopyBufferToImage(cmd, shownStaging_.handle(), shownImage_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &region);
    imageBarrier(cmd, shownImage_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT);
  }
  const rhi::Image& frame = shown ? shownImage_ : rendered;
  imageBarrier(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  // The frame was rendered at the swapchain's size, except on the frame a resize arrives: then it
  // is scaled. The blit also converts RGBA to the chain's channel order.
  VkImageBlit blit{};
  blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {int32_t(frame.desc().width), int32_t(frame.desc().height), 1};
  blit.dstOffsets[1] = {int32_t(e.width), int32_t(e.height), 1};
  const bool sameSize = frame.desc().width == e.width && frame.desc().height == e.height;
  vkCmdBlitImage(cmd, frame.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, sameSize ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
  imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
               VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
               VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  if (ui) {
    VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rbi.renderPass = uiPass_;
    rbi.framebuffer = framebuffers_[index];
    rbi.renderArea = {{0, 0}, e};
    vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ui, cmd);
    vkCmdEndRenderPass(cmd);
  }
  VkImageLayout layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkAccessFlags2 access = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
  if (capture) {
    const VkDeviceSize bytes = VkDeviceSize(e.width) * e.height * 4;
    if (!captureBuffer_ || captureBuffer_.size() < bytes)
      captureBuffer_ =
          rhi::Buffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "screenshot");
    imageBarrier(cmd, target, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, stage, access, VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {e.width, e.height, 1};
    vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, captureBuffer_.handle(), 1, &region);
    VkMemoryBarrier2 host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    host.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    host.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &host;
    vkCmdPipelineBarrier2(cmd, &dep);
    layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    stage = VK_PIPELINE_STAGE_2_COPY_BIT;
    access = 0;
  }
  imageBarrier(cmd, target, layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, stage, access,
               VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0);
  VK_CHECK(vkEndCommandBuffer(cmd));
  const uint64_t done = ctx_.submit(cmd, swapchain_.acquired(), swapchain_.renderDone(index));
  const bool presented = swapchain_.present(index);
  ctx_.wait(done);  // one frame in flight: the renderer waits for its frames anyway
  if (capture) {
    *capture = Image8::make(int(e.width), int(e.height));
    const uint8_t* src = static_cast<const uint8_t*>(captureBuffer_.mapped());
    const bool bgr = isBgr(swapchain_.format());
    for (size_t i = 0; i < size_t(e.width) * e.height; ++i) {
      capture->rgba[i * 4 + 0] = src[i * 4 + (bgr ? 2 : 0)];
      capture->rgba[i * 4 + 1] = src[i * 4 + 1];
      capture->rgba[i * 4 + 2] = src[i * 4 + (bgr ? 0 : 2)];
      capture->rgba[i * 4 + 3] = 255;
    }
  }
  return presented;
}

}  // namespace rayster::app
