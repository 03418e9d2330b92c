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
        for (auto h : {surface.current, surface.previous, motion, raw, history.previous})
          b.read(h, graph::Use::SampledCompute);
        b.write(history.next, graph::Use::StorageWriteCompute);
        b.write(variance, graph::Use::StorageWriteCompute);
      },
      [=](graph::PassContext& pc) {
        const rhi::Pipeline& pipe = in.pipelines.shadowTemporal;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        rhi::DescriptorWriter()
            .sampledImage(0, pc.image(surface.current).view(), in.nearest)
            .sampledImage(1, pc.image(surface.previous).view(), in.nearest)
            .sampledImage(2, pc.image(motion).view(), in.nearest)
            .sampledImage(3, pc.image(raw).view(), in.nearest)
            .sampledImage(4, pc.image(history.previous).view(), in.nearest)
            .storageImage(5, pc.image(history.next).view())
            .storageImage(6, pc.image(variance).view())
            .push(pc.cmd, pipe);
        const gpu::TemporalPush push{{in.size.width, in.size.height}, lights, temporalFlags(state)};
        vkCmdPushConstants(pc.cmd, pipe.layout(), pipe.stages(), 0, sizeof(push), &push);
        vkCmdDispatch(pc.cmd, (in.size.width + 7) / 8, (in.size.height + 7) / 8, 1);
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
        b.read(surface, graph::Use::SampledCompute);
        b.read(input, graph::Use::SampledCompute);
        b.read(variance, graph::Use::SampledCompute);
        b.write(out, graph::Use::StorageWriteCompute);
      },
      [=](graph::PassContext& pc) {
        const rhi::Pipeline& pipe =
            lights <= kShadowAtrousSmallLayers ? in.pipelines.shadowAtrous2 : in.pipelines.shadowAtrous;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        rhi::DescriptorWriter()
            .sampledImage(0, pc.image(surface).view(), in.nearest)
            .sampledImage(1, pc.image(input).view(), in.nearest)
            .storageImage(2, pc.image(out).view())
            .sampledImage(3, pc.image(variance).view(), in.nearest)
            .push(pc.cmd, pipe);
        const gpu::AtrousPush push{{in.size.width, in.size.height}, lights, step, 0, 0, 0, 0};
        vkCmdPushConstants(pc.cmd, pipe.layout(), pipe.stages(), 0, sizeof(push), &push);
        vkCmdDispatch(pc.cmd, (in.size.width + 7) / 8, (in.size.height + 7) / 8, 1);
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
