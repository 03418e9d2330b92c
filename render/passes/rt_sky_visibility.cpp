// Sky visibility (--sky-visibility on, off by default): how much of each pixel's hemisphere sees
// the sky, ray traced (one unbounded cosine ray per pixel per frame, shaders/sky_visibility.rgen.glsl)
// and denoised by the shadow denoiser in the frame function. An output for compositing and
// look development (AOVs "sky-visibility-raw" and "sky-visibility-denoised"); it does not change the
// lit image. Added as docs/architecture.md §10 describes, in four files: this one, its shader, the
// frame function (recordHybrid) and its test.
#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "render/settings_table.h"

namespace rayster::render {
namespace {
const PassSetting kSwitch{passSwitch("sky-visibility", "Effects",
                                     "Ray-traced, denoised sky visibility as an output (AOV "
                                     "sky-visibility-denoised): the fraction of each pixel's hemisphere that sees "
                                     "the sky; the lit image is unchanged",
                                     false)};
}  // namespace

graph::ImageHandle traceSkyVisibility(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb) {
  const graph::ImageHandle out =
      graph.createImage("sky-visibility-raw", {kVisibilityFormat, in.size.width, in.size.height, 1,
                                               VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, true});
  // Visibility rays: the shadow rays' miss shader and hit groups.
  const rhi::RayTracingPipeline& pipe = in.pipelines.rayTracing("sky_visibility.rgen", [] {
    rhi::RayTracingPipelineDesc d;
    d.raygen = "sky_visibility.rgen";
    d.miss = {"shadow.rmiss"};
    d.hitGroups = shadowHitGroups();
    return d;
  });
  graph.addPass(
      "rt-sky-visibility",
      [&](graph::PassBuilder& b) {
        b.pipeline(pipe).bind("tlas", in.tlas).bind("depthTex", gb.depth).bind("normalTex", gb.normals);
        b.bind("outSkyVisibility", out);
        b.rays(uint64_t(in.size.width) * in.size.height);  // one per pixel; none on the sky
      },
      [&pipe, size = in.size](graph::PassContext& pc) { pipe.trace(pc.cmd, size.width, size.height); });
  return out;
}

}  // namespace rayster::render
