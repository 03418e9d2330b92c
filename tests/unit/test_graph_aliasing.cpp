// Transient aliasing without a GPU: the lifetime packing (graph/aliasing.h) on synthetic items, and
// the graph's lifetimes and first barriers of aliased images on synthetic graphs.
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graph/aliasing.h"
#include "graph/graph.h"

namespace rayster::graph {
namespace {

constexpr VkDeviceSize kMiB = 1ull << 20;

bool memoryOverlaps(const AliasPlan& plan, const std::vector<AliasItem>& items, size_t a, size_t b) {
  const AliasPlacement& pa = plan.placements[a];
  const AliasPlacement& pb = plan.placements[b];
  return pa.heap == pb.heap && pa.offset < pb.offset + items[b].size && pb.offset < pa.offset + items[a].size;
}

// Every invariant a plan must keep, for any items.
void expectSound(const AliasPlan& plan, const std::vector<AliasItem>& items) {
  ASSERT_EQ(plan.placements.size(), items.size());
  for (size_t i = 0; i < items.size(); ++i) {
    const AliasPlacement& p = plan.placements[i];
    ASSERT_LT(p.heap, plan.heaps.size());
    EXPECT_EQ(plan.heaps[p.heap].memoryTypeBits, items[i].memoryTypeBits) << i;
    EXPECT_LE(p.offset + items[i].size, plan.heaps[p.heap].size) << i;
    EXPECT_EQ(p.offset % items[i].alignment, 0u) << i;
    EXPECT_EQ(plan.heaps[p.heap].alignment % items[i].alignment, 0u) << i;
    for (size_t j = 0; j < i; ++j)
      if (lifetimesOverlap(items[i], items[j])) {
        EXPECT_FALSE(memoryOverlaps(plan, items, i, j)) << i << " and " << j << " are alive together";
      }
  }
  EXPECT_TRUE(planFits(plan, items));
}

TEST(Aliasing, OverlappingLifetimesNeverShare) {
  const std::vector<AliasItem> items = {{8 * kMiB, 256, 1, 0, 3}, {8 * kMiB, 256, 1, 2, 5}, {8 * kMiB, 256, 1, 3, 3}};
  const AliasPlan plan = packByLifetime(items);
  expectSound(plan, items);
  EXPECT_EQ(plan.totalBytes(), 24 * kMiB);  // all three meet in pass 3
}

TEST(Aliasing, DisjointLifetimesShare) {
  const std::vector<AliasItem> items = {{8 * kMiB, 256, 1, 0, 1}, {8 * kMiB, 256, 1, 2, 3}, {4 * kMiB, 256, 1, 4, 4}};
  const AliasPlan plan = packByLifetime(items);
  expectSound(plan, items);
  EXPECT_EQ(plan.totalBytes(), 8 * kMiB);
  EXPECT_EQ(plan.placements[0].offset, plan.placements[1].offset);
  const auto before = aliasedBefore(plan, items);
  EXPECT_TRUE(before[0].empty());
  EXPECT_EQ(before[1], std::vector<uint32_t>{0});
  EXPECT_EQ(before[2], (std::vector<uint32_t>{0, 1}));
}

TEST(Aliasing, ChainOfPassesNeedsTwoImagesNotN) {
  // A post-processing chain: image k is written by pass k and read by pass k + 1.
  std::vector<AliasItem> items;
  for (uint32_t k = 0; k < 12; ++k) items.push_back({16 * kMiB, 4096, 1, k, k + 1});
  const AliasPlan plan = packByLifetime(items);
  expectSound(plan, items);
  EXPECT_EQ(plan.totalBytes(), 32 * kMiB);
}

TEST(Aliasing, SmallItemsFillGapsBesideLargeOnes) {
  // A big image lives throughout; two halves of another's size take turns next to it.
  const std::vector<AliasItem> items = {
      {32 * kMiB, 256, 1, 0, 9}, {16 * kMiB, 256, 1, 0, 4}, {8 * kMiB, 256, 1, 5, 9}, {8 * kMiB, 256, 1, 5, 9}};
  const AliasPlan plan = packByLifetime(items);
  expectSound(plan, items);
  EXPECT_EQ(plan.totalBytes(), 48 * kMiB);
}

TEST(Aliasing, DifferentMemoryTypesGetDifferentHeaps) {
  const std::vector<AliasItem> items = {{kMiB, 256, 0b01, 0, 0}, {kMiB, 256, 0b10, 1, 1}};
  const AliasPlan plan = packByLifetime(items);
  expectSound(plan, items);
  EXPECT_EQ(plan.heaps.size(), 2u);
  EXPECT_EQ(plan.totalBytes(), 2 * kMiB);
  EXPECT_TRUE(aliasedBefore(plan, items)[1].empty());
}

TEST(Aliasing, AlignmentIsKept) {
  const std::vector<AliasItem> items = {{1000, 1, 1, 0, 5}, {3000, 4096, 1, 0, 5}, {500, 512, 1, 0, 5}};
  const AliasPlan plan = packByLifetime(items);
  expectSound(plan, items);
}

TEST(Aliasing, RandomItemsAreSoundAndNeverWorseThanSeparate) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<AliasItem> items(std::uniform_int_distribution<size_t>(1, 30)(rng));
    VkDeviceSize separate = 0;
    for (AliasItem& it : items) {
      it.size = std::uniform_int_distribution<VkDeviceSize>(1, 64)(rng) * 4096 +
                std::uniform_int_distribution<VkDeviceSize>(0, 100)(rng);
      it.alignment = VkDeviceSize(1) << std::uniform_int_distribution<int>(0, 16)(rng);
      it.memoryTypeBits = std::uniform_int_distribution<uint32_t>(1, 2)(rng);
      it.first = std::uniform_int_distribution<uint32_t>(0, 20)(rng);
      it.last = it.first + std::uniform_int_distribution<uint32_t>(0, 8)(rng);
      separate += it.size + it.alignment;  // generous: separate images padded to their alignment
    }
    const AliasPlan plan = packByLifetime(items);
    expectSound(plan, items);
    EXPECT_LE(plan.totalBytes(), separate);
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(Aliasing, PlanFitsRejectsLifetimesThatNowOverlap) {
  std::vector<AliasItem> items = {{kMiB, 256, 1, 0, 1}, {kMiB, 256, 1, 2, 3}};
  const AliasPlan plan = packByLifetime(items);
  ASSERT_TRUE(planFits(plan, items));
  items[1].first = 1;  // now alive together with item 0, which shares its memory
  EXPECT_FALSE(planFits(plan, items));
  items[1].first = 3;  // disjoint again (shorter): the plan still holds
  EXPECT_TRUE(planFits(plan, items));
  items.push_back({kMiB, 256, 1, 0, 0});
  EXPECT_FALSE(planFits(plan, items));
}

rhi::ImageDesc storageDesc() {
  rhi::ImageDesc d;
  d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  d.width = 64;
  d.height = 32;
  d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  return d;
}

void addPass(RenderGraph& graph, const std::string& name, const std::function<void(PassBuilder&)>& setup) {
  graph.addPass(name, setup, [](PassContext&) { FAIL() << "execute callback ran during compile()"; });
}

TEST(GraphAliasing, LifetimesFollowLivePassesAndSkipImports) {
  RenderGraph graph(nullptr, nullptr);
  rhi::Image external;  // never touched by planning
  ResourceState externalState;
  ImageHandle a = graph.createImage("a", storageDesc());
  ImageHandle unused = graph.createImage("unused", storageDesc());
  ImageHandle b = graph.createImage("b", storageDesc());
  // importImage needs a real image only for its description: use a default one.
  ImageHandle history = graph.importImage("history", &external, &externalState);
  addPass(graph, "dead", [&](PassBuilder& p) { p.write(unused, Use::StorageWriteCompute); });
  addPass(graph, "writeA", [&](PassBuilder& p) { p.write(a, Use::StorageWriteCompute); });
  addPass(graph, "aToB", [&](PassBuilder& p) {
    p.read(a, Use::SampledCompute);
    p.write(b, Use::StorageWriteCompute);
  });
  addPass(graph, "bToHistory", [&](PassBuilder& p) {
    p.read(b, Use::SampledCompute);
    p.write(history, Use::StorageWriteCompute);
  });
  const auto lifetimes = graph.transientLifetimes();
  ASSERT_EQ(lifetimes.size(), 2u);  // "unused" only feeds a culled pass; "history" is imported
  EXPECT_EQ(lifetimes[0].image, a.id);
  EXPECT_EQ(lifetimes[0].first, 0u);  // positions among live passes: "dead" is culled
  EXPECT_EQ(lifetimes[0].last, 1u);
  EXPECT_EQ(lifetimes[1].image, b.id);
  EXPECT_EQ(lifetimes[1].first, 1u);
  EXPECT_EQ(lifetimes[1].last, 2u);
}

TEST(GraphAliasing, AliasedImageFirstBarrierWaitsForThePreviousOccupantAndDiscards) {
  RenderGraph graph(nullptr, nullptr);
  ImageHandle a = graph.createImage("a", storageDesc());
  ImageHandle mid = graph.createImage("mid", storageDesc());
  ImageHandle c = graph.createImage("c", storageDesc());
  addPass(graph, "writeA", [&](PassBuilder& p) { p.write(a, Use::StorageWriteRayTracing); });
  addPass(graph, "aToMid", [&](PassBuilder& p) {
    p.read(a, Use::SampledFragment);
    p.write(mid, Use::StorageWriteCompute);
  });
  addPass(graph, "midToC", [&](PassBuilder& p) {
    p.read(mid, Use::SampledCompute);
    p.write(c, Use::StorageWriteCompute);
  });
  addPass(graph, "readC", [&](PassBuilder& p) {
    p.read(c, Use::SampledCompute);
    p.sideEffect();
  });
  // Build the aliasing the pool would: c reuses a's memory.
  std::vector<AliasItem> items;
  for (const auto& t : graph.transientLifetimes()) items.push_back({kMiB, 256, 1, t.first, t.last});
  const AliasPlan plan = packByLifetime(items);
  const auto before = aliasedBefore(plan, items);
  ASSERT_EQ(before[2], std::vector<uint32_t>{0}) << "c must take a's memory";
  std::vector<std::vector<uint32_t>> byImage(3);
  byImage[c.id] = {a.id};

  auto firstBarrierOf = [](const std::vector<PlannedPass>& passes, uint32_t image) -> const Barrier* {
    for (const PlannedPass& pp : passes)
      for (const PlannedBarrier& b : pp.barriers)
        if (b.isImage && b.resource == image) return &b.barrier;
    return nullptr;
  };
  const std::vector<PlannedPass> unaliased = graph.compile();
  const Barrier* plain = firstBarrierOf(unaliased, c.id);
  ASSERT_NE(plain, nullptr);
  EXPECT_EQ(plain->srcStages, VK_PIPELINE_STAGE_2_NONE);  // a fresh image waits on nothing

  const std::vector<PlannedPass> aliased = graph.compile(&byImage);
  const Barrier* first = firstBarrierOf(aliased, c.id);
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);  // a's contents are discarded
  EXPECT_EQ(first->newLayout, VK_IMAGE_LAYOUT_GENERAL);
  // a was last read by the fragment stage (after a barrier that ordered its ray-tracing write
  // before that read): the new occupant's transition waits for that reader.
  EXPECT_TRUE(first->srcStages & VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
  EXPECT_TRUE(first->dstStages & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  // Nothing else changes.
  ASSERT_EQ(aliased.size(), unaliased.size());
  for (size_t i = 0; i < aliased.size(); ++i) EXPECT_EQ(aliased[i].barriers.size(), unaliased[i].barriers.size());
}

}  // namespace
}  // namespace rayster::graph
