// The path tracer's one pass: one path per pixel (shaders/pathtrace.rgen.glsl), folded into the
// running mean and mean square of the previous frames (fp32 histories, never updated in place).
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle tracePaths(graph::RenderGraph& graph, const FrameInputs& in, const PathAccumulation& acc) {
  const rhi::RayTracingPipeline& pipe = in.pipelines.rayTracing("pathtrace.rgen", [] {
    rhi::RayTracingPipelineDesc d;
    d.raygen = "pathtrace.rgen";
    d.miss = {"primary.rmiss", "shadow.rmiss"};  // radiance rays miss 0, shadow rays miss 1
    d.hitGroups = radianceHitGroups();
    return d;
  });
  graph.addPass(
      "pathtrace",
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe).bind("tlas", in.tlas);
        b.bind("prevMean", acc.previousMean).bind("prevMoments", acc.previousMoments);
        b.bind("outMean", acc.mean).bind("outMoments", acc.moments);
      },
      [&pipe, size = in.size](graph::PassContext& pc) { pipe.trace(pc.cmd, size.width, size.height); });
  return acc.mean;
}

}  // namespace rayster::render
