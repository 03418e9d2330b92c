// The denoisers' shared pieces: their pipelines, history descriptions and the surface image.
#include <algorithm>
#include <span>

#include "render/passes/denoise.h"
#include "shaders/shared/denoise.h"

namespace rayster::render {
namespace {
constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkImageUsageFlags kHistoryUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
}  // namespace

rhi::ImageDesc surfaceDesc(VkExtent2D size) { return {kSurfaceFormat, size.width, size.height, 1, kHistoryUsage}; }
rhi::ImageDesc shadowHistoryDesc(VkExtent2D size, uint32_t lights) {
  return {kShadowHistoryFormat, size.width, size.height, std::max(lights, 1u) + 1, kHistoryUsage, true};
}
rhi::ImageDesc svgfColorHistoryDesc(VkExtent2D size) {
  return {kSvgfColorHistoryFormat, size.width, size.height, 1, kHistoryUsage};
}
rhi::ImageDesc svgfMomentsHistoryDesc(VkExtent2D size) {
  return {kSvgfMomentsHistoryFormat, size.width, size.height, 1, kHistoryUsage};
}

DenoisePipelines DenoisePipelines::create(rhi::Context& ctx) {
  DenoisePipelines p;
  const rhi::Binding surface[] = {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kStorage}, {4, kSampled}};
  p.surface = rhi::createComputePipeline(ctx, "surface.comp", surface, sizeof(gpu::SurfacePush));
  const rhi::Binding shadowTemporal[] = {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled},
                                         {4, kSampled}, {5, kStorage}, {6, kStorage}};
  p.shadowTemporal = rhi::createComputePipeline(ctx, "shadow_temporal.comp", shadowTemporal, sizeof(gpu::TemporalPush));
  const rhi::Binding shadowAtrous[] = {{0, kSampled}, {1, kSampled}, {2, kStorage}, {3, kSampled}};
  p.shadowAtrous = rhi::createComputePipeline(ctx, "shadow_atrous.comp", shadowAtrous, sizeof(gpu::AtrousPush));
  p.shadowAtrous2 = rhi::createComputePipeline(ctx, "shadow_atrous_2.comp", shadowAtrous, sizeof(gpu::AtrousPush));
  const rhi::Binding svgfTemporal[] = {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kSampled},
                                       {5, kSampled}, {6, kStorage}, {7, kStorage}, {8, kStorage}};
  p.svgfTemporal = rhi::createComputePipeline(ctx, "svgf_temporal.comp", svgfTemporal, sizeof(gpu::TemporalPush));
  const rhi::Binding svgfAtrous[] = {{0, kSampled}, {1, kSampled}, {2, kStorage}, {3, kStorage}};
  p.svgfAtrous = rhi::createComputePipeline(ctx, "svgf_atrous.comp", std::span(svgfAtrous, 3), sizeof(gpu::AtrousPush));
  p.svgfAtrousHistory =
      rhi::createComputePipeline(ctx, "svgf_atrous_history.comp", svgfAtrous, sizeof(gpu::AtrousPush));
  return p;
}

graph::ImageHandle writeSurface(graph::RenderGraph& graph, const DenoiseInputs& in, graph::ImageHandle depth,
                                graph::ImageHandle normals, graph::ImageHandle id, graph::ImageHandle material,
                                graph::ImageHandle out, float zNear, float zFar) {
  graph.addPass(
      "denoise-surface",
      [&](graph::PassBuilder& b) {
        for (auto h : {depth, normals, id, material}) b.read(h, graph::Use::SampledCompute);
        b.write(out, graph::Use::StorageWriteCompute);
      },
      [=](graph::PassContext& pc) {
        const rhi::Pipeline& pipe = in.pipelines.surface;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        rhi::DescriptorWriter()
            .sampledImage(0, pc.image(depth).view(), in.nearest)
            .sampledImage(1, pc.image(normals).view(), in.nearest)
            .sampledImage(2, pc.image(id).view(), in.nearest)
            .storageImage(3, pc.image(out).view())
            .sampledImage(4, pc.image(material).view(), in.nearest)
            .push(pc.cmd, pipe);
        const gpu::SurfacePush push{{in.size.width, in.size.height}, zNear, zFar};
        vkCmdPushConstants(pc.cmd, pipe.layout(), pipe.stages(), 0, sizeof(push), &push);
        vkCmdDispatch(pc.cmd, (in.size.width + 7) / 8, (in.size.height + 7) / 8, 1);
      });
  return out;
}

}  // namespace rayster::render
