#include "rhi/suballocator.h"

#include "core/error.h"

namespace rayster::rhi {

SubAllocator::SubAllocator(uint64_t size) : size_(size) {
  if (size > 0) addFree(0, size);
}

std::optional<uint64_t> SubAllocator::allocate(uint64_t size, uint64_t alignment) {
  RAYSTER_ASSERT(size > 0, "SubAllocator::allocate of 0 bytes");
  RAYSTER_ASSERT(alignment > 0 && (alignment & (alignment - 1)) == 0, "SubAllocator alignment must be a power of two");
  // Smallest ranges first (best fit), lowest offset among equal sizes so results are
  // deterministic. A range of size + alignment - 1 always fits, so the walk ends there at worst.
  for (auto it = freeBySize_.lower_bound({size, 0}); it != freeBySize_.end(); ++it) {
    const auto [rangeSize, rangeOffset] = *it;
    const uint64_t padding = (alignment - (rangeOffset & (alignment - 1))) & (alignment - 1);
    if (padding > rangeSize - size) continue;
    removeFree(freeByOffset_.find(rangeOffset));
    const uint64_t offset = rangeOffset + padding;
    // The range was maximal, so neither leftover touches another free range.
    if (padding > 0) addFree(rangeOffset, padding);
    const uint64_t tail = rangeSize - padding - size;
    if (tail > 0) addFree(offset + size, tail);
    allocations_.emplace(offset, size);
    used_ += size;
    return offset;
  }
  return std::nullopt;
}

void SubAllocator::free(uint64_t offset) {
  const auto alloc = allocations_.find(offset);
  RAYSTER_ASSERT(alloc != allocations_.end(), "SubAllocator::free of an unknown or freed offset");
  uint64_t start = offset;
  uint64_t end = offset + alloc->second;
  used_ -= alloc->second;
  allocations_.erase(alloc);

  auto next = freeByOffset_.lower_bound(offset);
  if (next != freeByOffset_.begin()) {
    const auto prev = std::prev(next);
    if (prev->first + prev->second == start) {
      start = prev->first;
      removeFree(prev);
    }
  }
  if (next != freeByOffset_.end() && next->first == end) {
    end += next->second;
    removeFree(next);
  }
  addFree(start, end - start);
}

uint64_t SubAllocator::largestFreeRange() const { return freeBySize_.empty() ? 0 : freeBySize_.rbegin()->first; }

void SubAllocator::addFree(uint64_t offset, uint64_t size) {
  freeByOffset_.emplace(offset, size);
  freeBySize_.emplace(size, offset);
}

void SubAllocator::removeFree(std::map<uint64_t, uint64_t>::iterator it) {
  freeBySize_.erase({it->second, it->first});
  freeByOffset_.erase(it);
}

}  // namespace rayster::rhi
