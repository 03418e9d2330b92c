#pragma once
// GPU culling (TECHNIQUES.md §20): a compute pass tests every GpuScene::Draw's box against this
// frame's clip volume and against the depth pyramid of the previous frame, and compacts the
// survivors into two indirect lists (triangles, sphere sets) with a count each, which the raster
// G-buffer draws with vkCmdDrawIndirectCount.
//
// Occlusion is one-phase and exact: the pyramid is used only when it was built from the same view
// (the previous frame's unjittered clipFromWorld and size equal this frame's) in a static scene
// without stochastic (BLEND) coverage, where last frame's depth is this frame's up to the TAA
// jitter (a one-pixel margin). A moving camera or animated scene culls by frustum only; the
// two-phase scheme (draw last frame's visible set, build the pyramid, re-test the rest) would
// extend occlusion to motion.
#include <cstdint>
#include <memory>

#include "graph/graph.h"
#include "rhi/resources.h"

namespace rayster::rhi {
class Context;
}

namespace rayster::render {

struct FrameInputs;
struct GpuScene;

// Persistent (per scene) buffers of the culling pass; frames are serialised, so one set suffices.
struct CullBuffers {
  uint32_t drawCount = 0;
  rhi::Buffer commands;  // VkDrawIndirectCommand[2 × drawCount]: list 0 triangles, list 1 spheres
  rhi::Buffer drawIds;   // uint[2 × drawCount]: the DrawRecord row of each command (gl_DrawID)
  rhi::Buffer counts;    // uint[2]: commands in each list
  rhi::Buffer readback;  // uint[2]: the counts of the last frame rendered, host-visible
  rhi::Buffer hiz;       // gpu::HizHeader + levels, sized for the last frame's resolution
  VkExtent2D hizSize{0, 0};
  bool hizFresh = false;  // just (re)created: the next frame clears its header
  graph::ResourceState commandsState, drawIdsState, countsState, readbackState, hizState;
  rhi::Context* ctx = nullptr;
  bool enabled = true;  // false: every draw passes (RenderSettings::culling)
};

std::shared_ptr<CullBuffers> createCullBuffers(rhi::Context& ctx, uint32_t drawCount);

struct CulledDraws {
  graph::BufferHandle commands, drawIds, counts, hiz;
};

// Records "cull-clear" and "cull"; the caller draws from commands/counts (Use::IndirectRead) and
// drawIds (Use::VertexShaderRead), then calls buildDepthPyramid() and readbackCullStats().
CulledDraws cullDraws(graph::RenderGraph& graph, const FrameInputs& in);
// Builds the depth pyramid from the G-buffer depth ("hiz-build"), for the next frame's cullDraws().
void buildDepthPyramid(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle depth,
                       const CulledDraws& culled);
// Copies the counts where the host can read them after the frame ("readback-cull" and
// "host-visible-cull": bookkeeping, left out of the frame time).
void readbackCullStats(graph::RenderGraph& graph, const FrameInputs& in, const CulledDraws& culled);
// Draws that survived culling in the last frame read back (both lists), of scene.draws.size().
uint32_t visibleDraws(const GpuScene& scene);

}  // namespace rayster::render
