#pragma once
// Shows the renderer's output in the window: blits the tonemapped image into the swapchain image,
// draws Dear ImGui over it, and presents. Optionally reads the presented image back (screenshots).
#include <memory>
#include <optional>

#include <volk.h>

#include "core/image.h"
#include "rhi/commands.h"
#include "rhi/resources.h"
#include "rhi/swapchain.h"

struct ImDrawData;

namespace rayster::app {

class Presenter {
 public:
  Presenter(rhi::Context& ctx, VkExtent2D size, bool vsync);
  ~Presenter();

  rhi::Swapchain& swapchain() { return swapchain_; }
  void resize(VkExtent2D size, bool vsync);
  VkRenderPass uiPass() const { return uiPass_; }

  // Presents `frame` (TRANSFER_SRC_OPTIMAL, from Renderer::outputImage) with `ui` drawn over it.
  // With `capture`, also returns the presented pixels. False when the swapchain was out of date
  // (nothing was presented; resize and render again).
  // `shown`, when given, replaces the frame (debug views read back on the CPU; RGBA, sRGB-encoded).
  bool present(const rhi::Image& frame, ImDrawData* ui, Image8* capture, const Image8* shown = nullptr);

 private:
  void createFramebuffers();
  void destroyFramebuffers();
  rhi::Context& ctx_;
  rhi::Swapchain swapchain_;
  rhi::CommandList commands_;
  VkRenderPass uiPass_ = VK_NULL_HANDLE;
  std::vector<VkFramebuffer> framebuffers_;
  rhi::Buffer captureBuffer_;
  rhi::Buffer shownStaging_;
  rhi::Image shownImage_;
};

}  // namespace rayster::app
