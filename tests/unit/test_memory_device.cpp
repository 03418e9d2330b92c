// MemoryAllocator and buffers on the real device (lavapipe here): block sharing, dedicated
// allocations, deferred destruction through Context::retire, mapping, device addresses and an
// upload/readback round trip, all under the validation layer.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>

#include "rhi/commands.h"
#include "rhi/context.h"
#include "rhi/memory.h"
#include "rhi/resources.h"
#include "rhi/upload.h"

namespace rayster::rhi {
namespace {

constexpr VkDeviceSize kMiB = 1ull << 20;
constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

class MemoryDevice : public ::testing::Test {
 protected:
  void SetUp() override {
    auto created = Context::create({/*validation*/ true, /*requireRayTracing*/ false, ""});
    if (!created) GTEST_SKIP() << "no Vulkan device: " << created.error().message;
    ctx_ = std::move(created.value());
    EXPECT_TRUE(ctx_->validationEnabled());
    errorsBefore_ = ctx_->validationErrors();
  }
  void TearDown() override {
    if (!ctx_) return;
    ctx_->waitIdle();
    ctx_->collectGarbage();
    EXPECT_EQ(ctx_->validationErrors(), errorsBefore_) << "validation errors during the test";
    EXPECT_EQ(ctx_->validationErrors(), 0u);
    ctx_.reset();
  }
  MemoryStats stats() { return ctx_->memory().stats(); }
  // Destroys retired objects; stats only drop after this.
  void flush() {
    ctx_->waitIdle();
    ctx_->collectGarbage();
  }

