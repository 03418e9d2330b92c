#include "rhi/memory.h"

#include "rhi/context.h"
#include "rhi/suballocator.h"
#include "rhi/vk_check.h"

namespace rayster::rhi {

struct MemoryAllocator::Block {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  uint32_t memoryType = 0;
  bool linear = false;
  void* mapped = nullptr;
  std::unique_ptr<SubAllocator> sub;
};

MemoryAllocator::MemoryAllocator(Context& ctx) : ctx_(ctx) {
  vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &props_);
}

MemoryAllocator::~MemoryAllocator() {
  for (auto& b : blocks_)
    if (b && b->memory) vkFreeMemory(ctx_.device(), b->memory, nullptr);
}

uint32_t MemoryAllocator::findMemoryType(uint32_t typeBits, MemoryUsage usage) const {
  VkMemoryPropertyFlags required = 0, preferred = 0;
  switch (usage) {
    case MemoryUsage::GpuOnly:
      preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
      break;
    case MemoryUsage::Upload:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      break;
    case MemoryUsage::Readback:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      break;
  }
  uint32_t fallback = UINT32_MAX;
  for (uint32_t i = 0; i < props_.memoryTypeCount; ++i) {
    if (!(typeBits & (1u << i))) continue;
    VkMemoryPropertyFlags f = props_.memoryTypes[i].propertyFlags;
    if ((f & required) != required) continue;
    if ((f & preferred) == preferred) return i;
    if (fallback == UINT32_MAX) fallback = i;
  }
  if (fallback == UINT32_MAX)
    vkFailure(VK_ERROR_OUT_OF_DEVICE_MEMORY, "findMemoryType: no compatible memory type", __FILE__, __LINE__);
  return fallback;
}

VkDeviceMemory MemoryAllocator::allocateDeviceMemory(VkDeviceSize size, uint32_t type, void** mapped) {
  // Every allocation may back a buffer with a device address (scene data, AS, SBT).
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.pNext = &flags;
  ai.allocationSize = size;
  ai.memoryTypeIndex = type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateMemory(ctx_.device(), &ai, nullptr, &memory));
  *mapped = nullptr;
  if (props_.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
    VK_CHECK(vkMapMemory(ctx_.device(), memory, 0, VK_WHOLE_SIZE, 0, mapped));
  stats_.reservedBytes += size;
  return memory;
}

Allocation MemoryAllocator::allocate(const VkMemoryRequirements& req, MemoryUsage usage, bool linear,
                                     MemoryCategory category) {
  std::lock_guard lock(mutex_);
  uint32_t type = findMemoryType(req.memoryTypeBits, usage);
  Allocation a;
  a.size = req.size;
  a.category = category;
  stats_.categoryBytes[size_t(category)] += req.size;
  if (req.size >= kDedicatedThreshold) {
    a.memory = allocateDeviceMemory(req.size, type, &a.mapped);
    stats_.dedicatedCount++;
    stats_.usedBytes += req.size;
    return a;
  }
  for (size_t i = 0; i < blocks_.size(); ++i) {
    Block* b = blocks_[i].get();
    if (!b || b->memoryType != type || b->linear != linear) continue;
    if (auto offset = b->sub->allocate(req.size, req.alignment)) {
      a.memory = b->memory;
      a.offset = *offset;
      a.block = int32_t(i);
      a.mapped = b->mapped ? static_cast<char*>(b->mapped) + *offset : nullptr;
      stats_.usedBytes += req.size;
      return a;
    }
  }
  auto b = std::make_unique<Block>();
  b->memoryType = type;
  b->linear = linear;
  b->memory = allocateDeviceMemory(kBlockSize, type, &b->mapped);
  b->sub = std::make_unique<SubAllocator>(kBlockSize);
  auto offset = b->sub->allocate(req.size, req.alignment);
  RAYSTER_ASSERT(offset.has_value(), "a fresh block must fit a sub-threshold allocation");
  a.memory = b->memory;
  a.offset = *offset;
  a.mapped = b->mapped ? static_cast<char*>(b->mapped) + *offset : nullptr;
  size_t slot = 0;  // a released block's slot, or a new one
  while (slot < blocks_.size() && blocks_[slot]) ++slot;
  a.block = int32_t(slot);
  if (slot == blocks_.size()) blocks_.emplace_back();
  blocks_[slot] = std::move(b);
  stats_.blockCount++;
  stats_.usedBytes += req.size;
  return a;
}

void MemoryAllocator::free(const Allocation& a) {
  if (!a.memory) return;
  std::lock_guard lock(mutex_);
  stats_.usedBytes -= a.size;
  stats_.categoryBytes[size_t(a.category)] -= a.size;
  if (a.block < 0) {
    vkFreeMemory(ctx_.device(), a.memory, nullptr);
    stats_.reservedBytes -= a.size;
    stats_.dedicatedCount--;
    return;
  }
  Block& b = *blocks_[size_t(a.block)];
  b.sub->free(a.offset);
  if (!b.sub->empty()) return;
  // One empty block per memory type and kind stays for re-use (no driver round trip when a frame
  // frees and allocates again); another empty one is released.
  for (size_t i = 0; i < blocks_.size(); ++i) {
    const Block* o = blocks_[i].get();
    if (o && i != size_t(a.block) && o->memoryType == b.memoryType && o->linear == b.linear && o->sub->empty()) {
      releaseBlock(size_t(a.block));
      return;
    }
  }
}

void MemoryAllocator::releaseBlock(size_t index) {
  Block& b = *blocks_[index];
  RAYSTER_ASSERT(b.sub->empty(), "only an empty block may be released");
  vkFreeMemory(ctx_.device(), b.memory, nullptr);  // unmaps too
  stats_.reservedBytes -= kBlockSize;
  stats_.blockCount--;
  blocks_[index].reset();
}

VkDeviceSize MemoryAllocator::releaseEmptyBlocks() {
  std::lock_guard lock(mutex_);
  VkDeviceSize released = 0;
  for (size_t i = 0; i < blocks_.size(); ++i)
    if (blocks_[i] && blocks_[i]->sub->empty()) {
      releaseBlock(i);
      released += kBlockSize;
    }
  return released;
}

MemoryStats MemoryAllocator::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace rayster::rhi
