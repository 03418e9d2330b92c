// The denoisers' shared pieces: history descriptions and the surface image.
#include <algorithm>

#include "render/passes/denoise.h"
#include "shaders/shared/denoise.h"

namespace rayster::render {
namespace {
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

graph::ImageHandle writeSurface(graph::RenderGraph& graph, const DenoiseInputs& in, graph::ImageHandle depth,
                                graph::ImageHandle normals, graph::ImageHandle id, graph::ImageHandle material,
                                graph::ImageHandle out, float zNear, float zFar) {
  graph.addPass(
      "denoise-surface",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("surface.comp"));
        b.bind("depthTex", depth, in.nearest).bind("normalTex", normals, in.nearest).bind("idTex", id, in.nearest);
        b.bind("materialTex", material, in.nearest).bind("outSurface", out);
      },
      [size = in.size, zNear, zFar](graph::PassContext& pc) {
        pc.push(gpu::SurfacePush{{size.width, size.height}, zNear, zFar});
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return out;
}

}  // namespace rayster::render
