#include "graph/graph.h"

#include <algorithm>

#include "rhi/commands.h"
#include "rhi/context.h"

namespace rayster::graph {

ImageHandle PassBuilder::read(ImageHandle image, Use use) {
  RAYSTER_ASSERT(image.valid(), "pass reads an invalid image handle");
  RAYSTER_ASSERT(!accessInfo(use, true).writes, "read() given a writing use");
  graph_.passes_[pass_].accesses.push_back({true, image.id, use});
  return image;
}

ImageHandle PassBuilder::write(ImageHandle image, Use use) {
  RAYSTER_ASSERT(image.valid(), "pass writes an invalid image handle");
  RAYSTER_ASSERT(accessInfo(use, true).writes, "write() given a read-only use");
  graph_.passes_[pass_].accesses.push_back({true, image.id, use});
  return image;
}

BufferHandle PassBuilder::read(BufferHandle buffer, Use use) {
  RAYSTER_ASSERT(buffer.valid(), "pass reads an invalid buffer handle");
  graph_.passes_[pass_].accesses.push_back({false, buffer.id, use});
  return buffer;
}

BufferHandle PassBuilder::write(BufferHandle buffer, Use use) {
  RAYSTER_ASSERT(buffer.valid(), "pass writes an invalid buffer handle");
  graph_.passes_[pass_].accesses.push_back({false, buffer.id, use});
  return buffer;
}

void PassBuilder::sideEffect() { graph_.passes_[pass_].sideEffect = true; }
void PassBuilder::kind(PassKind kind) { graph_.passes_[pass_].info.kind = kind; }
void PassBuilder::twinOf(std::string pass) {
  PassInfo& info = graph_.passes_[pass_].info;
  info.kind = PassKind::Twin;
  info.twinOf = std::move(pass);
}
void PassBuilder::rays(uint64_t launched, bool exact) {
  PassInfo& info = graph_.passes_[pass_].info;
  info.rays = launched;
  info.raysExact = exact;
}

const rhi::Image& PassContext::image(ImageHandle h) const {
  // Transients alias by lifetime: a pass may only touch images it declared (read or write).
  const auto& accesses = graph_.passes_[pass_].accesses;
  RAYSTER_ASSERT(std::any_of(accesses.begin(), accesses.end(),
                             [&](const RenderGraph::Access& a) { return a.isImage && a.resource == h.id; }),
                 "a pass used an image it did not declare");
  return *graph_.images_[h.id].image;
}
const rhi::Buffer& PassContext::buffer(BufferHandle h) const { return *graph_.buffers_[h.id].buffer; }

ImageHandle RenderGraph::createImage(std::string name, const rhi::ImageDesc& desc, uint32_t tags) {
  rhi::ImageDesc d = desc;
  d.usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;  // any image can be read back (an AOV)
  images_.push_back({std::move(name), d, nullptr, nullptr, tags});
  return {uint32_t(images_.size() - 1)};
}

ImageHandle RenderGraph::importImage(std::string name, const rhi::Image* image, ResourceState* state, uint32_t tags) {
  RAYSTER_ASSERT(image && state, "imported image needs an image and its state");
  images_.push_back({std::move(name), image->desc(), image, state, tags});
  return {uint32_t(images_.size() - 1)};
}

ImageHandle RenderGraph::findImage(std::string_view name) const {
  for (size_t i = images_.size(); i-- > 0;)
    if (images_[i].name == name) return {uint32_t(i)};
  return {};
}

std::vector<std::string> RenderGraph::imageNames() const {
  std::vector<std::string> names;
  for (const ImageEntry& e : images_)
    if (std::find(names.begin(), names.end(), e.name) == names.end()) names.push_back(e.name);
  return names;
}

BufferHandle RenderGraph::importBuffer(std::string name, const rhi::Buffer* buffer, ResourceState* state) {
  RAYSTER_ASSERT(buffer && state, "imported buffer needs a buffer and its state");
  buffers_.push_back({std::move(name), buffer, state});
  return {uint32_t(buffers_.size() - 1)};
}

AccelHandle RenderGraph::importAccel(std::string name, VkAccelerationStructureKHR accel, const rhi::Buffer* buffer,
                                     ResourceState* state) {
  RAYSTER_ASSERT(accel != VK_NULL_HANDLE, "imported acceleration structure is null");
  const BufferHandle h = importBuffer(std::move(name), buffer, state);
  buffers_[h.id].accel = accel;
  return {h};
}

RenderGraph::History RenderGraph::history(const std::string& name, const rhi::ImageDesc& desc, uint32_t tags) {
  RAYSTER_ASSERT(ctx_ && histories_, "history() needs a Vulkan context and a history store");
  rhi::ImageDesc d = desc;
  d.usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;  // an AOV, like any image
  HistoryStore::Entry& e = histories_->acquire(*ctx_, name, d);
  const uint32_t f = histories_->frame_;
  // Frame f reads image f % 2 and writes the other.
  return {importImage(name + "-prev", &e.images[f % 2], &e.states[f % 2], tags),
          importImage(name, &e.images[(f + 1) % 2], &e.states[(f + 1) % 2], tags), e.frames};
}

void RenderGraph::addPass(std::string name, const std::function<void(PassBuilder&)>& setup, Execute execute) {
  passes_.push_back({std::move(name), {}, std::move(execute), false, {}});
  PassBuilder builder(*this, uint32_t(passes_.size() - 1));
  setup(builder);
  checkBindings(passes_.back());
}

std::vector<PlannedPass> RenderGraph::compile(const std::vector<std::vector<uint32_t>>* aliasedBefore) const {
  std::vector<ResourceState> imageStates, bufferStates;
  return plan(imageStates, bufferStates, aliasedBefore);
}

std::vector<uint32_t> RenderGraph::livePasses() const {
  // Culling, back to front: a pass lives if it has a side effect, writes an imported resource (its
  // contents outlive the frame), or writes something a live later pass reads.
  std::vector<bool> live(passes_.size(), false);
  std::vector<bool> imageNeeded(images_.size(), false), bufferNeeded(buffers_.size(), false);
  for (size_t i = passes_.size(); i-- > 0;) {
    const Pass& p = passes_[i];
    bool keep = p.sideEffect;
    for (const Access& a : p.accesses) {
      if (!accessInfo(a.use, a.isImage).writes) continue;
      bool external = a.isImage ? images_[a.resource].external != nullptr : buffers_[a.resource].external != nullptr;
      bool needed = a.isImage ? imageNeeded[a.resource] : bufferNeeded[a.resource];
      keep = keep || external || needed;
    }
    live[i] = keep;
    if (!keep) continue;
    for (const Access& a : p.accesses)
      if (accessInfo(a.use, a.isImage).reads) (a.isImage ? imageNeeded : bufferNeeded)[a.resource] = true;
  }
  std::vector<uint32_t> order;
  for (uint32_t i = 0; i < passes_.size(); ++i)
    if (live[i]) order.push_back(i);
  return order;
}

std::vector<RenderGraph::TransientLifetime> RenderGraph::transientLifetimes() const {
  std::vector<TransientLifetime> out;
  std::vector<int32_t> slot(images_.size(), -1);
  const std::vector<uint32_t> order = livePasses();
  for (uint32_t pos = 0; pos < order.size(); ++pos)
    for (const Access& a : passes_[order[pos]].accesses) {
      if (!a.isImage || images_[a.resource].external) continue;
      if (slot[a.resource] < 0) {
        slot[a.resource] = int32_t(out.size());
        out.push_back({a.resource, pos, pos});
      }
      out[size_t(slot[a.resource])].last = pos;
    }
  return out;
}

std::vector<PlannedPass> RenderGraph::plan(std::vector<ResourceState>& imageStates,
                                           std::vector<ResourceState>& bufferStates,
                                           const std::vector<std::vector<uint32_t>>* aliasedBefore) const {
  // Barriers are derived on copies of the states, so planning never changes the graph: execute()
  // writes the final states back to imported resources once the passes are recorded.
  imageStates.clear();
  bufferStates.clear();
  for (const ImageEntry& e : images_) imageStates.push_back(e.external ? *e.external : ResourceState{});
  for (const BufferEntry& e : buffers_) bufferStates.push_back(e.external ? *e.external : ResourceState{});
  std::vector<bool> touched(images_.size(), false);
  std::vector<PlannedPass> plan;
  for (uint32_t i : livePasses()) {
    PlannedPass pp{i, {}};
    for (const Access& a : passes_[i].accesses) {
      ResourceState& st = a.isImage ? imageStates[a.resource] : bufferStates[a.resource];
      if (a.isImage && !touched[a.resource]) {
        touched[a.resource] = true;
        // An aliased transient starts where the images before it in its memory ended: their last
        // writes and reads are what its first layout transition (from UNDEFINED) must wait for.
        if (aliasedBefore && a.resource < aliasedBefore->size())
          for (uint32_t j : (*aliasedBefore)[a.resource]) {
            st.writeStages |= imageStates[j].writeStages;
            st.writeAccess |= imageStates[j].writeAccess;
            st.readStages |= imageStates[j].readStages;
            st.contentsValid = false;
          }
      }
      if (auto b = transition(st, a.use, a.isImage)) pp.barriers.push_back({a.isImage, a.resource, *b});
    }
    plan.push_back(std::move(pp));
  }
  return plan;
}

void RenderGraph::execute(VkCommandBuffer cmd, rhi::TimestampPool* timers) {
  RAYSTER_ASSERT(ctx_ && pool_, "execute() needs a Vulkan context and a transient pool");
  // Transients get images (aliased by lifetime) only when a live pass uses them.
  const std::vector<TransientLifetime> lifetimes = transientLifetimes();
  const std::vector<uint32_t> order = livePasses();
  std::vector<TransientRequest> requests;
  for (const TransientLifetime& t : lifetimes)
    requests.push_back({images_[t.image].name, images_[t.image].desc, t.first, t.last, passes_[order[t.first]].name,
                        passes_[order[t.last]].name});
  std::vector<std::vector<uint32_t>> before;
  const std::vector<const rhi::Image*> transients = pool_->acquire(*ctx_, requests, before);
  std::vector<std::vector<uint32_t>> aliasedBefore(images_.size());
  for (size_t i = 0; i < lifetimes.size(); ++i) {
    images_[lifetimes[i].image].image = transients[i];
    for (uint32_t j : before[i]) aliasedBefore[lifetimes[i].image].push_back(lifetimes[j].image);
  }
  std::vector<std::pair<std::string, const rhi::Image*>> imported;
  for (const ImageEntry& e : images_)
    if (e.external) imported.emplace_back(e.name, e.image);
  pool_->recordImported(imported);
  std::vector<ResourceState> imageStates, bufferStates;
  const std::vector<PlannedPass> passes = plan(imageStates, bufferStates, &aliasedBefore);
  timedPasses_.clear();
  for (const PlannedPass& pp : passes) {
    Pass& pass = passes_[pp.pass];
    std::vector<VkImageMemoryBarrier2> imageBarriers;
    std::vector<VkMemoryBarrier2> memoryBarriers;
    for (const PlannedBarrier& pb : pp.barriers) {
      const Barrier& b = pb.barrier;
      if (pb.isImage) {
        const rhi::Image& img = *images_[pb.resource].image;
        VkImageMemoryBarrier2 ib{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        ib.srcStageMask = b.srcStages;
        ib.srcAccessMask = b.srcAccess;
        ib.dstStageMask = b.dstStages;
        ib.dstAccessMask = b.dstAccess;
        ib.oldLayout = b.oldLayout;
        ib.newLayout = b.newLayout;
        ib.srcQueueFamilyIndex = ib.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        ib.image = img.handle();
        ib.subresourceRange = {img.aspect(), 0, 1, 0, img.desc().layers};
        imageBarriers.push_back(ib);
      } else {
        // Buffers are whole-resource: a global memory barrier is as precise and cheaper to record.
        VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        mb.srcStageMask = b.srcStages;
        mb.srcAccessMask = b.srcAccess;
        mb.dstStageMask = b.dstStages;
        mb.dstAccessMask = b.dstAccess;
        memoryBarriers.push_back(mb);
      }
    }
    ctx_->beginLabel(cmd, pass.name.c_str());
    if (!imageBarriers.empty() || !memoryBarriers.empty()) {
      VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
      dep.imageMemoryBarrierCount = uint32_t(imageBarriers.size());
      dep.pImageMemoryBarriers = imageBarriers.data();
      dep.memoryBarrierCount = uint32_t(memoryBarriers.size());
      dep.pMemoryBarriers = memoryBarriers.data();
      vkCmdPipelineBarrier2(cmd, &dep);
    }
    uint32_t timer = timers ? timers->begin(cmd, pass.name) : UINT32_MAX;
    if (timer != UINT32_MAX) timedPasses_.push_back(pp.pass);
    if (pass.pipeline) bindPipeline(cmd, pass);
    PassContext pc(*this, cmd, pp.pass);
    pass.execute(pc);
    if (timers) timers->end(cmd, timer);
    ctx_->endLabel(cmd);
  }
  for (size_t i = 0; i < images_.size(); ++i)
    if (images_[i].external) *images_[i].external = imageStates[i];
  for (size_t i = 0; i < buffers_.size(); ++i)
    if (buffers_[i].external) *buffers_[i].external = bufferStates[i];
}

std::vector<RenderGraph::PassTiming> RenderGraph::readTimings(rhi::TimestampPool& timers) const {
  const std::vector<rhi::TimestampPool::Timing> times = timers.read();
  RAYSTER_ASSERT(times.size() == timedPasses_.size(), "timestamps read for another graph's execution");
  std::vector<PassTiming> out;
  for (size_t i = 0; i < times.size(); ++i) out.push_back({times[i].name, times[i].ms, passes_[timedPasses_[i]].info});
  return out;
}

}  // namespace rayster::graph
