// Pass 6a: ray-traced ambient occlusion from the G-buffer (one layer of R16F, 1 sample per pixel).
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

// AO rays are shadow rays of another length: the shadow pass's miss and hit groups.
const rhi::RayTracingPipeline& aoPipeline(rhi::PipelineLibrary& lib) {
  return lib.rayTracing("ao.rgen", [] {
    rhi::RayTracingPipelineDesc d;
    d.raygen = "ao.rgen";
    d.miss = {"shadow.rmiss"};
    d.hitGroups = shadowHitGroups();
    return d;
  });
}

graph::ImageHandle traceAo(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                           graph::ImageHandle into) {
  // A layer of an array image, so the shadow denoiser takes it unchanged: the shadow image's AO
  // layer (one denoiser run for lights and AO), or an image of its own.
  graph::ImageHandle ao = into.valid()
                              ? into
                              : graph.createImage("ao-raw", {kVisibilityFormat, in.size.width, in.size.height, 1,
                                                             VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                                                 VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                                             true});
  const rhi::RayTracingPipeline& pipe = aoPipeline(in.pipelines);
  graph.addPass(
      "rt-ao",
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe)
            .bind("tlas", in.tlas)
            .bind("depthTex", gb.depth)
            .bind("normalTex", gb.normals)
            .bind("outAo", ao);
        b.rays(uint64_t(in.size.width) * in.size.height);  // one occlusion ray per pixel; none on the sky
      },
      [&pipe, size = in.size](graph::PassContext& pc) { pipe.trace(pc.cmd, size.width, size.height); });
  return ao;
}

}  // namespace rayster::render
