#pragma once
// Temporal histories as graph resources (docs/architecture.md §2.5: never updated in place). A history
// is two images under one name that frames write alternately: frame f reads the one frame f − 1
// wrote and writes the other. The store keeps them across frames and owns their lifetime: a reset
// (the first frame of a run, a camera cut) empties every history, a new description (a resize, a
// format change) recreates one, and a history no frame asked for is released at the end of that
// frame, so an effect switched off keeps no memory.
#include <cstdint>
#include <map>
#include <string>

#include "graph/resource_state.h"
#include "rhi/resources.h"

namespace rayster::rhi {
class Context;
}

namespace rayster::graph {

class HistoryStore {
 public:
  // The frame about to be recorded: its index picks the image of each pair to read; `reset`
  // empties every history (no frame before this one counts).
  void beginFrame(uint32_t frame, bool reset);
  // The frame was recorded: what it wrote is history for the next one; histories it did not ask for
  // are released.
  void endFrame();
  // Frames accumulated in `name` before the current one (0: empty; what TAA and the path tracer's
  // running means need), and whether it exists at all.
  uint32_t frames(const std::string& name) const;
  void clear() { entries_.clear(); }
  // Memory the histories hold now (both images of every pair).
  uint64_t bytes() const;

 private:
  friend class RenderGraph;
  struct Entry {
    rhi::Image images[2];
    ResourceState states[2];
    uint32_t frames = 0;  // consecutive frames written, up to the last endFrame()
    bool used = false;    // asked for by the current frame
  };
  // The pair for `name` this frame, (re)created for `desc`.
  Entry& acquire(rhi::Context& ctx, const std::string& name, const rhi::ImageDesc& desc);
  std::map<std::string, Entry> entries_;
  uint32_t frame_ = 0;
};

}  // namespace rayster::graph
