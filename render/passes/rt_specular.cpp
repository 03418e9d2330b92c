// Pass 4: ray-traced reflections and refractions (the raygen bounce loop); denoised by SVGF
// (denoise_svgf.cpp). Rough glossy reflections trace half the pixels per frame in a checkerboard
// (lib/specular_weight.glsl); "rt-specular-fill" fills the other half from their neighbours, in place
// (recorded only where some surface is that rough: Renderer::Impl::specularFillOn).
#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

graph::ImageHandle traceSpecular(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb, uint32_t bounces,
                                 uint32_t lightsPerHit, bool halfRateFill, const ProbeLookup& probes) {
  graph::ImageHandle out =
      graph.createImage("specular-raw",
                        {kRadianceFormat, in.size.width, in.size.height, 1,
                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
                        kRadianceImage);
  const rhi::RayTracingPipeline& pipe = in.pipelines.rayTracing("specular.rgen", [] {
    rhi::RayTracingPipelineDesc d;
    d.raygen = "specular.rgen";
    d.miss = {"primary.rmiss", "shadow.rmiss"};  // radiance rays miss 0, shadow rays miss 1
    d.hitGroups = radianceHitGroups();
    return d;
  });
  graph.addPass(
      "rt-specular",
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe).bind("tlas", in.tlas);
        bindSurface(b, gb);
        b.bind("outSpecular", out);
        // Without probes any image stands in (kProbeLookup unset: never read).
        const bool lookup = probes.irradiance.valid();
        b.bind("probeIrradianceTex", lookup ? probes.irradiance : gb.albedo, in.linear.handle());
        b.bind("probeVisibilityTex", lookup ? probes.visibility : gb.material, in.linear.handle());
        b.bind("probeDataTex", lookup ? probes.data : gb.material);
        // Per pixel and bounce a ray and a shadow ray per light shaded at its hit: a bound, since
        // most pixels are not specular and most paths end after a bounce.
        b.rays(uint64_t(in.size.width) * in.size.height * bounces * (1u + lightsPerHit));
      },
      [&pipe, grid = probes.grid, size = in.size](graph::PassContext& pc) {
        pc.push(grid);
        pipe.trace(pc.cmd, size.width, size.height);
      });
  if (!halfRateFill) return out;  // nothing traced at half rate: nothing to fill
  const rhi::Pipeline& fill = in.pipelines.compute("specular_fill.comp");
  graph.addPass(
      "rt-specular-fill",
      [&](graph::PassBuilder& b) {
        b.pipeline(fill).bind("specular", out).bind("depthTex", gb.depth).bind("materialTex", gb.material);
      },
      [size = in.size](graph::PassContext& pc) {
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return out;
}

}  // namespace rayster::render
