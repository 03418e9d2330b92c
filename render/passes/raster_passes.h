#pragma once
// The passes only the raster mode uses (render/raster_frame.h wires them): shadow maps and their
// resolve into the visibility layers lighting reads, and screen-space reflections and refraction.
#include "render/passes/passes.h"

namespace rayster::render {

struct ShadowAtlas;

// Every shadow view of `atlas` rendered depth-only into its tile of one D32 atlas (reversed Z).
graph::ImageHandle renderShadowAtlas(graph::RenderGraph& graph, const FrameInputs& in, const ShadowAtlas& atlas);

// Per shadowed light, visibility from the shadow maps (PCF), in the layout of traceShadows()'s
// output: an R16F array with `lights` layers. `setup` holds gpu::ShadowSetup.
graph::ImageHandle resolveShadows(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                  graph::ImageHandle atlas, const rhi::Buffer& setup, uint32_t lights);

// Stand-ins for effects the raster mode does not compute: AO of 1 and a zero radiance image.
struct RasterConstants {
  graph::ImageHandle ao;    // R16F array, one layer, 1 everywhere
  graph::ImageHandle zero;  // RGBA16F, 0 everywhere
};
RasterConstants rasterConstants(graph::RenderGraph& graph, const FrameInputs& in);

// Screen-space reflections and approximate refraction from a lit image (RGBA16F, in the units of
// traceSpecular()'s output).
graph::ImageHandle screenSpaceSpecular(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                       graph::ImageHandle lit);

}  // namespace rayster::render
