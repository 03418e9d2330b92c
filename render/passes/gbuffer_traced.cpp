// Pass 1 (traced producer, --primary rt): primary rays write the same G-buffer as the rasteriser.
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

GBuffer createGBufferTargets(graph::RenderGraph& graph, const FrameInputs& in, bool traced,
                             graph::ImageHandle zeroLayers);

GBuffer traceGBuffer(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle zeroLayers) {
  GBuffer gb = createGBufferTargets(graph, in, true, zeroLayers);
  // Flat layers: the variant without the layers output (NO_LAYERS).
  const char* raygen = gb.flatLayers ? "gbuffer_flat.rgen" : "gbuffer.rgen";
  const rhi::RayTracingPipeline& pipe = in.pipelines.rayTracing(raygen, [raygen] {
    rhi::RayTracingPipelineDesc d;
    d.raygen = raygen;
    d.miss = {"primary.rmiss"};
    d.hitGroups = radianceHitGroups();
    return d;
  });
  graph.addPass(
      "gbuffer-traced",
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe).bind("tlas", in.tlas);
        b.bind("outDepth", gb.depth).bind("outNormals", gb.normals).bind("outAlbedo", gb.albedo);
        b.bind("outMaterial", gb.material).bind("outEmissive", gb.emissive).bind("outId", gb.id);
        b.bind("outMotion", gb.motion).bind("outSpecular", gb.specular);
        if (!gb.flatLayers) b.bind("outLayers", gb.layers);
        b.rays(uint64_t(in.size.width) * in.size.height, true);  // one primary ray per pixel, always traced
      },
      [&pipe, size = in.size](graph::PassContext& pc) { pipe.trace(pc.cmd, size.width, size.height); });
  return gb;
}

}  // namespace rayster::render
