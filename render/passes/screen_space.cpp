// Raster mode: screen-space reflections and refraction, and the constant stand-in images.
#include "render/passes/raster_passes.h"
#include "render/pipelines.h"

namespace rayster::render {

RasterConstants rasterConstants(graph::RenderGraph& graph, const FrameInputs& in) {
  constexpr VkImageUsageFlags kUsage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                       VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  RasterConstants c;
  c.ao = graph.createImage("raster-ao", {kVisibilityFormat, in.size.width, in.size.height, 1, kUsage, true});
  c.zero = graph.createImage("raster-zero", {kRadianceFormat, in.size.width, in.size.height, 1, kUsage}, kRadianceImage);
  graph.addPass(
      "raster-constants",
      [&](graph::PassBuilder& b) {
        b.write(c.ao, graph::Use::StorageWriteCompute);
        b.write(c.zero, graph::Use::StorageWriteCompute);
      },
      [c, &in](graph::PassContext& pc) {
        const rhi::Pipeline& pipe = in.pipelines.rasterConstants;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        rhi::DescriptorWriter()
            .storageImage(0, pc.image(c.ao).view())
            .storageImage(1, pc.image(c.zero).view())
            .push(pc.cmd, pipe);
        const uint32_t size[2] = {in.size.width, in.size.height};
        vkCmdPushConstants(pc.cmd, pipe.layout(), pipe.stages(), 0, sizeof(size), size);
        vkCmdDispatch(pc.cmd, (in.size.width + 7) / 8, (in.size.height + 7) / 8, 1);
      });
  return c;
}

graph::ImageHandle screenSpaceSpecular(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                       graph::ImageHandle lit) {
  graph::ImageHandle out = graph.createImage(
      "ssr", {kRadianceFormat, in.size.width, in.size.height, 1,
              VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
      kRadianceImage);
  graph.addPass(
      "ssr",
      [&](graph::PassBuilder& b) {
        for (auto h : {gb.depth, gb.normals, gb.albedo, gb.material, gb.emissive, lit, gb.specular})
          b.read(h, graph::Use::SampledCompute);
        b.write(out, graph::Use::StorageWriteCompute);
      },
      [gb, lit, out, &in](graph::PassContext& pc) {
        const rhi::Pipeline& pipe = in.pipelines.ssr;
        VkSampler s = in.nearest.handle(), l = in.linear.handle();
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .sampledImage(1, pc.image(gb.depth).view(), s)
            .sampledImage(2, pc.image(gb.normals).view(), s)
            .sampledImage(3, pc.image(gb.albedo).view(), s)
            .sampledImage(4, pc.image(gb.material).view(), s)
            .sampledImage(5, pc.image(gb.emissive).view(), s)
            .sampledImage(6, pc.image(lit).view(), l)
            .storageImage(7, pc.image(out).view())
            .sampledImage(8, pc.image(gb.specular).view(), s)
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.layout());
        vkCmdDispatch(pc.cmd, (in.size.width + 7) / 8, (in.size.height + 7) / 8, 1);
      });
  return out;
}

} // namespace rayster::render
