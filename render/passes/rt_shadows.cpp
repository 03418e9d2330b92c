// Pass 2: ray-traced soft shadows from the G-buffer, and their accumulation over a static camera.
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle traceShadows(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t lights) {
  const uint32_t layers = std::max(lights, 1u);
  graph::ImageHandle vis = graph.createImage(
      "shadow-raw", {kVisibilityFormat, in.size.width, in.size.height, layers,
                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, true});
  graph.addPass(
      "rt-shadows",
      [&](graph::PassBuilder& b) {
        b.read(gb.depth, graph::Use::SampledRayTracing);
        b.read(gb.normals, graph::Use::SampledRayTracing);
        b.write(vis, graph::Use::StorageWriteRayTracing);
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

graph::ImageHandle accumulateShadows(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle raw,
                                     graph::ImageHandle history, graph::ImageHandle next, uint32_t samples,
                                     const char* name) {
  graph.addPass(
      name,
      [&](graph::PassBuilder& b) {
        b.read(raw, graph::Use::StorageReadCompute);
        b.read(history, graph::Use::StorageReadCompute);
        b.write(next, graph::Use::StorageWriteCompute);
      },
      [raw, history, next, samples, &in](graph::PassContext& pc) {
        const rhi::Pipeline& pipe = in.pipelines.shadowAccumulate;
        const rhi::Image& out = pc.image(next);
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        rhi::DescriptorWriter()
            .storageImage(1, pc.image(raw).view())
            .storageImage(2, pc.image(history).view())
            .storageImage(3, out.view())
            .push(pc.cmd, pipe);
        uint32_t push[4] = {in.size.width, in.size.height, out.desc().layers, samples};
        vkCmdPushConstants(pc.cmd, pipe.layout(), pipe.stages(), 0, sizeof(push), push);
        vkCmdDispatch(pc.cmd, (in.size.width + 7) / 8, (in.size.height + 7) / 8, out.desc().layers);
      });
  return next;
}

} // namespace rayster::render
