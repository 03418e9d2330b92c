// Aliased transients on the real device (lavapipe here) under the validation layer with
// synchronization validation: images with disjoint lifetimes share memory, each keeps the
// contents its own passes wrote, and the frame's images are kept while the graph stays the same.
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graph/graph.h"
#include "rhi/commands.h"
#include "rhi/context.h"

namespace rayster::graph {
namespace {

constexpr uint32_t kW = 64, kH = 48;

class GraphAliasingDevice : public ::testing::Test {
 protected:
  void SetUp() override {
    auto created = rhi::Context::create({/*validation*/ true, /*requireRayTracing*/ false, ""});
    if (!created) GTEST_SKIP() << "no Vulkan device: " << created.error().message;
    ctx_ = std::move(created.value());
    commands_ = std::make_unique<rhi::CommandList>(*ctx_);
  }
  void TearDown() override {
    if (!ctx_) return;
    ctx_->waitIdle();
    EXPECT_EQ(ctx_->validationErrors(), 0u) << "validation errors during the test";
    commands_.reset();
  }

  static rhi::ImageDesc desc(VkFormat format = VK_FORMAT_R8G8B8A8_UNORM) {
    // Sampled: every rhi::Image gets a view, which needs a viewable usage.
    return {format, kW, kH, 1,
            VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT};
  }

  // A frame of `count` steps: each clears its own transient to a colour, copies it to a host buffer
  // and is done with it, so no two transients are alive together.
  void frame(TransientPool& pool, uint32_t count, std::vector<rhi::Buffer>& buffers, uint32_t seed) {
    RenderGraph graph(ctx_.get(), &pool);
    std::vector<ResourceState> states(count);
    for (uint32_t i = 0; i < count; ++i) {
      ImageHandle img = graph.createImage("step" + std::to_string(i), desc());
      BufferHandle buf = graph.importBuffer("readback", &buffers[i], &states[i]);
      const VkClearColorValue colour{{float(i + 1) / 16.0f, float(seed) / 16.0f, 0.5f, 1.0f}};
      graph.addPass(
          "clear", [&](PassBuilder& b) { b.write(img, Use::TransferDst); },
          [img, colour](PassContext& pc) {
            const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            vkCmdClearColorImage(pc.cmd, pc.image(img).handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &colour, 1,
                                 &range);
          });
      graph.addPass(
          "copy",
          [&](PassBuilder& b) {
            b.read(img, Use::TransferSrc);
            b.write(buf, Use::TransferDst);
          },
          [img, buf](PassContext& pc) {
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {kW, kH, 1};
            vkCmdCopyImageToBuffer(pc.cmd, pc.image(img).handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   pc.buffer(buf).handle(), 1, &region);
          });
      graph.addPass(
          "host",
          [&](PassBuilder& b) {
            b.read(buf, Use::HostRead);
            b.sideEffect();
          },
          [](PassContext&) {});
    }
    VkCommandBuffer cmd = commands_->begin();
    graph.execute(cmd, nullptr);
    ctx_->wait(commands_->submit());
    ctx_->collectGarbage();
    for (uint32_t i = 0; i < count; ++i) {
      const uint8_t* px = static_cast<const uint8_t*>(buffers[i].mapped());
      const uint8_t r = uint8_t(std::lround((i + 1) / 16.0f * 255.0f)), g = uint8_t(std::lround(seed / 16.0f * 255.0f));
      for (size_t p = 0; p < size_t(kW) * kH; p += 97) {
        ASSERT_EQ(px[p * 4 + 0], r) << "step " << i << " pixel " << p;
        ASSERT_EQ(px[p * 4 + 1], g) << "step " << i << " pixel " << p;
        ASSERT_EQ(px[p * 4 + 2], 128) << "step " << i << " pixel " << p;
      }
    }
  }

