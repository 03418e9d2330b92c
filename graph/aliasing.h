#pragma once
// Memory aliasing of the render graph's transient images (docs/architecture.md §2.4): images whose
// lifetimes within a frame (first to last use, in the order of the live passes) do not overlap
// may occupy the same memory. Pure functions on sizes and pass indices, unit-tested without a GPU.
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan_core.h>

namespace rayster::graph {

struct AliasItem {
  VkDeviceSize size = 0, alignment = 1;
  uint32_t memoryTypeBits = ~0u;  // items share a heap only with identical bits
  uint32_t first = 0, last = 0;   // live-pass positions of the first and last use (inclusive)
};

struct AliasHeap {
  VkDeviceSize size = 0, alignment = 1;
  uint32_t memoryTypeBits = ~0u;
};

struct AliasPlacement {
  uint32_t heap = 0;
  VkDeviceSize offset = 0;
};

struct AliasPlan {
  std::vector<AliasPlacement> placements;  // one per item, in the items' order
  std::vector<AliasHeap> heaps;
  VkDeviceSize totalBytes() const;
};

bool lifetimesOverlap(const AliasItem& a, const AliasItem& b);
// Places every item at the lowest offset of its heap that no item alive at the same time covers,
// largest items first (a greedy interval packing; memory is never shared by overlapping lifetimes).
AliasPlan packByLifetime(std::span<const AliasItem> items);
// True when the plan fits `items` (same count and heaps big enough) and keeps every two items with
// overlapping lifetimes in disjoint memory: a frame whose lifetimes changed may keep its images.
bool planFits(const AliasPlan& plan, std::span<const AliasItem> items);
// For each item, the items sharing memory with it that end before it starts (their contents are
// what its first use discards, and what its first barrier must wait for).
std::vector<std::vector<uint32_t>> aliasedBefore(const AliasPlan& plan, std::span<const AliasItem> items);

}  // namespace rayster::graph