  std::unique_ptr<Context> ctx_;
  uint32_t errorsBefore_ = 0;
};

TEST_F(MemoryDevice, SmallBuffersShareOneBlock) {
  const MemoryStats before = stats();
  std::vector<Buffer> buffers;
  buffers.emplace_back(*ctx_, kMiB, kStorage, MemoryUsage::GpuOnly, "small0");
  const MemoryStats first = stats();
  EXPECT_LE(first.blockCount, before.blockCount + 1);
  EXPECT_GE(first.usedBytes, before.usedBytes + kMiB);
  EXPECT_EQ(first.dedicatedCount, before.dedicatedCount);
  for (int i = 1; i < 4; ++i) buffers.emplace_back(*ctx_, kMiB, kStorage, MemoryUsage::GpuOnly, "small");
  const MemoryStats after = stats();
  EXPECT_EQ(after.blockCount, first.blockCount) << "1 MiB buffers of one memory type must share a block";
  EXPECT_EQ(after.reservedBytes, first.reservedBytes);
  EXPECT_EQ(after.dedicatedCount, before.dedicatedCount);
  EXPECT_GE(after.usedBytes, before.usedBytes + 4 * kMiB);
  EXPECT_LE(after.usedBytes, after.reservedBytes);

  // Sub-allocations of one block must not overlap: device address ranges are disjoint.
  for (size_t i = 0; i < buffers.size(); ++i)
    for (size_t j = i + 1; j < buffers.size(); ++j) {
      const VkDeviceAddress a = buffers[i].address(), b = buffers[j].address();
      EXPECT_TRUE(a + buffers[i].size() <= b || b + buffers[j].size() <= a) << i << " overlaps " << j;
    }

  buffers.clear();
  // Destruction is deferred: nothing returns until the garbage is collected.
  EXPECT_EQ(stats().usedBytes, after.usedBytes);
  flush();
  const MemoryStats freed = stats();
  EXPECT_EQ(freed.usedBytes, before.usedBytes);
  EXPECT_EQ(freed.blockCount, after.blockCount) << "empty blocks are kept for reuse";

  // The freed space is reused: another small buffer needs no new block.
  Buffer again(*ctx_, kMiB, kStorage, MemoryUsage::GpuOnly, "again");
  EXPECT_EQ(stats().blockCount, after.blockCount);
  EXPECT_EQ(stats().reservedBytes, after.reservedBytes);
}

TEST_F(MemoryDevice, EmptiedBlocksBeyondOneSpareAreReleased) {
  flush();
  ctx_->memory().releaseEmptyBlocks();
  const MemoryStats before = stats();
  // Staging for a big upload: 12 host-visible buffers of 15 MiB (under the dedicated threshold)
  // need several 64 MiB blocks.
  std::vector<Buffer> staging;
  for (int i = 0; i < 12; ++i)
    staging.emplace_back(*ctx_, 15 * kMiB, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging");
  const MemoryStats during = stats();
  ASSERT_GE(during.blockCount, before.blockCount + 2);
  EXPECT_EQ(during.dedicatedCount, before.dedicatedCount);
  staging.clear();
  flush();
  const MemoryStats after = stats();
  EXPECT_EQ(after.usedBytes, before.usedBytes);
  EXPECT_EQ(after.blockCount, before.blockCount + 1) << "one emptied block stays as a spare, the rest are released";
  EXPECT_EQ(after.reservedBytes, before.reservedBytes + MemoryAllocator::kBlockSize);
  // After uploads, the spare goes too.
  EXPECT_EQ(ctx_->memory().releaseEmptyBlocks(), MemoryAllocator::kBlockSize);
  EXPECT_EQ(stats().blockCount, before.blockCount);
  EXPECT_EQ(stats().reservedBytes, before.reservedBytes);
  EXPECT_EQ(ctx_->memory().releaseEmptyBlocks(), 0u);
  // A released block's slot serves new blocks, mapped and usable.
  std::vector<Buffer> again;
  for (int i = 0; i < 5; ++i) {
    again.emplace_back(*ctx_, 15 * kMiB, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "again");
    ASSERT_NE(again.back().mapped(), nullptr);
    std::memset(again.back().mapped(), i, 15 * kMiB);
  }
  for (int i = 0; i < 5; ++i) EXPECT_EQ(static_cast<const uint8_t*>(again[size_t(i)].mapped())[15 * kMiB - 1], i);
  EXPECT_GE(stats().blockCount, before.blockCount + 1);
}

TEST_F(MemoryDevice, UploadBuffersDoNotClobberEachOther) {
  std::vector<Buffer> buffers;
  for (int i = 0; i < 4; ++i) buffers.emplace_back(*ctx_, 64 * 1024, kStorage, MemoryUsage::Upload, "upload");
  for (size_t i = 0; i < buffers.size(); ++i) {
    ASSERT_NE(buffers[i].mapped(), nullptr);
    std::memset(buffers[i].mapped(), int(0x10 + i), buffers[i].size());
  }
  for (size_t i = 0; i < buffers.size(); ++i) {
    const auto* bytes = static_cast<const uint8_t*>(buffers[i].mapped());
    for (VkDeviceSize k = 0; k < buffers[i].size(); k += 997)
      ASSERT_EQ(bytes[k], uint8_t(0x10 + i)) << "buffer " << i << " byte " << k;
    ASSERT_EQ(bytes[buffers[i].size() - 1], uint8_t(0x10 + i));
  }
}

TEST_F(MemoryDevice, LargeBufferIsDedicated) {
  const MemoryStats before = stats();
  const VkDeviceSize size = MemoryAllocator::kDedicatedThreshold;
  auto big = std::make_unique<Buffer>(*ctx_, size, kStorage, MemoryUsage::GpuOnly, "big");
  const MemoryStats during = stats();
  EXPECT_EQ(during.dedicatedCount, before.dedicatedCount + 1);
  EXPECT_EQ(during.blockCount, before.blockCount) << "a dedicated allocation must not create a block";
  EXPECT_GE(during.usedBytes, before.usedBytes + size);
  EXPECT_GE(during.reservedBytes, before.reservedBytes + size);
  EXPECT_NE(big->address(), 0u);

  // A buffer well below the threshold is sub-allocated.
  Buffer below(*ctx_, MemoryAllocator::kDedicatedThreshold / 2, kStorage, MemoryUsage::GpuOnly, "below");
  const MemoryStats withBelow = stats();
  EXPECT_EQ(withBelow.dedicatedCount, during.dedicatedCount);

  big.reset();
  ctx_->waitIdle();
  EXPECT_EQ(stats().dedicatedCount, during.dedicatedCount) << "freed before collectGarbage()";
  EXPECT_EQ(stats().usedBytes, withBelow.usedBytes);
  ctx_->collectGarbage();
  const MemoryStats after = stats();
  EXPECT_EQ(after.dedicatedCount, before.dedicatedCount);
  EXPECT_EQ(after.usedBytes, withBelow.usedBytes - (during.usedBytes - before.usedBytes));
  EXPECT_EQ(after.reservedBytes, withBelow.reservedBytes - (during.reservedBytes - before.reservedBytes))
      << "dedicated memory goes back to the driver";
}

TEST_F(MemoryDevice, UsedBytesReturnAfterDestruction) {
  const MemoryStats before = stats();
  {
    Buffer a(*ctx_, 3 * kMiB, kStorage, MemoryUsage::GpuOnly, "a");
    Buffer b(*ctx_, 100 * 1024, kStorage, MemoryUsage::Upload, "b");
    Buffer c(*ctx_, 20 * kMiB, kStorage, MemoryUsage::Readback, "c");
    EXPECT_GE(stats().usedBytes, before.usedBytes + 3 * kMiB + 100 * 1024 + 20 * kMiB);
  }
  EXPECT_GT(stats().usedBytes, before.usedBytes) << "destruction must wait for collectGarbage()";
  flush();
  const MemoryStats after = stats();
  EXPECT_EQ(after.usedBytes, before.usedBytes);
  EXPECT_EQ(after.dedicatedCount, before.dedicatedCount);
  // Blocks stay, dedicated memory goes back to the driver.
  EXPECT_EQ(after.reservedBytes,
            before.reservedBytes + uint64_t(after.blockCount - before.blockCount) * MemoryAllocator::kBlockSize);
}

TEST_F(MemoryDevice, MappingAndAddresses) {
  Buffer upload(*ctx_, 4096, kStorage, MemoryUsage::Upload, "upload");
  Buffer readback(*ctx_, 4096, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "readback");
  Buffer gpu(*ctx_, 4096, kStorage, MemoryUsage::GpuOnly, "gpu");
  Buffer bigUpload(*ctx_, MemoryAllocator::kDedicatedThreshold, kStorage, MemoryUsage::Upload, "bigUpload");
  EXPECT_NE(upload.mapped(), nullptr);
  EXPECT_NE(readback.mapped(), nullptr);
  EXPECT_NE(bigUpload.mapped(), nullptr) << "dedicated host-visible memory must be mapped too";
  EXPECT_NE(gpu.address(), 0u);
  EXPECT_NE(upload.address(), 0u);
  EXPECT_NE(gpu.address(), upload.address());
  EXPECT_EQ(gpu.size(), 4096u);
  // Mapped memory is writable end to end.
  std::memset(bigUpload.mapped(), 0xab, bigUpload.size());
  EXPECT_EQ(static_cast<uint8_t*>(bigUpload.mapped())[bigUpload.size() - 1], 0xab);
}

// Uploads `bytes` with createBufferWithData and reads them back through a Readback buffer.
std::vector<std::byte> roundTrip(Context& ctx, const std::vector<std::byte>& bytes) {
  Buffer gpu = createBufferWithData(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                    "roundTrip");
  EXPECT_GE(gpu.size(), bytes.size());
  EXPECT_NE(gpu.address(), 0u);
  Buffer readback(ctx, bytes.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "readback");
  std::memset(readback.mapped(), 0xcd, bytes.size());
  {
    OneShot cmd(ctx);
    VkBufferCopy region{0, 0, bytes.size()};
    vkCmdCopyBuffer(cmd, gpu.handle(), readback.handle(), 1, &region);
    cmd.submitAndWait();
  }
  std::vector<std::byte> out(bytes.size());
  std::memcpy(out.data(), readback.mapped(), bytes.size());
  return out;
}

TEST_F(MemoryDevice, CreateBufferWithDataRoundTrip) {
  for (size_t size : {size_t(5), size_t(1000), size_t(256 * 1024 + 3)}) {
    std::vector<std::byte> bytes(size);
    for (size_t i = 0; i < size; ++i) bytes[i] = std::byte(uint8_t((i * 131 + 7) ^ (i >> 8)));
    EXPECT_EQ(roundTrip(*ctx_, bytes), bytes) << "size " << size;
  }
  flush();
}

TEST_F(MemoryDevice, LargeRoundTripThroughDedicatedMemory) {
  std::vector<uint32_t> words(MemoryAllocator::kDedicatedThreshold / 4);
  std::iota(words.begin(), words.end(), 0x1234u);
  std::vector<std::byte> bytes(words.size() * 4);
  std::memcpy(bytes.data(), words.data(), bytes.size());
  const uint32_t dedicatedBefore = stats().dedicatedCount;
  const std::vector<std::byte> out = roundTrip(*ctx_, bytes);
  ASSERT_EQ(out.size(), bytes.size());
  EXPECT_TRUE(std::memcmp(out.data(), bytes.data(), bytes.size()) == 0);
  flush();
  EXPECT_EQ(stats().dedicatedCount, dedicatedBefore);
}

// rhi::UploadBatch: many buffers through shared staging chunks (one larger than a chunk, so it
// gets its own), read back by a submission made after the batch's without any host wait between
// them: the batch's closing barrier must order its copies first (validation, with synchronization
// checks, is on in this fixture).
TEST_F(MemoryDevice, UploadBatchRoundTripsAcrossChunksWithoutAHostWait) {
  std::vector<std::vector<std::byte>> inputs;
  for (size_t i = 0; i < 60; ++i) inputs.emplace_back(i % 3 == 0 ? 5 : i % 3 == 1 ? 1000 : 5 * 1024 * 1024 + 3);
  inputs.emplace_back(size_t(65) << 20);  // larger than a 64 MiB chunk
  for (size_t b = 0; b < inputs.size(); ++b)
    for (size_t i = 0; i < inputs[b].size(); ++i) inputs[b][i] = std::byte(uint8_t(i * 131 + b * 7 + (i >> 10)));
  std::vector<Buffer> gpu;
  UploadBatch batch(*ctx_);
  for (const auto& bytes : inputs)
    gpu.push_back(batch.buffer(bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, "batch"));
  batch.submit();
  EXPECT_GE(batch.submissions(), 3u);
  std::vector<Buffer> readback;
  {
    OneShot cmd(*ctx_);
    for (size_t b = 0; b < inputs.size(); ++b) {
      readback.emplace_back(*ctx_, inputs[b].size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "rb");
      VkBufferCopy region{0, 0, inputs[b].size()};
      vkCmdCopyBuffer(cmd, gpu[b].handle(), readback.back().handle(), 1, &region);
    }
    cmd.submitAndWait();
  }
  for (size_t b = 0; b < inputs.size(); ++b)
    EXPECT_TRUE(std::memcmp(readback[b].mapped(), inputs[b].data(), inputs[b].size()) == 0) << "buffer " << b;
  batch.wait();
  EXPECT_EQ(ctx_->validationErrors(), 0u);
  gpu.clear();
  readback.clear();
  flush();
}

}  // namespace
}  // namespace rayster::rhi
