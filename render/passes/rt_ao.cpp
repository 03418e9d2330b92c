// Pass 6a: ray-traced ambient occlusion from the G-buffer (one layer of R16F, 1 sample per pixel).
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle traceAo(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                           graph::ImageHandle into) {
  // A layer of an array image, so the shadow denoiser takes it unchanged: the shadow image's AO
  // layer (one denoiser run for lights and AO), or an image of its own.
  graph::ImageHandle ao = into.valid() ? into
                                       : graph.createImage("ao-raw", {kVisibilityFormat, in.size.width, in.size.height, 1,
                                                                      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                                                          VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                                                      true});
  graph.addPass(
      "rt-ao",
      [&](graph::PassBuilder& b) {
        b.read(gb.depth, graph::Use::SampledRayTracing);
        b.read(gb.normals, graph::Use::SampledRayTracing);
        b.write(ao, graph::Use::StorageWriteRayTracing);
        b.rays(uint64_t(in.size.width) * in.size.height);  // one occlusion ray per pixel; none on the sky
      },
      [gb, ao, &in](graph::PassContext& pc) {
        const rhi::RayTracingPipeline& pipe = in.pipelines.ao;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .accelerationStructure(1, in.scene.tlas.handle())
            .sampledImage(2, pc.image(gb.depth).view(), in.nearest.handle())
            .sampledImage(3, pc.image(gb.normals).view(), in.nearest.handle())
            .storageImage(4, pc.image(ao).view())
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        pipe.trace(pc.cmd, in.size.width, in.size.height);
      });
  return ao;
}

} // namespace rayster::render
