// Pass 1 (traced producer, --primary rt): primary rays write the same G-buffer as the rasteriser.
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

GBuffer createGBufferTargets(graph::RenderGraph& graph, VkExtent2D size, bool traced);

GBuffer traceGBuffer(graph::RenderGraph& graph, const FrameInputs& in) {
  GBuffer gb = createGBufferTargets(graph, in.size, true);
  graph.addPass(
      "gbuffer-traced",
      [&](graph::PassBuilder& b) {
        for (auto h : {gb.depth, gb.normals, gb.albedo, gb.material, gb.emissive, gb.id, gb.motion, gb.specular})
          b.write(h, graph::Use::StorageWriteRayTracing);
        b.rays(uint64_t(in.size.width) * in.size.height, true);  // one primary ray per pixel, always traced
      },
      [gb, &in](graph::PassContext& pc) {
        const rhi::RayTracingPipeline& pipe = in.pipelines.gbufferTraced;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .accelerationStructure(1, in.scene.tlas.handle())
            .storageImage(2, pc.image(gb.depth).view())
            .storageImage(3, pc.image(gb.normals).view())
            .storageImage(4, pc.image(gb.albedo).view())
            .storageImage(5, pc.image(gb.material).view())
            .storageImage(6, pc.image(gb.emissive).view())
            .storageImage(7, pc.image(gb.id).view())
            .storageImage(8, pc.image(gb.motion).view())
            .storageImage(9, pc.image(gb.specular).view())
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        pipe.trace(pc.cmd, in.size.width, in.size.height);
      });
  return gb;
}

} // namespace rayster::render
