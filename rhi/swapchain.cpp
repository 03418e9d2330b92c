#include "rhi/swapchain.h"

#include <algorithm>

#include "core/log.h"
#include "rhi/context.h"
#include "rhi/vk_check.h"

namespace rayster::rhi {
namespace {

// The renderer's output holds sRGB-encoded bytes, so a UNORM chain shows them as they are (an sRGB
// chain would encode them twice); Dear ImGui's colours are authored for that too.
VkSurfaceFormatKHR chooseFormat(VkPhysicalDevice pd, VkSurfaceKHR surface) {
  uint32_t n = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &n, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(n);
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &n, formats.data()));
  for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
    for (const auto& f : formats)
      if (f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
  return formats.front();
}

VkPresentModeKHR choosePresentMode(VkPhysicalDevice pd, VkSurfaceKHR surface, bool vsync) {
  if (vsync) return VK_PRESENT_MODE_FIFO_KHR;  // always supported
  uint32_t n = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface, &n, nullptr));
  std::vector<VkPresentModeKHR> modes(n);
  VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface, &n, modes.data()));
  for (VkPresentModeKHR want : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
    if (std::find(modes.begin(), modes.end(), want) != modes.end()) return want;
  return VK_PRESENT_MODE_FIFO_KHR;
}

}  // namespace

Swapchain::Swapchain(Context& ctx, VkExtent2D size, bool vsync) : ctx_(ctx) {
  VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VK_CHECK(vkCreateSemaphore(ctx.device(), &sci, nullptr, &acquired_));
  recreate(size, vsync);
}

Swapchain::~Swapchain() {
  vkDeviceWaitIdle(ctx_.device());
  destroyViews();
  for (VkSemaphore s : renderDone_) vkDestroySemaphore(ctx_.device(), s, nullptr);
  vkDestroySemaphore(ctx_.device(), acquired_, nullptr);
  if (swapchain_) vkDestroySwapchainKHR(ctx_.device(), swapchain_, nullptr);
}

void Swapchain::destroyViews() {
  for (VkImageView v : views_) vkDestroyImageView(ctx_.device(), v, nullptr);
  views_.clear();
}

void Swapchain::recreate(VkExtent2D size, bool vsync) {
  ctx_.waitIdle();
  const VkPhysicalDevice pd = ctx_.physicalDevice();
  const VkSurfaceKHR surface = ctx_.surface();
  VkSurfaceCapabilitiesKHR caps;
  VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, surface, &caps));
  const VkSurfaceFormatKHR format = chooseFormat(pd, surface);
  if (caps.currentExtent.width != UINT32_MAX) size = caps.currentExtent;  // the window system decides
  size.width = std::clamp(size.width, caps.minImageExtent.width, caps.maxImageExtent.width);
  size.height = std::clamp(size.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  minImageCount_ = std::max(2u, caps.minImageCount + 1);
  if (caps.maxImageCount) minImageCount_ = std::min(minImageCount_, caps.maxImageCount);

  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface;
  ci.minImageCount = minImageCount_;
  ci.imageFormat = format.format;
  ci.imageColorSpace = format.colorSpace;
  ci.imageExtent = size;
  ci.imageArrayLayers = 1;
  // Transfer dst: the frame is blitted in; transfer src: --screenshot reads the presented image.
  ci.imageUsage =
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  ci.presentMode = choosePresentMode(pd, surface, vsync);
  ci.clipped = VK_TRUE;
  ci.oldSwapchain = swapchain_;
  VkSwapchainKHR next = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSwapchainKHR(ctx_.device(), &ci, nullptr, &next));
  destroyViews();
  if (swapchain_) vkDestroySwapchainKHR(ctx_.device(), swapchain_, nullptr);
  swapchain_ = next;
  format_ = format.format;
  extent_ = size;
  vsync_ = vsync;

  uint32_t n = 0;
  VK_CHECK(vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &n, nullptr));
  images_.resize(n);
  VK_CHECK(vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &n, images_.data()));
  for (VkImage image : images_) {
    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.image = image;
    vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vci.format = format_;
    vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view;
    VK_CHECK(vkCreateImageView(ctx_.device(), &vci, nullptr, &view));
    views_.push_back(view);
  }
  VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  while (renderDone_.size() < n) {
    VkSemaphore s;
    VK_CHECK(vkCreateSemaphore(ctx_.device(), &sci, nullptr, &s));
    renderDone_.push_back(s);
  }
  log::debug("swapchain: {}x{}, {} images, format {}, {}", size.width, size.height, n, int(format_),
             vsync ? "vsync" : "no vsync");
}

bool Swapchain::acquire(uint32_t& index) {
  VkResult r = vkAcquireNextImageKHR(ctx_.device(), swapchain_, UINT64_MAX, acquired_, VK_NULL_HANDLE, &index);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) return false;
  if (r != VK_SUBOPTIMAL_KHR) VK_CHECK(r);
  return true;
}

bool Swapchain::present(uint32_t index) {
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &renderDone_[index];
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_;
  pi.pImageIndices = &index;
  VkResult r = vkQueuePresentKHR(ctx_.queue(), &pi);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) return false;
  VK_CHECK(r);
  return true;
}

}  // namespace rayster::rhi
