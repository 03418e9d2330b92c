// Pass 6b: one-bounce ray-traced indirect diffuse from the G-buffer (RGBA16F irradiance, 1 sample
// per pixel). At quarter rate (--indirect-rate quarter) a (w+1)/2 × (h+1)/2 launch traces one pixel
// of each 2×2 block, rotating over 4 frames (lib/indirect_ray.glsl), and "rt-indirect-fill"
// (indirect_fill.comp) fills the block's other pixels in place from traced neighbours.
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

VkExtent2D indirectLaunchSize(VkExtent2D size, bool quarter) {
  const uint32_t shift = quarter ? 1u : 0u;  // one invocation per 2×2 block
  return {(size.width + shift) >> shift, (size.height + shift) >> shift};
}
uint64_t indirectLaunch(VkExtent2D size, bool quarter) {
  const VkExtent2D l = indirectLaunchSize(size, quarter);
  return uint64_t(l.width) * l.height;
}

graph::ImageHandle traceIndirect(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                 graph::ImageHandle surface, bool quarter) {
  graph::ImageHandle out = graph.createImage(
      "indirect-raw", {kRadianceFormat, in.size.width, in.size.height, 1,
                       VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
      kRadianceImage);
  graph.addPass(
      "rt-indirect",
      [&](graph::PassBuilder& b) {
        b.read(gb.depth, graph::Use::SampledRayTracing);
        b.read(gb.normals, graph::Use::SampledRayTracing);
        b.write(out, graph::Use::StorageWriteRayTracing);
        b.rays(indirectLaunch(in.size, quarter) * 2);  // a bounce ray and a shadow ray at its hit
      },
      [gb, out, quarter, &in](graph::PassContext& pc) {
        const rhi::RayTracingPipeline& pipe = in.pipelines.indirect;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .accelerationStructure(1, in.scene.tlas.handle())
            .sampledImage(2, pc.image(gb.depth).view(), in.nearest.handle())
            .sampledImage(3, pc.image(gb.normals).view(), in.nearest.handle())
            .storageImage(4, pc.image(out).view())
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        const VkExtent2D launch = indirectLaunchSize(in.size, quarter);
        pipe.trace(pc.cmd, launch.width, launch.height);
      });
  if (!quarter) return out;
  graph.addPass(
      "rt-indirect-fill",
      [&](graph::PassBuilder& b) {
        b.read(surface, graph::Use::SampledCompute);
        b.write(out, graph::Use::StorageReadWriteCompute);
      },
      [surface, out, &in](graph::PassContext& pc) {
        const rhi::Pipeline& pipe = in.pipelines.indirectFill;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .storageImage(1, pc.image(out).view())
            .sampledImage(2, pc.image(surface).view(), in.nearest.handle())
            .push(pc.cmd, pipe);
        vkCmdDispatch(pc.cmd, (in.size.width + 7) / 8, (in.size.height + 7) / 8, 1);
      });
  return out;
}

} // namespace rayster::render
