#include "render/raster_frame.h"

#include <cstring>

#include "render/gpu_scene.h"
#include "render/pipelines.h"
#include "rhi/context.h"
#include "rhi/memory.h"

namespace rayster::render {

RasterFrame::RasterFrame(rhi::Context& ctx)
    : setup_(ctx, sizeof(gpu::ShadowSetup), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, rhi::MemoryUsage::Upload,
             "shadow-setup") {}

RasterFrameOutput RasterFrame::record(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                      const scene::Scene& scene, const scene::Camera& camera,
                                      const RasterEffects& effects) {
  RasterFrameOutput out;
  out.visibility = effects.white;
  if (effects.shadowLights > 0) {
    atlas_ = planShadowAtlas(scene, in.scene.bounds, camera, float(in.size.width) / float(in.size.height),
                             effects.shadowLights);
    std::memcpy(setup_.mapped(), &atlas_.setup, sizeof(atlas_.setup));
    const graph::ImageHandle atlas = renderShadowAtlas(graph, in, atlas_);
    out.visibility = resolveShadows(graph, in, gb, atlas, setup_, effects.shadowLights);
  }
  const RasterConstants constants = rasterConstants(graph, in);
  out.ao = constants.ao;
  out.indirect = constants.zero;
  out.specular = effects.black;
  if (effects.reflections) {
    // Lit without specular light: what reflections and refractions see.
    const graph::ImageHandle lit = shadeLighting(
        graph, in, gb, {out.visibility, constants.zero, constants.ao, constants.zero, {}}, "lighting-direct");
    out.specular = screenSpaceSpecular(graph, in, gb, lit);
  }
  out.hdr = shadeLighting(graph, in, gb, {out.visibility, out.specular, constants.ao, constants.zero, {}});
  return out;
}

}  // namespace rayster::render
