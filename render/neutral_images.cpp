#include "render/neutral_images.h"

#include "graph/transient_pool.h"
#include "render/pipelines.h"
#include "rhi/commands.h"
#include "rhi/context.h"

namespace rayster::render {

NeutralImages::NeutralImages(rhi::Context& ctx)
    : white_(ctx,
             {kVisibilityFormat, 1, 1, 1,
              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, true},
             "neutral-white"),
      black_(ctx,
             {kRadianceFormat, 1, 1, 1,
              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
             "neutral-black"),
      layers_(ctx,
              {kLayersFormat, 1, 1, 1,
               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
              "neutral-layers") {
  // Cleared through a graph of their own, so their states say what the frames' graphs will find.
  graph::TransientPool pool(false);
  graph::RenderGraph graph(&ctx, &pool);
  for (auto [h, value] : {std::pair{white(graph), 1.0f}, {black(graph), 0.0f}, {layers(graph), 0.0f}})
    graph.addPass(
        "neutral-clear", [h](graph::PassBuilder& b) { b.write(h, graph::Use::TransferDst); },
        [h, value](graph::PassContext& pc) {
          const VkClearColorValue colour{{value, value, value, value}};  // 0.0f is all-zero bits for the uint image
          const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
          vkCmdClearColorImage(pc.cmd, pc.image(h).handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &colour, 1, &range);
        });
  rhi::OneShot once(ctx);
  graph.execute(once, nullptr);
  once.submitAndWait();
}

}  // namespace rayster::render
