// Pass 2b: many-light direct lighting, one importance-picked light and one shadow ray per pixel.
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle traceDirect(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb) {
  graph::ImageHandle out =
      graph.createImage("direct-raw",
                        {kRadianceFormat, in.size.width, in.size.height, 1,
                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
                        kRadianceImage);
  const rhi::RayTracingPipeline& pipe = in.pipelines.rayTracing("direct.rgen", [] {
    rhi::RayTracingPipelineDesc d;
    d.raygen = "direct.rgen";
    d.miss = {"shadow.rmiss"};
    d.hitGroups = shadowHitGroups();
    return d;
  });
  graph.addPass(
      "rt-direct",
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe).bind("tlas", in.tlas);
        bindSurface(b, gb);
        b.bind("outDirect", out);
        b.rays(uint64_t(in.size.width) * in.size.height);  // one shadow ray to the picked light per pixel
      },
      [&pipe, size = in.size](graph::PassContext& pc) { pipe.trace(pc.cmd, size.width, size.height); });
  return out;
}

}  // namespace rayster::render
