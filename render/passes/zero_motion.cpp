// Interim, until the G-buffer has motion vectors (another branch adds GBuffer::motion): a motion
// image cleared to zero, right for static scenes. Delete this file and its declaration in
// denoise.h at the merge, and pass gb.motion to the denoisers in renderer.cpp.
#include "render/passes/denoise.h"

namespace rayster::render {

graph::ImageHandle zeroMotion(graph::RenderGraph& graph, VkExtent2D size) {
  graph::ImageHandle motion = graph.createImage(
      "motion-zero", {kMotionFormat, size.width, size.height, 1,
                      VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
  graph.addPass(
      "motion-zero", [&](graph::PassBuilder& b) { b.write(motion, graph::Use::TransferDst); },
      [motion](graph::PassContext& pc) {
        const VkClearColorValue zero{};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(pc.cmd, pc.image(motion).handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &all);
      });
  return motion;
}

}  // namespace rayster::render
