#include "graph/graph.h"

#include "rhi/commands.h"
#include "rhi/context.h"

namespace rayster::graph {

rhi::Image& TransientPool::acquire(rhi::Context& ctx, const std::string& name, const rhi::ImageDesc& desc) {
  auto it = images_.find(name);
  if (it != images_.end() && it->second.desc() == desc) return it->second;
  rhi::Image image(ctx, desc, name.c_str());
  return images_.insert_or_assign(name, std::move(image)).first->second;
}

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

const rhi::Image& PassContext::image(ImageHandle h) const { return *graph_.images_[h.id].image; }
const rhi::Buffer& PassContext::buffer(BufferHandle h) const { return *graph_.buffers_[h.id].buffer; }

ImageHandle RenderGraph::createImage(std::string name, const rhi::ImageDesc& desc) {
  images_.push_back({std::move(name), desc, nullptr, nullptr});
  return {uint32_t(images_.size() - 1)};
}

ImageHandle RenderGraph::importImage(std::string name, const rhi::Image* image, ResourceState* state) {
  RAYSTER_ASSERT(image && state, "imported image needs an image and its state");
  images_.push_back({std::move(name), image->desc(), image, state});
  return {uint32_t(images_.size() - 1)};
}

BufferHandle RenderGraph::importBuffer(std::string name, const rhi::Buffer* buffer, ResourceState* state) {
  RAYSTER_ASSERT(buffer && state, "imported buffer needs a buffer and its state");
  buffers_.push_back({std::move(name), buffer, state});
  return {uint32_t(buffers_.size() - 1)};
}

void RenderGraph::addPass(std::string name, const std::function<void(PassBuilder&)>& setup, Execute execute) {
  passes_.push_back({std::move(name), {}, std::move(execute), false});
  PassBuilder builder(*this, uint32_t(passes_.size() - 1));
  setup(builder);
}


std::vector<PlannedPass> RenderGraph::compile() const {
  std::vector<ResourceState> imageStates, bufferStates;
  return plan(imageStates, bufferStates);
}

std::vector<PlannedPass> RenderGraph::plan(std::vector<ResourceState>& imageStates,
                                           std::vector<ResourceState>& bufferStates) const {
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

  // Barriers are derived on copies of the states, so planning never changes the graph: execute()
  // writes the final states back to imported resources once the passes are recorded.
  imageStates.clear();
  bufferStates.clear();
  for (const ImageEntry& e : images_) imageStates.push_back(e.external ? *e.external : ResourceState{});
  for (const BufferEntry& e : buffers_) bufferStates.push_back(e.external ? *e.external : ResourceState{});
  std::vector<PlannedPass> plan;
  for (uint32_t i = 0; i < passes_.size(); ++i) {
    if (!live[i]) continue;
    PlannedPass pp{i, {}};
    for (const Access& a : passes_[i].accesses) {
      ResourceState& st = a.isImage ? imageStates[a.resource] : bufferStates[a.resource];
      if (auto b = transition(st, a.use, a.isImage)) pp.barriers.push_back({a.isImage, a.resource, *b});
    }
    plan.push_back(std::move(pp));
  }
  return plan;
}

void RenderGraph::execute(VkCommandBuffer cmd, rhi::TimestampPool* timers) {
  RAYSTER_ASSERT(ctx_ && pool_, "execute() needs a Vulkan context and a transient pool");
  for (ImageEntry& e : images_)
    if (!e.image) e.image = &pool_->acquire(*ctx_, e.name, e.desc);
  std::vector<ResourceState> imageStates, bufferStates;
  const std::vector<PlannedPass> passes = plan(imageStates, bufferStates);
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
    PassContext pc(*this, cmd);
    pass.execute(pc);
    if (timers) timers->end(cmd, timer);
    ctx_->endLabel(cmd);
  }
  for (size_t i = 0; i < images_.size(); ++i)
    if (images_[i].external) *images_[i].external = imageStates[i];
  for (size_t i = 0; i < buffers_.size(); ++i)
    if (buffers_[i].external) *buffers_[i].external = bufferStates[i];
}

} // namespace rayster::graph
