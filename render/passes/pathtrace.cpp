// The path tracer's one pass: one path per pixel (shaders/pathtrace.rgen.glsl), folded into the
// running mean and mean square of the previous frames (fp32 histories, never updated in place).
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle tracePaths(graph::RenderGraph& graph, const FrameInputs& in, const rhi::RayTracingPipeline& pipe,
                              const PathAccumulation& acc) {
  graph.addPass(
      "pathtrace",
      [&](graph::PassBuilder& b) {
        b.read(acc.previousMean, graph::Use::StorageReadRayTracing);
        b.read(acc.previousMoments, graph::Use::StorageReadRayTracing);
        b.write(acc.mean, graph::Use::StorageWriteRayTracing);
        b.write(acc.moments, graph::Use::StorageWriteRayTracing);
      },
      [acc, &pipe, &in](graph::PassContext& pc) {
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .accelerationStructure(1, in.scene.tlas.handle())
            .storageImage(2, pc.image(acc.previousMean).view())
            .storageImage(3, pc.image(acc.previousMoments).view())
            .storageImage(4, pc.image(acc.mean).view())
            .storageImage(5, pc.image(acc.moments).view())
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        pipe.trace(pc.cmd, in.size.width, in.size.height);
      });
  return acc.mean;
}

} // namespace rayster::render
