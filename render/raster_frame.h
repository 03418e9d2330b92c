#pragma once
// The raster frame (docs/architecture.md §5): the baseline, and the fallback on devices without
// ray-tracing pipelines. After the raster G-buffer: shadow maps (sun cascades, spot frusta, point
// light cubes) resolved with PCF into the visibility layers lighting reads, a first lighting pass,
// screen-space reflections and approximate refraction from that lit image, and the final lighting.
// No acceleration structure, no ray-tracing pipeline. TAA and tonemapping follow as in hybrid.
#include <cstdint>

#include "render/passes/raster_passes.h"
#include "render/shadow_setup.h"
#include "rhi/resources.h"
#include "scene/scene.h"

namespace rayster::render {

struct RasterFrameOutput {
  graph::ImageHandle hdr;         // linear radiance, before TAA
  graph::ImageHandle visibility;  // per shadowed light, from the shadow maps (R16F array)
  graph::ImageHandle specular;    // screen-space reflections and refraction (RGBA16F)
  graph::ImageHandle ao;          // constant 1 (no AO in raster mode)
  graph::ImageHandle indirect;    // constant 0 (ambient and SH environment light instead)
};

// What the raster frame leaves out (off means gone, docs/architecture.md §2.2): with no shadowed
// light (--shadows off) no shadow maps, without reflections (--reflections off) no screen-space
// reflections; lighting reads the neutral `white` visibility or `black` specular light instead.
struct RasterEffects {
  uint32_t shadowLights = 0;
  bool reflections = true;
  graph::ImageHandle white, black;
};

// Keeps what a frame's passes read after recording: the shadow layout and its uniform buffer
// (rewritten each frame; frames are serialised).
class RasterFrame {
 public:
  explicit RasterFrame(rhi::Context& ctx);
  RasterFrameOutput record(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                           const scene::Scene& scene, const scene::Camera& camera, const RasterEffects& effects);

 private:
  rhi::Buffer setup_;
  ShadowAtlas atlas_;
};

}  // namespace rayster::render
