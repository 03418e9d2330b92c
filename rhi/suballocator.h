#pragma once
// Offset sub-allocator for carving device-memory blocks (docs/architecture.md §1: no VMA, our own small
// allocator). Knows nothing of Vulkan so it is tested exhaustively on the CPU.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <utility>

namespace rayster::rhi {

// Best-fit over free ranges; alignment padding goes back to the free list rather than being
// charged to the allocation, so used() is exactly the sum of live allocation sizes.
// allocate and free are O(log n), except that allocate may step over free ranges that are big
// enough in size but not once aligned (at most those smaller than size + alignment - 1).
class SubAllocator {
 public:
  explicit SubAllocator(uint64_t size);

  // Returns an offset aligned to `alignment` (a power of two), or nullopt if no free range fits.
  std::optional<uint64_t> allocate(uint64_t size, uint64_t alignment);
  // `offset` must come from allocate and not be freed yet; merges with free neighbours.
  void free(uint64_t offset);

  uint64_t size() const { return size_; }
  uint64_t used() const { return used_; }
  bool empty() const { return allocations_.empty(); }
  uint64_t largestFreeRange() const;
  size_t allocationCount() const { return allocations_.size(); }

 private:
  void addFree(uint64_t offset, uint64_t size);
  void removeFree(std::map<uint64_t, uint64_t>::iterator it);

  uint64_t size_;
  uint64_t used_ = 0;
  std::map<uint64_t, uint64_t> freeByOffset_;           // offset -> size, for coalescing
  std::set<std::pair<uint64_t, uint64_t>> freeBySize_;  // (size, offset), for best fit
  std::map<uint64_t, uint64_t> allocations_;            // offset -> size
};

}  // namespace rayster::rhi
