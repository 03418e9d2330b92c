// Pass 6b: one-bounce ray-traced indirect diffuse from the G-buffer (RGBA16F irradiance, 1 sample
// per pixel). At quarter rate (--indirect-rate quarter) a (w+1)/2 × (h+1)/2 launch traces one pixel
// of each 2×2 block, rotating over 4 frames (lib/indirect_ray.glsl), and "rt-indirect-fill"
// (indirect_fill.comp) fills the block's other pixels in place from traced neighbours.
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
                                 graph::ImageHandle surface, bool quarter, const ProbeLookup& probes) {
  graph::ImageHandle out =
      graph.createImage("indirect-raw",
                        {kRadianceFormat, in.size.width, in.size.height, 1,
                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
                        kRadianceImage);
  const rhi::RayTracingPipeline& pipe = in.pipelines.rayTracing("indirect.rgen", [] {
    rhi::RayTracingPipelineDesc d;
    d.raygen = "indirect.rgen";
    d.miss = {"primary.rmiss", "shadow.rmiss"};  // radiance rays miss 0, shadow rays miss 1
    d.hitGroups = radianceHitGroups();
    return d;
  });
  const VkExtent2D launch = indirectLaunchSize(in.size, quarter);
  graph.addPass(
      "rt-indirect",
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe).bind("tlas", in.tlas).bind("depthTex", gb.depth).bind("normalTex", gb.normals);
        b.bind("outIndirect", out);
        // Without probes any image stands in (kProbeLookup unset: never read).
        const bool lookup = probes.irradiance.valid();
        b.bind("probeIrradianceTex", lookup ? probes.irradiance : gb.albedo, in.linear.handle());
        b.bind("probeVisibilityTex", lookup ? probes.visibility : gb.material, in.linear.handle());
        b.bind("probeDataTex", lookup ? probes.data : gb.material);
        b.rays(indirectLaunch(in.size, quarter) * 2);  // a bounce ray and a shadow ray at its hit
      },
      [&pipe, launch, grid = probes.grid](graph::PassContext& pc) {
        pc.push(grid);
        pipe.trace(pc.cmd, launch.width, launch.height);
      });
  if (!quarter) return out;
  const rhi::Pipeline& fill = in.pipelines.compute("indirect_fill.comp");
  graph.addPass(
      "rt-indirect-fill",
      [&](graph::PassBuilder& b) { b.pipeline(fill).bind("indirect", out).bind("surfaceTex", surface); },
      [size = in.size](graph::PassContext& pc) {
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return out;
}

}  // namespace rayster::render
