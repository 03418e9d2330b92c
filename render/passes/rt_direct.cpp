// Pass 2b: many-light direct lighting, one importance-picked light and one shadow ray per pixel.
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle traceDirect(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb) {
  graph::ImageHandle out = graph.createImage(
      "direct-raw", {kRadianceFormat, in.size.width, in.size.height, 1,
                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
      kRadianceImage);
  graph.addPass(
      "rt-direct",
      [&](graph::PassBuilder& b) {
        for (auto h : {gb.depth, gb.normals, gb.albedo, gb.material, gb.emissive, gb.specular})
          b.read(h, graph::Use::SampledRayTracing);
        b.write(out, graph::Use::StorageWriteRayTracing);
        b.rays(uint64_t(in.size.width) * in.size.height);  // one shadow ray to the picked light per pixel
      },
      [gb, out, &in](graph::PassContext& pc) {
        const rhi::RayTracingPipeline& pipe = in.pipelines.direct;
        VkSampler s = in.nearest.handle();
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .accelerationStructure(1, in.scene.tlas.handle())
            .sampledImage(2, pc.image(gb.depth).view(), s)
            .sampledImage(3, pc.image(gb.normals).view(), s)
            .sampledImage(4, pc.image(gb.albedo).view(), s)
            .sampledImage(5, pc.image(gb.material).view(), s)
            .storageImage(6, pc.image(out).view())
            .sampledImage(7, pc.image(gb.emissive).view(), s)
            .sampledImage(8, pc.image(gb.specular).view(), s)
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        pipe.trace(pc.cmd, in.size.width, in.size.height);
      });
  return out;
}

} // namespace rayster::render
