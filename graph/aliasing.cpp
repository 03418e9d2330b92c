#include "graph/aliasing.h"

#include <algorithm>
#include <numeric>

namespace rayster::graph {
namespace {

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return a <= 1 ? v : (v + a - 1) / a * a; }

bool rangesOverlap(VkDeviceSize aOffset, VkDeviceSize aSize, VkDeviceSize bOffset, VkDeviceSize bSize) {
  return aOffset < bOffset + bSize && bOffset < aOffset + aSize;
}

bool sharesMemory(const AliasPlan& plan, std::span<const AliasItem> items, size_t a, size_t b) {
  const AliasPlacement& pa = plan.placements[a];
  const AliasPlacement& pb = plan.placements[b];
  return pa.heap == pb.heap && rangesOverlap(pa.offset, items[a].size, pb.offset, items[b].size);
}

}  // namespace

VkDeviceSize AliasPlan::totalBytes() const {
  VkDeviceSize total = 0;
  for (const AliasHeap& h : heaps) total += h.size;
  return total;
}

bool lifetimesOverlap(const AliasItem& a, const AliasItem& b) { return a.first <= b.last && b.first <= a.last; }

AliasPlan packByLifetime(std::span<const AliasItem> items) {
  AliasPlan plan;
  plan.placements.resize(items.size());
  std::vector<size_t> order(items.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (items[a].size != items[b].size) return items[a].size > items[b].size;
    return items[a].first < items[b].first;
  });
  std::vector<size_t> placed;
  for (size_t i : order) {
    const AliasItem& item = items[i];
    uint32_t heap = 0;
    while (heap < plan.heaps.size() && plan.heaps[heap].memoryTypeBits != item.memoryTypeBits) ++heap;
    if (heap == plan.heaps.size()) plan.heaps.push_back({0, 1, item.memoryTypeBits});
    // The items of this heap alive at the same time, by offset: the first gap that fits wins.
    std::vector<size_t> live;
    for (size_t j : placed)
      if (plan.placements[j].heap == heap && lifetimesOverlap(item, items[j])) live.push_back(j);
    std::sort(live.begin(), live.end(),
              [&](size_t a, size_t b) { return plan.placements[a].offset < plan.placements[b].offset; });
    VkDeviceSize offset = 0;
    for (size_t j : live) {
      if (alignUp(offset, item.alignment) + item.size <= plan.placements[j].offset) break;
      offset = std::max(offset, plan.placements[j].offset + items[j].size);
    }
    offset = alignUp(offset, item.alignment);
    plan.placements[i] = {heap, offset};
    AliasHeap& h = plan.heaps[heap];
    h.size = std::max(h.size, offset + item.size);
    h.alignment = std::max(h.alignment, item.alignment);
    placed.push_back(i);
  }
  return plan;
}

bool planFits(const AliasPlan& plan, std::span<const AliasItem> items) {
  if (plan.placements.size() != items.size()) return false;
  for (size_t i = 0; i < items.size(); ++i) {
    const AliasPlacement& p = plan.placements[i];
    if (p.heap >= plan.heaps.size()) return false;
    const AliasHeap& h = plan.heaps[p.heap];
    if (h.memoryTypeBits != items[i].memoryTypeBits || p.offset + items[i].size > h.size) return false;
    if (items[i].alignment > 1 && p.offset % items[i].alignment != 0) return false;
    for (size_t j = 0; j < i; ++j)
      if (lifetimesOverlap(items[i], items[j]) && sharesMemory(plan, items, i, j)) return false;
  }
  return true;
}

std::vector<std::vector<uint32_t>> aliasedBefore(const AliasPlan& plan, std::span<const AliasItem> items) {
  std::vector<std::vector<uint32_t>> before(items.size());
  for (size_t i = 0; i < items.size(); ++i)
    for (size_t j = 0; j < items.size(); ++j)
      if (j != i && items[j].last < items[i].first && sharesMemory(plan, items, i, j)) before[i].push_back(uint32_t(j));
  return before;
}

}  // namespace rayster::graph
