#pragma once
// The render graph (docs/architecture.md §2): passes declare what they read and write; the graph culls
// passes whose results nobody uses, derives synchronization2 barriers and layouts from tracked
// per-resource state, creates transient images, and wraps every pass in a debug label and a GPU
// timestamp pair. Passes run in the order they were added: a pass can only name resources that
// exist when it is added, so that order is already a valid topological order.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <volk.h>

#include "graph/history.h"
#include "graph/resource_state.h"
#include "graph/transient_pool.h"
#include "rhi/resources.h"

namespace rayster::rhi {
class Context;
class TimestampPool;
} // namespace rayster::rhi

namespace rayster::graph {

struct ImageHandle {
  uint32_t id = UINT32_MAX;
  bool valid() const { return id != UINT32_MAX; }
};
struct BufferHandle {
  uint32_t id = UINT32_MAX;
  bool valid() const { return id != UINT32_MAX; }
};

class RenderGraph;

// What a pass is, for everything that reports on passes (--timings, bench JSON, the viewer): a
// property the pass declares, never inferred from its name.
enum class PassKind : uint8_t {
  Frame,     // the frame's own work: its GPU time counts in the frame's
  Utility,   // work around the frame (copies for presentation): not the frame's cost, not reported
  Readback,  // copies to the host: not the frame's cost, not reported
  Twin,      // a raw-rate twin (PassInfo::twinOf): reported beside its pass, not the frame's cost
};
struct PassInfo {
  PassKind kind = PassKind::Frame;
  std::string twinOf;      // Twin: the pass whose rays it replays
  uint64_t rays = 0;       // rays launched per frame: launch size × traceRayEXT calls per invocation
  bool raysExact = false;  // true when every launched ray is traced (else `rays` is an upper bound)
  bool reported() const { return kind == PassKind::Frame || kind == PassKind::Twin; }
};

class PassBuilder {
 public:
  ImageHandle read(ImageHandle image, Use use);
  ImageHandle write(ImageHandle image, Use use);
  BufferHandle read(BufferHandle buffer, Use use);
  BufferHandle write(BufferHandle buffer, Use use);
  // Keeps the pass even if nothing reads what it writes (readbacks, host-visible results).
  void sideEffect();
  // The pass's report metadata (PassInfo).
  void kind(PassKind kind);
  void twinOf(std::string pass);  // kind Twin
  void rays(uint64_t launched, bool exact = false);

 private:
  friend class RenderGraph;
  PassBuilder(RenderGraph& graph, uint32_t pass) : graph_(graph), pass_(pass) {}
  RenderGraph& graph_;
  uint32_t pass_;
};

class PassContext {
 public:
  VkCommandBuffer cmd;
  const rhi::Image& image(ImageHandle h) const;
  const rhi::Buffer& buffer(BufferHandle h) const;

 private:
  friend class RenderGraph;
  PassContext(const RenderGraph& graph, VkCommandBuffer c, uint32_t pass) : cmd(c), graph_(graph), pass_(pass) {}
  const RenderGraph& graph_;
  uint32_t pass_;
};

struct PlannedBarrier {
  bool isImage;
  uint32_t resource;
  Barrier barrier;
};
struct PlannedPass {
  uint32_t pass;
  std::vector<PlannedBarrier> barriers;
};

class RenderGraph {
 public:
  // ctx may be null for planning-only use (unit tests): then execute() is unavailable. Without
  // `histories`, history() is unavailable.
  RenderGraph(rhi::Context* ctx, TransientPool* pool, HistoryStore* histories = nullptr)
      : ctx_(ctx), pool_(pool), histories_(histories) {}

