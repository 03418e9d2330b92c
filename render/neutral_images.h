#pragma once
// What lighting reads in place of an effect that records no pass (docs/architecture.md §2.2, "off means
// gone"): AO switched off is unoccluded (1), no shadowed light needs no visibility, and no
// reflections, indirect or many-light direct light add nothing (0), and a scene without clear coats
// or sheens has no layers to store (0). One texel each, cleared once
// when the renderer is made, imported into every frame's graph (so the graph still tracks their
// state and the memory report lists them); no frame allocates an image or records a pass for them.
#include "graph/graph.h"
#include "render/passes/passes.h"
#include "rhi/resources.h"

namespace rayster::rhi {
class Context;
}

namespace rayster::render {

class NeutralImages {
 public:
  explicit NeutralImages(rhi::Context& ctx);
  // A one-layer visibility array holding 1: unoccluded, fully lit.
  graph::ImageHandle white(graph::RenderGraph& graph) {
    return graph.importImage("neutral-white", &white_, &whiteState_);
  }
  // Radiance 0 (RGBA16F): no light.
  graph::ImageHandle black(graph::RenderGraph& graph) {
    return graph.importImage("neutral-black", &black_, &blackState_, kRadianceImage);
  }
  // Zeros (RGBA32UI): the G-buffer's layers target where no material has a clear coat or sheen
  // (GBuffer::flatLayers).
  graph::ImageHandle layers(graph::RenderGraph& graph) {
    return graph.importImage("neutral-layers", &layers_, &layersState_);
  }
  // Whether `image` is one of these (an AOV of it is the constant broadcast to the frame).
  bool holds(const rhi::Image& image) const { return &image == &white_ || &image == &black_ || &image == &layers_; }

 private:
  rhi::Image white_, black_, layers_;
  graph::ResourceState whiteState_, blackState_, layersState_;
};

}  // namespace rayster::render
