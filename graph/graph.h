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
class Pipeline;
class TimestampPool;
struct ShaderBinding;
}  // namespace rayster::rhi

namespace rayster::graph {

struct ImageHandle {
  uint32_t id = UINT32_MAX;
  bool valid() const { return id != UINT32_MAX; }
};
struct BufferHandle {
  uint32_t id = UINT32_MAX;
  bool valid() const { return id != UINT32_MAX; }
};
// An acceleration structure (the TLAS): tracked through the buffer that backs it, so a build or
// refit pass (Use::AccelStructBuildWrite) and the ray-tracing passes that read it get their barriers
// from the graph like any other resource.
struct AccelHandle {
  BufferHandle buffer;
  bool valid() const { return buffer.valid(); }
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
  // The pipeline this pass runs, bound (with set 0 and, when it uses it, the global set 1) by the
  // graph right before the pass's execute function. Name the descriptors with bind().
  PassBuilder& pipeline(const rhi::Pipeline& pipeline);
  // Binds the descriptor the pipeline's shaders call `name` (rhi/spirv_reflect.h) and records the
  // access it implies: sampled images are read; storage images and buffers are read, written or both
  // as the GLSL says (readonly / writeonly / neither); an acceleration structure is traced against.
  // Sampled images use the graph's default sampler (setGlobals) unless given one. Every set-0
  // descriptor of the pipeline must be bound (else the program stops, naming the pass and the
  // descriptor); a name the compiled shaders do not declare (optimised away) binds nothing.
  PassBuilder& bind(std::string_view name, ImageHandle image, VkSampler sampler = VK_NULL_HANDLE);
  PassBuilder& bind(std::string_view name, BufferHandle buffer);
  PassBuilder& bind(std::string_view name, AccelHandle accel);
  // A buffer that does not change while the frame runs (the frame constants, the scene's tables):
  // bound, not tracked.
  PassBuilder& bind(std::string_view name, const rhi::Buffer& constant);

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
  const rhi::ShaderBinding* declared(std::string_view name) const;
  RenderGraph& graph_;
  uint32_t pass_;
};

class PassContext {
 public:
  VkCommandBuffer cmd;
  const rhi::Image& image(ImageHandle h) const;
  const rhi::Buffer& buffer(BufferHandle h) const;
  // The pass's pipeline (PassBuilder::pipeline), already bound with its descriptors.
  const rhi::Pipeline& pipeline() const;
  // Push constants for the pass's pipeline: T is the block's shared struct (shaders/shared/push.h),
  // checked against the size the shader declares.
  template <class T>
  void push(const T& value) const {
    pushBytes(&value, uint32_t(sizeof(T)));
  }
  void pushBytes(const void* data, uint32_t bytes) const;
  // For passes that switch pipelines while they record (the draw loops of the raster G-buffer and
  // the shadow maps): binds `pipeline` with the graph's globals (its shaders may declare no other
  // set-0 descriptor); push to it with pipeline.push(cmd, value).
  void bindWithGlobals(const rhi::Pipeline& pipeline) const;

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
  // An acceleration structure backed by `buffer` (its state in `state`, across frames).
  AccelHandle importAccel(std::string name, VkAccelerationStructureKHR accel, const rhi::Buffer* buffer,
                          ResourceState* state);
  // What every pass with a pipeline gets without naming it: the global descriptor set (set 1, the
  // bindless textures) for pipelines whose shaders use it, the sampler of sampled images bound
  // without one, and buffers that stay constant for the frame, bound wherever a pipeline declares
  // their name (the frame constants' "FrameBlock").
  struct Constant {
    std::string name;
    const rhi::Buffer* buffer = nullptr;
  };
  struct Globals {
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
    std::vector<Constant> constants;
  };
  void setGlobals(Globals globals) { globals_ = globals; }
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
  // One descriptor of set 0, as bound by PassBuilder::bind.
  struct Descriptor {
    uint32_t binding = 0;
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
    uint32_t image = UINT32_MAX, buffer = UINT32_MAX;
    VkSampler sampler = VK_NULL_HANDLE;
    const rhi::Buffer* constant = nullptr;
  };
  struct Pass {
    std::string name;
    std::vector<Access> accesses;
    Execute execute;
    bool sideEffect = false;
    PassInfo info;
    const rhi::Pipeline* pipeline = nullptr;
    std::vector<Descriptor> descriptors;
  };
  void bindPipeline(VkCommandBuffer cmd, const Pass& pass) const;
  void checkBindings(Pass& pass) const;  // every set-0 descriptor of the pass's pipeline is bound
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
    VkAccelerationStructureKHR accel = VK_NULL_HANDLE;  // importAccel
  };
  std::vector<uint32_t> livePasses() const;  // culling: the passes that run, in order
  // Plans on copies of the resource states and returns the states after the frame.
  std::vector<PlannedPass> plan(std::vector<ResourceState>& imageStates, std::vector<ResourceState>& bufferStates,
                                const std::vector<std::vector<uint32_t>>* aliasedBefore) const;

  rhi::Context* ctx_;
  TransientPool* pool_;
  HistoryStore* histories_;
  Globals globals_;
  std::vector<Pass> passes_;
  std::vector<ImageEntry> images_;
  std::vector<BufferEntry> buffers_;
  std::vector<uint32_t> timedPasses_;  // execute(): the pass of each timestamp region, in order
};

}  // namespace rayster::graph
