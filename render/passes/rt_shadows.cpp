// Pass 2: ray-traced soft shadows from the G-buffer (denoised in denoise_shadows.cpp).
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle traceShadows(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t lights,
                                uint32_t extraLayers) {
  const uint32_t layers = std::max(lights + extraLayers, 1u);
  graph::ImageHandle vis = graph.createImage(
      "shadow-raw", {kVisibilityFormat, in.size.width, in.size.height, layers,
                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, true});
  graph.addPass(
      "rt-shadows",
      [&](graph::PassBuilder& b) {
        b.read(gb.depth, graph::Use::SampledRayTracing);
        b.read(gb.normals, graph::Use::SampledRayTracing);
        b.write(vis, graph::Use::StorageWriteRayTracing);
        b.rays(uint64_t(in.size.width) * in.size.height * lights);  // one per pixel and light; none on the sky
      },
      [gb, vis, lights, &in](graph::PassContext& pc) {
        const rhi::RayTracingPipeline& pipe = in.pipelines.shadows;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .accelerationStructure(1, in.scene.tlas.handle())
            .sampledImage(2, pc.image(gb.depth).view(), in.nearest.handle())
            .sampledImage(3, pc.image(gb.normals).view(), in.nearest.handle())
            .storageImage(4, pc.image(vis).view())
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        if (lights > 0) pipe.trace(pc.cmd, in.size.width, in.size.height, lights);
      });
  return vis;
}

} // namespace rayster::render
