// Pass 2: ray-traced soft shadows from the G-buffer (denoised in denoise_shadows.cpp).
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle traceShadows(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t lights,
                                uint32_t extraLayers) {
  const uint32_t layers = std::max(lights + extraLayers, 1u);
  graph::ImageHandle vis = graph.createImage(
      "shadow-raw", {kVisibilityFormat, in.size.width, in.size.height, layers,
                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, true});
  const rhi::RayTracingPipeline& pipe = in.pipelines.rayTracing("shadows.rgen", [] {
    rhi::RayTracingPipelineDesc d;
    d.raygen = "shadows.rgen";
    d.miss = {"shadow.rmiss"};
    d.hitGroups = shadowHitGroups();
    return d;
  });
  graph.addPass(
      "rt-shadows",
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe).bind("tlas", in.tlas).bind("depthTex", gb.depth).bind("normalTex", gb.normals);
        b.bind("outVisibility", vis);
        b.rays(uint64_t(in.size.width) * in.size.height * lights);  // one per pixel and light; none on the sky
      },
      [&pipe, lights, size = in.size](graph::PassContext& pc) {
        if (lights > 0) pipe.trace(pc.cmd, size.width, size.height, lights);
      });
  return vis;
}

}  // namespace rayster::render
