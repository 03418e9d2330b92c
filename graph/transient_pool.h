#pragma once
// The render graph's transient images and the frame's memory report (docs/architecture.md §2.4). The pool
// keeps a frame's transients alive between frames so a static configuration allocates once, and
// places them on shared memory heaps: images whose lifetimes within the frame do not overlap alias
// (graph/aliasing.h). Imported images (histories, outputs) are listed in the report, never aliased.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "graph/aliasing.h"
#include "rhi/resources.h"

namespace rayster::graph {

struct TransientRequest {
  std::string name;
  rhi::ImageDesc desc;
  uint32_t first = 0, last = 0;     // live-pass positions of the first and last use
  std::string firstPass, lastPass;  // their names, for the report
};

// One image of the last executed frame: a transient (placed on heap `heap` at `offset`) or an
// imported image (heap -1).
struct FrameMemoryEntry {
  std::string name;
  rhi::ImageDesc desc;
  uint64_t bytes = 0;  // the image's memory requirements
  bool imported = false;
  int32_t heap = -1;
  uint64_t offset = 0;
  std::string firstPass, lastPass;
};

// The frame resources: what one frame's graph needs besides the scene (G-buffer, targets,
// intermediates, histories), as allocated for the last executed graph.
struct FrameMemoryReport {
  std::vector<FrameMemoryEntry> entries;
  uint64_t transientBytes = 0;           // the transients' heaps, with aliasing
  uint64_t transientUnaliasedBytes = 0;  // the transients' sizes summed: one image each, no aliasing
  uint64_t importedBytes = 0;            // distinct imported images (histories, presented output)
  uint64_t frameBytes() const { return transientBytes + importedBytes; }
};

const char* formatName(VkFormat format);
// The report as a table, one image per line (the `--memory-report` listing).
std::string formatMemoryReport(const FrameMemoryReport& report);

class TransientPool {
 public:
  // aliasing false gives every transient memory of its own (RAYSTER_NO_ALIASING=1 in the renderer's
  // environment turns it off, to compare).
  TransientPool() : TransientPool(aliasingDefault()) {}
  explicit TransientPool(bool aliasing) : aliasing_(aliasing) {}
  ~TransientPool() { release(); }
  TransientPool(TransientPool&& o) noexcept { *this = std::move(o); }
  // Releases this pool's images (deferred, through Context::retire) and takes over o's.
  TransientPool& operator=(TransientPool&& o) noexcept;
  static bool aliasingDefault();

  // Images for a frame's transients, in the requests' order. The previous frame's images stay when
  // the names and descriptions match and their placement still fits the new lifetimes. `before`
  // receives, per request, the requests whose memory it reuses (graph/aliasing.h aliasedBefore).
  std::vector<const rhi::Image*> acquire(rhi::Context& ctx, const std::vector<TransientRequest>& requests,
                                         std::vector<std::vector<uint32_t>>& before);
  // The frame's imported images, for the report (duplicates, by image, count once).
  void recordImported(const std::vector<std::pair<std::string, const rhi::Image*>>& imported);
  // Built on demand from the last frame's placement: nothing of it is assembled per frame.
  FrameMemoryReport report() const;
  size_t size() const { return images_.size(); }
  size_t rebuilds() const { return rebuilds_; }  // times the images were (re)created

 private:
  void release();
  bool aliasing_ = true;
  rhi::Context* ctx_ = nullptr;
  std::vector<TransientRequest> requests_;
  std::vector<AliasItem> items_;
  AliasPlan plan_;
  std::vector<rhi::Allocation> heaps_;
  std::vector<rhi::Image> images_;
  std::vector<FrameMemoryEntry> imported_;
  size_t rebuilds_ = 0;
};

}  // namespace rayster::graph
