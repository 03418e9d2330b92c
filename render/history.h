#pragma once
// A temporal history: two images written alternately, so no dispatch reads and writes one image
// (docs/architecture.md §2.5: never update a history in place). Owned by the renderer across frames and
// imported into each frame's graph.
#include <string>

#include "graph/graph.h"
#include "rhi/resources.h"

namespace rayster::render {

struct History {
  rhi::Image images[2];
  graph::ResourceState states[2];
  bool valid = false;  // false until a frame has written it, and again after a reset (cut, resize)

  // (Re)creates both images when the description changes; a new image holds no history.
  void ensure(rhi::Context& ctx, const rhi::ImageDesc& desc, const std::string& name) {
    for (int i = 0; i < 2; ++i) {
      if (images[i] && images[i].desc() == desc) continue;
      images[i] = rhi::Image(ctx, desc, (name + "-" + std::to_string(i)).c_str());
      states[i] = {};
      valid = false;
    }
  }
  // Frame f reads image f % 2 and writes the other.
  graph::ImageHandle previous(graph::RenderGraph& g, const std::string& name, uint32_t f) {
    return g.importImage(name + "-prev", &images[f % 2], &states[f % 2]);
  }
  graph::ImageHandle next(graph::RenderGraph& g, const std::string& name, uint32_t f) {
    return g.importImage(name, &images[(f + 1) % 2], &states[(f + 1) % 2]);
  }
};

} // namespace rayster::render
