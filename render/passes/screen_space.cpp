// Raster mode: screen-space reflections and refraction, and the constant stand-in images.
#include "render/passes/raster_passes.h"
#include "render/pipelines.h"
#include "shaders/shared/push.h"

namespace rayster::render {

RasterConstants rasterConstants(graph::RenderGraph& graph, const FrameInputs& in) {
  constexpr VkImageUsageFlags kUsage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  RasterConstants c;
  c.ao = graph.createImage("raster-ao", {kVisibilityFormat, in.size.width, in.size.height, 1, kUsage, true});
  c.zero =
      graph.createImage("raster-zero", {kRadianceFormat, in.size.width, in.size.height, 1, kUsage}, kRadianceImage);
  graph.addPass(
      "raster-constants",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("raster_constants.comp")).bind("outAo", c.ao).bind("outZero", c.zero);
      },
      [size = in.size](graph::PassContext& pc) {
        pc.push(gpu::SizePush{{size.width, size.height}});
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return c;
}

graph::ImageHandle screenSpaceSpecular(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                       graph::ImageHandle lit) {
  graph::ImageHandle out =
      graph.createImage("ssr",
                        {kRadianceFormat, in.size.width, in.size.height, 1,
                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
                        kRadianceImage);
  graph.addPass(
      "ssr",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("ssr.comp"));
        bindSurface(b, gb);
        b.bind("litTex", lit, in.linear.handle()).bind("outSpecular", out);
      },
      [size = in.size](graph::PassContext& pc) {
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return out;
}

}  // namespace rayster::render