  std::unique_ptr<rhi::Context> ctx_;
  std::unique_ptr<rhi::CommandList> commands_;
};

TEST_F(GraphAliasingDevice, DisjointTransientsShareMemoryAndKeepTheirContents) {
  constexpr uint32_t kSteps = 5;
  std::vector<rhi::Buffer> buffers;
  for (uint32_t i = 0; i < kSteps; ++i)
    buffers.emplace_back(*ctx_, kW * kH * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "readback");
  TransientPool aliased(true), separate(false);
  frame(aliased, kSteps, buffers, 1);
  frame(separate, kSteps, buffers, 2);
  const FrameMemoryReport& a = aliased.report();
  const FrameMemoryReport& s = separate.report();
  ASSERT_EQ(a.entries.size(), kSteps);
  const uint64_t one = a.entries[0].bytes;
  EXPECT_GE(one, uint64_t(kW) * kH * 4);
  EXPECT_EQ(a.transientUnaliasedBytes, kSteps * one);
  EXPECT_EQ(a.transientBytes, one) << "five images used one after another need the memory of one";
  EXPECT_EQ(s.transientBytes, kSteps * one);
  for (const FrameMemoryEntry& e : a.entries) EXPECT_EQ(e.offset, 0u);

  // The same frame again keeps the images; a different one re-creates them.
  EXPECT_EQ(aliased.rebuilds(), 1u);
  frame(aliased, kSteps, buffers, 3);
  EXPECT_EQ(aliased.rebuilds(), 1u);
  frame(aliased, kSteps - 1, buffers, 4);
  EXPECT_EQ(aliased.rebuilds(), 2u);
  EXPECT_EQ(aliased.report().entries.size(), kSteps - 1);
}

TEST_F(GraphAliasingDevice, ImportedImagesAreReportedNotAliased) {
  rhi::Image history(*ctx_, desc(VK_FORMAT_R16G16B16A16_SFLOAT), "history");
  ResourceState historyState;
  rhi::Buffer buffer(*ctx_, kW * kH * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "readback");
  ResourceState bufferState;
  TransientPool pool(true);
  RenderGraph graph(ctx_.get(), &pool);
  ImageHandle h = graph.importImage("history", &history, &historyState);
  // Imported twice (a history is both last frame's and this frame's image in a one-image setup):
  // the report counts it once. Only one handle is used, so the graph tracks one state.
  graph.importImage("history-again", &history, &historyState);
  BufferHandle buf = graph.importBuffer("readback", &buffer, &bufferState);
  graph.addPass(
      "clear", [&](PassBuilder& b) { b.write(h, Use::TransferDst); },
      [h](PassContext& pc) {
        const VkClearColorValue colour{{0.25f, 0.5f, 0.75f, 1.0f}};
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(pc.cmd, pc.image(h).handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &colour, 1, &range);
      });
  graph.addPass(
      "copy",
      [&](PassBuilder& b) {
        b.read(h, Use::TransferSrc);
        b.write(buf, Use::TransferDst);
        b.sideEffect();
      },
      [h, buf](PassContext& pc) {
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {kW, kH, 1};
        vkCmdCopyImageToBuffer(pc.cmd, pc.image(h).handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               pc.buffer(buf).handle(), 1, &region);
      });
  VkCommandBuffer cmd = commands_->begin();
  graph.execute(cmd, nullptr);
  ctx_->wait(commands_->submit());
  const FrameMemoryReport& r = pool.report();
  EXPECT_EQ(r.transientBytes, 0u);
  ASSERT_EQ(r.entries.size(), 1u) << "one image imported twice counts once";
  EXPECT_TRUE(r.entries[0].imported);
  EXPECT_EQ(r.importedBytes, history.bytes());
  EXPECT_GE(history.bytes(), uint64_t(kW) * kH * 8);
  EXPECT_EQ(r.frameBytes(), history.bytes());
  const std::string listing = formatMemoryReport(r);
  EXPECT_NE(listing.find("history"), std::string::npos) << listing;
  EXPECT_NE(listing.find("RGBA16F"), std::string::npos) << listing;
}

// A history through three frames: each frame copies what the frame before wrote, then writes its own
// colour; a reset empties it, and a frame that does not ask for it releases its memory.
TEST_F(GraphAliasingDevice, HistoryReadsTheFrameBeforeAndIsReleasedWhenUnused) {
  HistoryStore store;
  TransientPool pool(true);
  rhi::Buffer buffer(*ctx_, kW * kH * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "readback");
  ResourceState bufferState;
  auto frame = [&](uint32_t f, bool reset, bool ask) -> uint32_t {
    store.beginFrame(f, reset);
    RenderGraph graph(ctx_.get(), &pool, &store);
    uint32_t frames = 0;
    if (ask) {
      const RenderGraph::History h = graph.history("taa", desc());
      frames = h.frames;
      BufferHandle buf = graph.importBuffer("readback", &buffer, &bufferState);
      if (h.frames > 0)
        graph.addPass(
            "copy-previous",
            [&](PassBuilder& b) {
              b.read(h.previous, Use::TransferSrc);
              b.write(buf, Use::TransferDst);
            },
            [h, buf](PassContext& pc) {
              VkBufferImageCopy region{};
              region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
              region.imageExtent = {kW, kH, 1};
              vkCmdCopyImageToBuffer(pc.cmd, pc.image(h.previous).handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                     pc.buffer(buf).handle(), 1, &region);
            });
      graph.addPass(
          "write-next", [&](PassBuilder& b) { b.write(h.next, Use::TransferDst); },
          [h, f](PassContext& pc) {
            const VkClearColorValue colour{{float(f + 1) / 16.0f, 0.0f, 0.0f, 1.0f}};
            const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            vkCmdClearColorImage(pc.cmd, pc.image(h.next).handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &colour, 1,
                                 &range);
          });
    }
    VkCommandBuffer cmd = commands_->begin();
    graph.execute(cmd, nullptr);
    ctx_->wait(commands_->submit());
    store.endFrame();
    ctx_->collectGarbage();
    return frames;
  };
  auto red = [&] { return static_cast<const uint8_t*>(buffer.mapped())[4 * (kW * kH / 2)]; };
  EXPECT_EQ(frame(0, true, true), 0u) << "the first frame has no history";
  EXPECT_EQ(store.frames("taa"), 1u);
  EXPECT_EQ(store.bytes(), 2 * rhi::Image(*ctx_, desc(), "probe").bytes());
  EXPECT_EQ(frame(1, false, true), 1u);
  EXPECT_EQ(red(), uint8_t(std::lround(1 / 16.0f * 255.0f))) << "frame 1 reads what frame 0 wrote";
  EXPECT_EQ(frame(2, false, true), 2u);
  EXPECT_EQ(red(), uint8_t(std::lround(2 / 16.0f * 255.0f))) << "frame 2 reads what frame 1 wrote, not frame 0";
  EXPECT_EQ(frame(3, true, true), 0u) << "a reset (camera cut) empties the history";
  frame(4, false, false);
  EXPECT_EQ(store.frames("taa"), 0u);
  EXPECT_EQ(store.bytes(), 0u) << "a history no frame asked for is released";
}

}  // namespace
}  // namespace rayster::graph
