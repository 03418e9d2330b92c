#pragma once
// Device-memory sub-allocator (VMA is not packaged in Debian). Large blocks per memory type, carved
// with a best-fit SubAllocator; big resources get dedicated allocations. Buffers and images come
// from separate blocks, so bufferImageGranularity never needs checking.
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include <volk.h>

namespace rayster::rhi {

class Context;
class SubAllocator;

enum class MemoryUsage {
  GpuOnly,   // device local, never mapped
  Upload,    // host visible + coherent, written sequentially by the CPU (staging, constants)
  Readback,  // host visible, preferably cached, read by the CPU
};

// What an allocation backs, for the per-category totals `rayster bench` reports.
enum class MemoryCategory : uint8_t {
  Image,   // render targets, textures, history
  Buffer,  // device-local buffers: geometry, scene tables, SBT, scratch
  Accel,   // acceleration-structure storage (BLAS, TLAS)
  Host,    // host-visible buffers: staging uploads, constants, readback
};
inline constexpr size_t kMemoryCategories = 4;

struct Allocation {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // already offset; null unless host visible
  int32_t block = -1;      // -1: dedicated
  MemoryCategory category = MemoryCategory::Buffer;
  explicit operator bool() const { return memory != VK_NULL_HANDLE; }
};

struct MemoryStats {
  uint64_t usedBytes = 0;      // handed out to resources
  uint64_t reservedBytes = 0;  // allocated from the driver (blocks + dedicated)
  uint32_t blockCount = 0;
  uint32_t dedicatedCount = 0;
  uint64_t categoryBytes[kMemoryCategories] = {};  // usedBytes split by MemoryCategory
  uint64_t bytes(MemoryCategory c) const { return categoryBytes[size_t(c)]; }
};

class MemoryAllocator {
 public:
  static constexpr VkDeviceSize kBlockSize = 64ull << 20;           // few driver allocations, modest waste
  static constexpr VkDeviceSize kDedicatedThreshold = 16ull << 20;  // big targets/AS get their own memory

  explicit MemoryAllocator(Context& ctx);
  ~MemoryAllocator();
  MemoryAllocator(const MemoryAllocator&) = delete;
  MemoryAllocator& operator=(const MemoryAllocator&) = delete;

  // linear: the resource is a buffer (or linear image); images and buffers never share a block.
  Allocation allocate(const VkMemoryRequirements& req, MemoryUsage usage, bool linear,
                      MemoryCategory category = MemoryCategory::Buffer);
  // An emptied block stays as the one spare of its memory type and kind; a second empty one goes
  // back to the driver at once.
  void free(const Allocation& allocation);
  // Returns every empty block to the driver (after uploads, whose staging blocks would otherwise
  // stay reserved). Returns the bytes released.
  VkDeviceSize releaseEmptyBlocks();
  MemoryStats stats() const;
  uint32_t findMemoryType(uint32_t typeBits, MemoryUsage usage) const;

 private:
  struct Block;
  VkDeviceMemory allocateDeviceMemory(VkDeviceSize size, uint32_t type, void** mapped);
  void releaseBlock(size_t index);  // the block must be empty; mutex held
  Context& ctx_;
  VkPhysicalDeviceMemoryProperties props_{};
  std::vector<std::unique_ptr<Block>> blocks_;
  MemoryStats stats_;
  mutable std::mutex mutex_;
};

}  // namespace rayster::rhi
