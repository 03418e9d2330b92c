#pragma once
// The window's swapchain: images, their views, and the semaphores that order acquire, the frame's
// submission and presentation. Recreated on resize and when vsync is toggled.
#include <cstdint>
#include <vector>

#include <volk.h>

namespace rayster::rhi {

class Context;

class Swapchain {
 public:
  Swapchain(Context& ctx, VkExtent2D size, bool vsync);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // Waits for the device to go idle and rebuilds the chain (the old one is handed over to the driver).
  void recreate(VkExtent2D size, bool vsync);
  // The next image to draw into; false when the chain is out of date (recreate, then try again).
  bool acquire(uint32_t& index);
  // Queues `index` for presentation after renderDone(index) is signalled; false when out of date.
  bool present(uint32_t index);

  VkSemaphore acquired() const { return acquired_; }
  VkSemaphore renderDone(uint32_t index) const { return renderDone_[index]; }
  VkImage image(uint32_t index) const { return images_[index]; }
  VkImageView view(uint32_t index) const { return views_[index]; }
  uint32_t imageCount() const { return uint32_t(images_.size()); }
  uint32_t minImageCount() const { return minImageCount_; }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  bool vsync() const { return vsync_; }

 private:
  void destroyViews();
  Context& ctx_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{};
  bool vsync_ = true;
  uint32_t minImageCount_ = 2;
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  VkSemaphore acquired_ = VK_NULL_HANDLE;
  std::vector<VkSemaphore> renderDone_;  // one per image: presentation may hold it until reacquired
};

}  // namespace rayster::rhi
