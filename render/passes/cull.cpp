// Two-phase GPU culling into indirect draw lists (render/passes/cull.h).
#include "render/passes/cull.h"

#include <algorithm>
#include <cstring>

#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "rhi/context.h"
#include "shaders/shared/types.h"

namespace rayster::render {

namespace {
constexpr VkDeviceSize kCountBytes = gpu::kCullLists * sizeof(uint32_t);
}

std::shared_ptr<CullBuffers> createCullBuffers(rhi::Context& ctx, uint32_t drawCount) {
  auto c = std::make_shared<CullBuffers>();
  c->drawCount = drawCount;
  c->ctx = &ctx;
  const VkDeviceSize rows = std::max(drawCount, 1u);
  const VkDeviceSize slots = gpu::kCullLists * rows;
  constexpr VkBufferUsageFlags kIndirect = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  constexpr VkBufferUsageFlags kCopied =
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  c->commands =
      rhi::Buffer(ctx, slots * sizeof(VkDrawIndirectCommand), kIndirect, rhi::MemoryUsage::GpuOnly, "cull-commands");
  c->drawIds = rhi::Buffer(ctx, slots * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, rhi::MemoryUsage::GpuOnly,
                           "cull-draw-ids");
  c->counts = rhi::Buffer(ctx, kCountBytes, kIndirect | kCopied, rhi::MemoryUsage::GpuOnly, "cull-counts");
  c->visibility = rhi::Buffer(ctx, rows * sizeof(uint32_t), kCopied, rhi::MemoryUsage::GpuOnly, "cull-visibility");
  const VkDeviceSize readbackBytes = kCountBytes + rows * sizeof(uint32_t);
  c->readback =
      rhi::Buffer(ctx, readbackBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "cull-readback");
  std::memset(c->readback.mapped(), 0, readbackBytes);
  return c;
}

namespace {

uint32_t hizFloats(VkExtent2D size) {
  uint64_t n = 0;
  for (uint32_t level = 0;; ++level) {
    const uint32_t w = std::max((size.width + (1u << level) - 1) >> level, 1u);
    const uint32_t h = std::max((size.height + (1u << level) - 1) >> level, 1u);
    n += uint64_t(w) * h;
    if (w == 1 && h == 1) return uint32_t(n);
  }
}

// The pyramid is rebuilt every frame before it is read, so only its size matters.
void ensureHiz(CullBuffers& c, VkExtent2D size) {
  if (c.hiz && c.hizSize.width == size.width && c.hizSize.height == size.height) return;
  c.hiz = rhi::Buffer(*c.ctx, sizeof(float) * VkDeviceSize(hizFloats(size)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                      rhi::MemoryUsage::GpuOnly, "hiz");
  c.hizState = {};
  c.hizSize = size;
}

void dispatchCull(graph::PassContext& pc, const FrameInputs& in, const CulledDraws& out, uint32_t flags) {
  const CullBuffers& c = *in.scene.cull;
  const gpu::CullPush push{in.scene.drawRecords.address(),
                           pc.buffer(out.commands).address(),
                           pc.buffer(out.drawIds).address(),
                           pc.buffer(out.counts).address(),
                           pc.buffer(out.visibility).address(),
                           out.hiz.valid() ? pc.buffer(out.hiz).address() : 0,
                           c.drawCount,
                           flags};
  pc.push(push);
  vkCmdDispatch(pc.cmd, (c.drawCount + gpu::kCullGroupSize - 1) / gpu::kCullGroupSize, 1, 1);
}

}  // namespace

CulledDraws cullDraws(graph::RenderGraph& graph, const FrameInputs& in) {
  CullBuffers& c = *in.scene.cull;
  CulledDraws out;
  if (c.enabled) {
    ensureHiz(c, in.size);
    out.hiz = graph.importBuffer("hiz", &c.hiz, &c.hizState);
  }
  out.commands = graph.importBuffer("cull-commands", &c.commands, &c.commandsState);
  out.drawIds = graph.importBuffer("cull-draw-ids", &c.drawIds, &c.drawIdsState);
  out.counts = graph.importBuffer("cull-counts", &c.counts, &c.countsState);
  out.visibility = graph.importBuffer("cull-visibility", &c.visibility, &c.visibilityState);
  const bool fresh = c.visibilityFresh;
  c.visibilityFresh = false;
  graph.addPass(
      "cull-clear",
      [&](graph::PassBuilder& b) {
        b.write(out.counts, graph::Use::TransferDst);
        if (fresh) b.write(out.visibility, graph::Use::TransferDst);
      },
      [out, fresh](graph::PassContext& pc) {
        vkCmdFillBuffer(pc.cmd, pc.buffer(out.counts).handle(), 0, VK_WHOLE_SIZE, 0);
        // Everything "visible last frame": the first frame draws the frustum-visible set early, so
        // its late phase already records true visibility.
        if (fresh) vkCmdFillBuffer(pc.cmd, pc.buffer(out.visibility).handle(), 0, VK_WHOLE_SIZE, 1u);
      });
  const uint32_t flags = c.enabled ? gpu::kCullFrustum : 0u;
  graph.addPass(
      c.enabled ? "cull-early" : "cull",
      [&](graph::PassBuilder& b) {
        // The lists are written through device addresses (CullPush): declared by hand.
        b.pipeline(in.pipelines.compute("cull.comp"));
        b.write(out.commands, graph::Use::StorageWriteCompute);
        b.write(out.drawIds, graph::Use::StorageWriteCompute);
        b.write(out.counts, graph::Use::StorageReadWriteCompute);  // atomicAdd
        if (flags != 0) b.write(out.visibility, graph::Use::StorageReadWriteCompute);
      },
      [out, flags, &in](graph::PassContext& pc) { dispatchCull(pc, in, out, flags); });
  return out;
}

void cullLate(graph::RenderGraph& graph, const FrameInputs& in, const CulledDraws& culled) {
  graph.addPass(
      "cull-late",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("cull.comp"));
        b.write(culled.commands, graph::Use::StorageWriteCompute);
        b.write(culled.drawIds, graph::Use::StorageWriteCompute);
        b.write(culled.counts, graph::Use::StorageReadWriteCompute);
        b.write(culled.visibility, graph::Use::StorageReadWriteCompute);
        b.read(culled.hiz, graph::Use::StorageReadCompute);
      },
      [culled, &in](graph::PassContext& pc) { dispatchCull(pc, in, culled, gpu::kCullFrustum | gpu::kCullLate); });
}

