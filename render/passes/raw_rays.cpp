// Raw ray rates (rayster bench --raw-rays): the primary and shadow rays of the frame traced again
// with trivial shaders into scratch images, so each pass can report the share of the device's raw
// ray rate it reaches (its rays are the same; only shading and memory traffic differ).
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

namespace {
// Results nobody reads: a side effect keeps the graph from culling the pass.
constexpr VkImageUsageFlags kScratchUsage = VK_IMAGE_USAGE_STORAGE_BIT;
}  // namespace

void traceRawPrimary(graph::RenderGraph& graph, const FrameInputs& in, const RawRayPipelines& raw) {
  graph::ImageHandle hit =
      graph.createImage("raw-primary-hit", {kVisibilityFormat, in.size.width, in.size.height, 1, kScratchUsage});
  graph.addPass(
      "raw-gbuffer-traced",
      [&](graph::PassBuilder& b) {
        b.write(hit, graph::Use::StorageWriteRayTracing);
        b.sideEffect();
      },
      [hit, &in, &raw](graph::PassContext& pc) {
        const rhi::RayTracingPipeline& pipe = raw.primary;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .accelerationStructure(1, in.scene.tlas.handle())
            .storageImage(2, pc.image(hit).view())
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        pipe.trace(pc.cmd, in.size.width, in.size.height);
      });
}

void traceRawShadows(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t lights,
                     const RawRayPipelines& raw) {
  if (lights == 0) return;  // many-light mode: the shadow pass traces nothing either
  graph::ImageHandle vis = graph.createImage(
      "raw-shadow-visibility", {kVisibilityFormat, in.size.width, in.size.height, lights, kScratchUsage, true});
  graph.addPass(
      "raw-rt-shadows",
      [&](graph::PassBuilder& b) {
        b.read(gb.depth, graph::Use::SampledRayTracing);
        b.read(gb.normals, graph::Use::SampledRayTracing);
        b.write(vis, graph::Use::StorageWriteRayTracing);
        b.sideEffect();
      },
      [gb, vis, lights, &in, &raw](graph::PassContext& pc) {
        const rhi::RayTracingPipeline& pipe = raw.shadows;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.handle());
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .accelerationStructure(1, in.scene.tlas.handle())
            .sampledImage(2, pc.image(gb.depth).view(), in.nearest.handle())
            .sampledImage(3, pc.image(gb.normals).view(), in.nearest.handle())
            .storageImage(4, pc.image(vis).view())
            .push(pc.cmd, pipe);
        bindTextures(pc.cmd, in, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipe.layout());
        pipe.trace(pc.cmd, in.size.width, in.size.height, lights);
      });
}

}  // namespace rayster::render
