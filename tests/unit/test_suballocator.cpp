#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "rhi/suballocator.h"

namespace rayster::rhi {
namespace {

TEST(SubAllocator, HonoursAlignment) {
  SubAllocator a(1 << 20);
  ASSERT_EQ(a.allocate(3, 1), 0u);
  for (uint64_t alignment : {2u, 16u, 256u, 4096u, 65536u}) {
    const auto offset = a.allocate(5, alignment);
    ASSERT_TRUE(offset);
    EXPECT_EQ(*offset % alignment, 0u) << "alignment " << alignment;
  }
}

TEST(SubAllocator, PaddingReturnsToFreeList) {
  SubAllocator a(1024);
  ASSERT_EQ(a.allocate(1, 1), 0u);
  ASSERT_EQ(a.allocate(16, 256), 256u);
  EXPECT_EQ(a.used(), 17u);
  // The 255-byte gap left by the padding is still usable.
  EXPECT_EQ(a.allocate(255, 1), 1u);
}

TEST(SubAllocator, WholeBlockFits) {
  SubAllocator a(4096);
  EXPECT_EQ(a.allocate(4096, 4096), 0u);
  EXPECT_EQ(a.used(), 4096u);
  EXPECT_EQ(a.largestFreeRange(), 0u);
  EXPECT_FALSE(a.allocate(1, 1));
  a.free(0);
  EXPECT_TRUE(a.empty());
  EXPECT_EQ(a.largestFreeRange(), 4096u);
}

TEST(SubAllocator, ExhaustionReturnsNullopt) {
  SubAllocator a(1000);
  EXPECT_FALSE(a.allocate(1001, 1));
  ASSERT_TRUE(a.allocate(600, 1));
  EXPECT_FALSE(a.allocate(401, 1));
  // 400 bytes free from offset 600, but it holds no 1024-aligned offset at all.
  EXPECT_FALSE(a.allocate(100, 1024));
  EXPECT_TRUE(a.allocate(400, 8));
  EXPECT_FALSE(a.allocate(1, 1));
  EXPECT_EQ(a.allocationCount(), 2u);
}

TEST(SubAllocator, BestFitPicksSmallestHole) {
  SubAllocator a(1000);
  // Holes of 300 (at 0), 100 (at 400) and 200 (at 600) separated by live blocks.
  const auto h300 = a.allocate(300, 1);
  ASSERT_EQ(a.allocate(100, 1), 300u);
  const auto h100 = a.allocate(100, 1);
  ASSERT_EQ(a.allocate(100, 1), 500u);
  const auto h200 = a.allocate(200, 1);
  ASSERT_EQ(a.allocate(200, 1), 800u);
  a.free(*h300);
  a.free(*h100);
  a.free(*h200);
  EXPECT_EQ(a.allocate(150, 1), 600u);  // the 200 hole, not the 300 one
  EXPECT_EQ(a.allocate(80, 1), 400u);   // the 100 hole
  EXPECT_EQ(a.allocate(250, 1), 0u);
  EXPECT_EQ(a.largestFreeRange(), 50u);
}

TEST(SubAllocator, CoalescesBackToOneRange) {
  constexpr uint64_t kSize = 1 << 16;
  SubAllocator a(kSize);
  std::mt19937 rng(7);
  std::vector<uint64_t> offsets;
  while (auto offset = a.allocate(1 + rng() % 300, uint64_t(1) << (rng() % 7))) {
    offsets.push_back(*offset);
  }
  ASSERT_GT(offsets.size(), 100u);
  std::shuffle(offsets.begin(), offsets.end(), rng);
  for (uint64_t offset : offsets) a.free(offset);
  EXPECT_TRUE(a.empty());
  EXPECT_EQ(a.used(), 0u);
  EXPECT_EQ(a.largestFreeRange(), kSize);
  EXPECT_EQ(a.allocate(kSize, 1), 0u);
}

// Whether any gap between live allocations could hold `size` at `alignment`.
bool shadowCouldFit(const std::map<uint64_t, uint64_t>& live, uint64_t total, uint64_t size, uint64_t alignment) {
  uint64_t gapStart = 0;
  auto fits = [&](uint64_t begin, uint64_t end) {
    const uint64_t aligned = (begin + alignment - 1) & ~(alignment - 1);
    return aligned <= end && end - aligned >= size;
  };
  for (const auto& [offset, liveSize] : live) {
    if (fits(gapStart, offset)) return true;
    gapStart = offset + liveSize;
  }
  return fits(gapStart, total);
}

TEST(SubAllocator, RandomisedNeverOverlaps) {
  constexpr uint64_t kSize = 1 << 20;
  SubAllocator a(kSize);
  std::map<uint64_t, uint64_t> live;  // shadow model: offset -> size
  std::mt19937_64 rng(12345);
  int exhausted = 0;
  for (int op = 0; op < 10000; ++op) {
    if (live.empty() || rng() % 100 < 55) {
      const uint64_t size = 1 + rng() % (rng() % 8 == 0 ? 65536 : 2048);
      const uint64_t alignment = uint64_t(1) << (rng() % 13);
      const auto offset = a.allocate(size, alignment);
      if (!offset) {
        ASSERT_FALSE(shadowCouldFit(live, kSize, size, alignment)) << "op " << op;
        ++exhausted;
        continue;
      }
      ASSERT_EQ(*offset % alignment, 0u);
      ASSERT_LE(*offset + size, kSize);
      const auto next = live.lower_bound(*offset);
      if (next != live.end()) {
        ASSERT_LE(*offset + size, next->first) << "op " << op;
      }
      if (next != live.begin()) {
        const auto prev = std::prev(next);
        ASSERT_LE(prev->first + prev->second, *offset) << "op " << op;
      }
      live.emplace(*offset, size);
    } else {
      auto it = live.begin();
      std::advance(it, rng() % live.size());
      a.free(it->first);
      live.erase(it);
    }
    const uint64_t liveBytes = std::accumulate(live.begin(), live.end(), uint64_t(0),
                                               [](uint64_t s, const auto& kv) { return s + kv.second; });
    ASSERT_EQ(a.used(), liveBytes);
    ASSERT_EQ(a.allocationCount(), live.size());
  }
  EXPECT_GT(exhausted, 0) << "the block never filled up, so nullopt went untested";
  for (const auto& [offset, size] : live) a.free(offset);
  EXPECT_EQ(a.largestFreeRange(), kSize);
}

TEST(SubAllocatorDeathTest, MisuseAsserts) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  SubAllocator a(1024);
  const auto offset = a.allocate(64, 16);
  ASSERT_TRUE(offset);
  EXPECT_DEATH(a.allocate(0, 16), "0 bytes");
  EXPECT_DEATH(a.allocate(8, 3), "power of two");
  EXPECT_DEATH(a.free(*offset + 1), "unknown or freed");
  a.free(*offset);
  EXPECT_DEATH(a.free(*offset), "unknown or freed");
}

}  // namespace
}  // namespace rayster::rhi