  // `tags`: bits whose meaning is the caller's (render: what an image holds, for its AOV). Every
  // created image can be copied from (TRANSFER_SRC): any of them can be read back.
  ImageHandle createImage(std::string name, const rhi::ImageDesc& desc, uint32_t tags = 0);
  // External images/buffers keep their state in `state` across frames (histories, outputs).
  ImageHandle importImage(std::string name, const rhi::Image* image, ResourceState* state, uint32_t tags = 0);
  BufferHandle importBuffer(std::string name, const rhi::Buffer* buffer, ResourceState* state);
  // A temporal history of the HistoryStore (graph/history.h): `next` is written this frame (as
  // image `name`), `previous` holds what the frame before wrote ("<name>-prev"); `frames` counts the
  // frames accumulated in it, 0 when it is empty (first frame, reset, new size) and must not be read.
  struct History {
    ImageHandle previous, next;
    uint32_t frames = 0;
  };
  History history(const std::string& name, const rhi::ImageDesc& desc, uint32_t tags = 0);
  // The image created or imported last under `name` (invalid if none): what `--aov NAME` reads.
  ImageHandle findImage(std::string_view name) const;
  std::vector<std::string> imageNames() const;  // each name once, in the order first recorded
  uint32_t imageTags(ImageHandle h) const { return images_[h.id].tags; }
  // The image behind `h` once execute() has placed it (nullptr before, for a transient).
  const rhi::Image* importedImage(ImageHandle h) const { return images_[h.id].image; }

  using Execute = std::function<void(PassContext&)>;
  void addPass(std::string name, const std::function<void(PassBuilder&)>& setup, Execute execute);

  // Orders, culls and derives barriers; pure (no Vulkan calls, no state changes), so it is
  // unit-testable and may be called any number of times. aliasedBefore (indexed by image id): the
  // transients whose memory an image reuses; its first barrier then waits for their last accesses
  // and discards their contents (oldLayout UNDEFINED).
  std::vector<PlannedPass> compile(const std::vector<std::vector<uint32_t>>* aliasedBefore = nullptr) const;
  // The transient images live passes use, with the positions (in the live pass order) of their
  // first and last use: what TransientPool packs. Imported images never alias.
  struct TransientLifetime {
    uint32_t image, first, last;
  };
  std::vector<TransientLifetime> transientLifetimes() const;
  // Records every live pass into cmd, with its barriers, label and timestamps.
  void execute(VkCommandBuffer cmd, rhi::TimestampPool* timers);
  // After the submission of execute() completed: each timed pass's GPU time with its PassInfo, in
  // execution order.
  struct PassTiming {
    std::string name;
    double ms = 0;
    PassInfo info;
  };
  std::vector<PassTiming> readTimings(rhi::TimestampPool& timers) const;

  const std::string& passName(uint32_t pass) const { return passes_[pass].name; }
  const std::string& imageName(uint32_t image) const { return images_[image].name; }
  const rhi::ImageDesc& imageDesc(ImageHandle h) const { return images_[h.id].desc; }

 private:
  friend class PassBuilder;
  friend class PassContext;
  struct Access {
    bool isImage;
    uint32_t resource;
    Use use;
  };
  struct Pass {
    std::string name;
    std::vector<Access> accesses;
    Execute execute;
    bool sideEffect = false;
    PassInfo info;
  };
  struct ImageEntry {
    std::string name;
    rhi::ImageDesc desc;
    const rhi::Image* image = nullptr;
    ResourceState* external = nullptr;
    uint32_t tags = 0;
  };
  struct BufferEntry {
    std::string name;
    const rhi::Buffer* buffer = nullptr;
    ResourceState* external = nullptr;
  };
  std::vector<uint32_t> livePasses() const;  // culling: the passes that run, in order
  // Plans on copies of the resource states and returns the states after the frame.
  std::vector<PlannedPass> plan(std::vector<ResourceState>& imageStates, std::vector<ResourceState>& bufferStates,
                                const std::vector<std::vector<uint32_t>>* aliasedBefore) const;

  rhi::Context* ctx_;
  TransientPool* pool_;
  HistoryStore* histories_;
  std::vector<Pass> passes_;
  std::vector<ImageEntry> images_;
  std::vector<BufferEntry> buffers_;
  std::vector<uint32_t> timedPasses_;  // execute(): the pass of each timestamp region, in order
};

} // namespace rayster::graph
