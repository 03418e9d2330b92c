// Pass 5: SVGF for radiance signals (docs/techniques.md §14): temporal integration of colour and
// luminance moments with the variance estimate in the same pass, 5 edge-aware à-trous iterations
// at steps 1 .. 16: 6 dispatches.
#include "render/passes/denoise.h"
#include "render/passes/passes.h"
#include "shaders/shared/denoise.h"

namespace rayster::render {
namespace {
uint32_t temporalFlags(TemporalState s) {
  return (s.moving ? gpu::kDenoiseMoving : 0u) | (s.reset ? gpu::kDenoiseReset : 0u);
}
template <class Push>
void dispatch(graph::PassContext& pc, VkExtent2D size, const Push& push) {
  pc.push(push);
  vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
}
}  // namespace

graph::ImageHandle createSvgfImage(graph::RenderGraph& graph, VkExtent2D size, const std::string& name) {
  return graph.createImage(name,
                           {kSvgfWorkingFormat, size.width, size.height, 1,
                            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
                           kRadianceImage);
}

graph::ImageHandle svgfTemporal(graph::RenderGraph& graph, const DenoiseInputs& in, const std::string& name,
                                SurfacePair surface, graph::ImageHandle motion, graph::ImageHandle raw,
                                HistoryPair color, HistoryPair moments, graph::ImageHandle out, TemporalState state) {
  graph.addPass(
      name + "-temporal",
      [&](graph::PassBuilder& b) {
        const VkSampler n = in.nearest;
        b.pipeline(in.pipelines.compute("svgf_temporal.comp"));
        b.bind("surfaceTex", surface.current, n)
            .bind("prevSurfaceTex", surface.previous, n)
            .bind("motionTex", motion, n);
        b.bind("rawTex", raw, n)
            .bind("colorHistoryTex", color.previous, n)
            .bind("momentsHistoryTex", moments.previous, n);
        b.bind("outColor", color.next).bind("outMoments", moments.next).bind("outColorVariance", out);
      },
      [size = in.size, state](graph::PassContext& pc) {
        dispatch(pc, size,
                 gpu::TemporalPush{{size.width, size.height}, 1, temporalFlags(state), state.historyScale, 0u});
      });
  return out;
}

graph::ImageHandle svgfAtrous(graph::RenderGraph& graph, const DenoiseInputs& in, const std::string& name,
                              graph::ImageHandle surface, graph::ImageHandle input, graph::ImageHandle output,
                              uint32_t step, graph::ImageHandle history) {
  graph.addPass(
      name + "-atrous-" + std::to_string(step),
      [&](graph::PassBuilder& b) {
        const VkSampler n = in.nearest;
        b.pipeline(in.pipelines.compute(history.valid() ? "svgf_atrous_history.comp" : "svgf_atrous.comp"));
        b.bind("surfaceTex", surface, n).bind("inputTex", input, n).bind("outColorVariance", output);
        if (history.valid()) b.bind("outHistory", history);  // read-write: keeps its a (n)
      },
      [size = in.size, step](graph::PassContext& pc) {
        dispatch(pc, size, gpu::AtrousPush{{size.width, size.height}, 1, step, 0, 0, 0, 0});
      });
  return output;
}

RadianceDenoised denoiseRadiance(graph::RenderGraph& graph, const DenoiseInputs& in, const std::string& name,
                                 SurfacePair surface, graph::ImageHandle motion, graph::ImageHandle raw,
                                 HistoryPair color, HistoryPair moments, TemporalState state) {
  RadianceDenoised out;
  // Two working images: the temporal pass writes the first, the iterations ping-pong between them.
  const graph::ImageHandle work[2] = {createSvgfImage(graph, in.size, name + "-atrous"),
                                      createSvgfImage(graph, in.size, name + "-denoised")};
  static_assert(gpu::kSvgfAtrousIterations % 2 == 1, "the last iteration must land in work[1]");
  out.variance = svgfTemporal(graph, in, name, surface, motion, raw, color, moments, work[0], state);
  out.temporal = color.next;
  out.moments = moments.next;
  graph::ImageHandle input = out.variance;
  for (uint32_t i = 0; i < gpu::kSvgfAtrousIterations; ++i) {
    const uint32_t left = gpu::kSvgfAtrousIterations - 1 - i;  // the last one lands in work[1]
    // Iteration 1's output is the colour history (SVGF paper) while moving; a static camera keeps
    // the exact running mean the temporal pass wrote, so the still frame converges to the truth.
    const graph::ImageHandle history = i == 0 && state.moving ? color.next : graph::ImageHandle{};
    input = svgfAtrous(graph, in, name, surface.current, input, work[(left + 1) % 2], 1u << i, history);
  }
  out.denoised = input;
  return out;
}

}  // namespace rayster::render
