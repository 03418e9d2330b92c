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
void dispatch(VkCommandBuffer cmd, const rhi::Pipeline& pipe, VkExtent2D size, const void* push, uint32_t bytes) {
  vkCmdPushConstants(cmd, pipe.layout(), pipe.stages(), 0, bytes, push);
  vkCmdDispatch(cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
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
        for (auto h : {surface.current, surface.previous, motion, raw, color.previous, moments.previous})
          b.read(h, graph::Use::SampledCompute);
        for (auto h : {color.next, moments.next, out}) b.write(h, graph::Use::StorageWriteCompute);
      },
      [=](graph::PassContext& pc) {
        const rhi::Pipeline& pipe = in.pipelines.svgfTemporal;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        rhi::DescriptorWriter()
            .sampledImage(0, pc.image(surface.current).view(), in.nearest)
            .sampledImage(1, pc.image(surface.previous).view(), in.nearest)
            .sampledImage(2, pc.image(motion).view(), in.nearest)
            .sampledImage(3, pc.image(raw).view(), in.nearest)
            .sampledImage(4, pc.image(color.previous).view(), in.nearest)
            .sampledImage(5, pc.image(moments.previous).view(), in.nearest)
            .storageImage(6, pc.image(color.next).view())
            .storageImage(7, pc.image(moments.next).view())
            .storageImage(8, pc.image(out).view())
            .push(pc.cmd, pipe);
        const gpu::TemporalPush push{{in.size.width, in.size.height}, 1, temporalFlags(state)};
        dispatch(pc.cmd, pipe, in.size, &push, sizeof(push));
      });
  return out;
}

graph::ImageHandle svgfAtrous(graph::RenderGraph& graph, const DenoiseInputs& in, const std::string& name,
                              graph::ImageHandle surface, graph::ImageHandle input, graph::ImageHandle output,
                              uint32_t step, graph::ImageHandle history) {
  graph.addPass(
      name + "-atrous-" + std::to_string(step),
      [&](graph::PassBuilder& b) {
        for (auto h : {surface, input}) b.read(h, graph::Use::SampledCompute);
        b.write(output, graph::Use::StorageWriteCompute);
        if (history.valid()) b.write(history, graph::Use::StorageReadWriteCompute);  // keeps its a (n)
      },
      [=](graph::PassContext& pc) {
        const rhi::Pipeline& pipe = history.valid() ? in.pipelines.svgfAtrousHistory : in.pipelines.svgfAtrous;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        rhi::DescriptorWriter w;
        w.sampledImage(0, pc.image(surface).view(), in.nearest)
            .sampledImage(1, pc.image(input).view(), in.nearest)
            .storageImage(2, pc.image(output).view());
        if (history.valid()) w.storageImage(3, pc.image(history).view());
        w.push(pc.cmd, pipe);
        const gpu::AtrousPush push{{in.size.width, in.size.height}, 1, step, 0, 0, 0, 0};
        dispatch(pc.cmd, pipe, in.size, &push, sizeof(push));
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
