// Pass 4: ray-traced reflections and refractions (the raygen bounce loop), and their accumulation
// over the frames of a static camera.
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle traceSpecular(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb) {
  graph::ImageHandle out = graph.createImage(
      "specular-raw", {kRadianceFormat, in.size.width, in.size.height, 1,
                       VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
  graph.addPass(
      "rt-specular",
      [&](graph::PassBuilder& b) {
        for (auto h : {gb.depth, gb.normals, gb.albedo, gb.material, gb.emissive}) b.read(h, graph::Use::SampledRayTracing);
        b.write(out, graph::Use::StorageWriteRayTracing);
      },
      [gb, out, &in](graph::PassContext& pc) {
        const rhi::RayTracingPipeline& pipe = in.pipelines.specular;
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
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        pipe.trace(pc.cmd, in.size.width, in.size.height);
      });
  return out;
}

graph::ImageHandle accumulateRadiance(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle raw,
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
        const rhi::Pipeline& pipe = in.pipelines.radianceAccumulate;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        rhi::DescriptorWriter()
            .storageImage(1, pc.image(raw).view())
            .storageImage(2, pc.image(history).view())
            .storageImage(3, pc.image(next).view())
            .push(pc.cmd, pipe);
        uint32_t push[4] = {in.size.width, in.size.height, samples, 0};
        vkCmdPushConstants(pc.cmd, pipe.layout(), pipe.stages(), 0, sizeof(push), push);
        vkCmdDispatch(pc.cmd, (in.size.width + 7) / 8, (in.size.height + 7) / 8, 1);
      });
  return next;
}

} // namespace rayster::render
