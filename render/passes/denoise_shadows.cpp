// Pass 3: the shadow denoiser (docs/techniques.md §11). Temporal running mean per light with
// reprojection and disocclusion tests, then edge-aware à-trous at steps 1, 2, 4 (depth, normal and
// variance-normalised value weights).
#include "render/passes/denoise.h"
#include "shaders/shared/denoise.h"

namespace rayster::render {
namespace {
uint32_t temporalFlags(TemporalState s) {
  return (s.moving ? gpu::kDenoiseMoving : 0u) | (s.reset ? gpu::kDenoiseReset : 0u);
}
}  // namespace

ShadowDenoised shadowTemporal(graph::RenderGraph& graph, const DenoiseInputs& in, SurfacePair surface,
                              graph::ImageHandle motion, graph::ImageHandle raw, HistoryPair history, uint32_t lights,
                              TemporalState state, const std::string& name) {
  const graph::ImageHandle variance = createShadowImage(graph, in.size, lights, name + "-variance");
  graph.addPass(
      name + "-temporal",
      [&](graph::PassBuilder& b) {
        const VkSampler n = in.nearest;
        b.pipeline(in.pipelines.compute("shadow_temporal.comp"));
        b.bind("surfaceTex", surface.current, n)
            .bind("prevSurfaceTex", surface.previous, n)
            .bind("motionTex", motion, n);
        b.bind("rawTex", raw, n).bind("historyTex", history.previous, n);
        b.bind("outHistory", history.next).bind("outVariance", variance);
      },
      [size = in.size, lights, state](graph::PassContext& pc) {
        pc.push(gpu::TemporalPush{
            {size.width, size.height}, lights, temporalFlags(state), 1.0f, 0u});  // visibility: no units
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return {history.next, variance, {}};
}

graph::ImageHandle createShadowImage(graph::RenderGraph& graph, VkExtent2D size, uint32_t lights,
                                     const std::string& name) {
  return graph.createImage(
      name, {kShadowDenoisedFormat, size.width, size.height, std::max(lights, 1u),
             VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, true});
}

graph::ImageHandle shadowAtrous(graph::RenderGraph& graph, const DenoiseInputs& in, graph::ImageHandle surface,
                                graph::ImageHandle input, graph::ImageHandle variance, graph::ImageHandle out,
                                uint32_t lights, uint32_t step, const std::string& name) {
  graph.addPass(
      name + "-atrous-" + std::to_string(step),
      [&](graph::PassBuilder& b) {
        const VkSampler n = in.nearest;
        b.pipeline(
            in.pipelines.compute(lights <= kShadowAtrousSmallLayers ? "shadow_atrous_2.comp" : "shadow_atrous.comp"));
        b.bind("surfaceTex", surface, n).bind("inputTex", input, n).bind("varianceTex", variance, n);
        b.bind("outVisibility", out);
      },
      [size = in.size, lights, step](graph::PassContext& pc) {
        pc.push(gpu::AtrousPush{{size.width, size.height}, lights, step, 0, 0, 0, 0});
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return out;
}

ShadowDenoised denoiseShadows(graph::RenderGraph& graph, const DenoiseInputs& in, SurfacePair surface,
                              graph::ImageHandle motion, graph::ImageHandle raw, HistoryPair history,
                              TemporalState state, const std::string& name) {
  const uint32_t lights = std::min(graph.imageDesc(raw).layers, gpu::kMaxShadowDenoiseLayers);
  ShadowDenoised out = shadowTemporal(graph, in, surface, motion, raw, history, lights, state, name);
  // Ping-pong between two transients; the last iteration writes "<name>-denoised".
  const graph::ImageHandle work[2] = {createShadowImage(graph, in.size, lights, name + "-atrous"),
                                      createShadowImage(graph, in.size, lights, name + "-denoised")};
  graph::ImageHandle input = out.temporal;
  for (uint32_t i = 0; i < gpu::kShadowAtrousIterations; ++i) {
    const uint32_t left = gpu::kShadowAtrousIterations - 1 - i;  // the last one lands in work[1]
    input = shadowAtrous(graph, in, surface.current, input, out.variance, work[(left + 1) % 2], lights, 1u << i, name);
  }
  out.denoised = input;
  return out;
}

}  // namespace rayster::render