void buildDepthPyramid(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle depth,
                       const CulledDraws& culled) {
  const graph::BufferHandle hiz = culled.hiz;
  graph.addPass(
      "hiz-build",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("hiz.comp")).bind("depthImage", depth);
        b.write(hiz, graph::Use::StorageReadWriteCompute);  // through its device address (HizPush)
      },
      [hiz, &in](graph::PassContext& pc) {
        const rhi::Buffer& buffer = pc.buffer(hiz);
        for (uint32_t level = 0;; ++level) {
          const uint32_t w = std::max((in.size.width + (1u << level) - 1) >> level, 1u);
          const uint32_t h = std::max((in.size.height + (1u << level) - 1) >> level, 1u);
          if (level > 0) {  // each level reads the one before: a barrier inside the pass
            VkBufferMemoryBarrier2 mb{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
            mb.srcStageMask = mb.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            mb.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
            mb.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
            mb.srcQueueFamilyIndex = mb.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            mb.buffer = buffer.handle();
            mb.size = VK_WHOLE_SIZE;
            VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
            dep.bufferMemoryBarrierCount = 1;
            dep.pBufferMemoryBarriers = &mb;
            vkCmdPipelineBarrier2(pc.cmd, &dep);
          }
          pc.push(gpu::HizPush{buffer.address(), level, 0});
          vkCmdDispatch(pc.cmd, (w + gpu::kHizGroupSize - 1) / gpu::kHizGroupSize,
                        (h + gpu::kHizGroupSize - 1) / gpu::kHizGroupSize, 1);
          if (w == 1 && h == 1) break;
        }
      });
}

void readbackCullStats(graph::RenderGraph& graph, const FrameInputs& in, const CulledDraws& culled) {
  CullBuffers& c = *in.scene.cull;
  const graph::BufferHandle readback = graph.importBuffer("cull-readback", &c.readback, &c.readbackState);
  graph.addPass(
      "readback-cull",
      [&](graph::PassBuilder& b) {
        b.read(culled.counts, graph::Use::TransferSrc);
        b.read(culled.visibility, graph::Use::TransferSrc);
        b.write(readback, graph::Use::TransferDst);
        b.kind(graph::PassKind::Readback);
      },
      [culled, readback, rows = std::max(c.drawCount, 1u)](graph::PassContext& pc) {
        const VkBufferCopy counts{0, 0, kCountBytes};
        vkCmdCopyBuffer(pc.cmd, pc.buffer(culled.counts).handle(), pc.buffer(readback).handle(), 1, &counts);
        const VkBufferCopy visibility{0, kCountBytes, rows * sizeof(uint32_t)};
        vkCmdCopyBuffer(pc.cmd, pc.buffer(culled.visibility).handle(), pc.buffer(readback).handle(), 1, &visibility);
      });
  makeHostVisible(graph, "host-visible-cull", readback);
}

CullCounts cullCounts(const GpuScene& scene) {
  uint32_t n[gpu::kCullLists];
  std::memcpy(n, scene.cull->readback.mapped(), sizeof(n));
  return {n[0] + n[1], n[2] + n[3]};
}

uint32_t visibleDraws(const GpuScene& scene) {
  const CullCounts n = cullCounts(scene);
  return n.early + n.late;
}

std::vector<uint8_t> drawVisibility(const GpuScene& scene) {
  const CullBuffers& c = *scene.cull;
  std::vector<uint32_t> rows(c.drawCount);
  std::memcpy(rows.data(), static_cast<const uint8_t*>(c.readback.mapped()) + kCountBytes,
              rows.size() * sizeof(uint32_t));
  std::vector<uint8_t> out(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) out[i] = rows[i] != 0 ? 1 : 0;
  return out;
}

}  // namespace rayster::render
