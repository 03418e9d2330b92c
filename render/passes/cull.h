#pragma once
// Two-phase GPU culling (docs/techniques.md §23; Aaltonen & Haar, SIGGRAPH 2015) of the raster
// G-buffer's draws, in compute, drawn with vkCmdDrawIndirectCount:
//   1. early cull: every GpuScene::Draw's box against this frame's clip volume; the frustum-visible
//      draws that were visible last frame (a per-draw flag kept in a buffer) go to the early lists;
//   2. the G-buffer draws the early lists (clearing the targets);
//   3. a depth pyramid is built from that depth;
//   4. late cull: every frustum-visible draw against the pyramid; the result is next frame's
//      visibility, and the visible ones the early phase skipped go to the late lists;
//   5. the G-buffer draws the late lists into the same targets (load, not clear).
// The pyramid holds this frame's depth (same view, same jitter, same instance transforms), a subset
// of the final depth, so a draw culled in step 4 has no visible pixel: nothing pops, whether the
// camera or the instances move. Last frame's visibility only decides what is drawn early.
#include <cstdint>
#include <memory>
#include <vector>

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
  rhi::Buffer commands;    // VkDrawIndirectCommand[kCullLists × drawCount]: gpu::kCullLists lists
  rhi::Buffer drawIds;     // uint[kCullLists × drawCount]: the DrawRecord row of each command (gl_DrawID)
  rhi::Buffer counts;      // uint[kCullLists]: commands in each list
  rhi::Buffer visibility;  // uint[drawCount]: visible in the last late phase (kept across frames)
  rhi::Buffer readback;    // uint[kCullLists] counts, then uint[drawCount] visibility, of the last frame
  rhi::Buffer hiz;         // the pyramid's levels, sized for the last frame's resolution
  VkExtent2D hizSize{0, 0};
  bool visibilityFresh = true;  // the next frame sets every draw visible (all drawn early)
  graph::ResourceState commandsState, drawIdsState, countsState, visibilityState, readbackState, hizState;
  rhi::Context* ctx = nullptr;
  bool enabled = true;  // false: one phase, every draw passes (RenderSettings::culling)
};

std::shared_ptr<CullBuffers> createCullBuffers(rhi::Context& ctx, uint32_t drawCount);

struct CulledDraws {
  graph::BufferHandle commands, drawIds, counts, visibility, hiz;
};

// The draw lists of a phase: gpu::kCullLists lists, of which a phase uses two (triangles, spheres).
enum class CullPhase { Early = 0, Late = 1 };

// Records "cull-clear" and "cull-early" (culling off: "cull", every draw into the early lists).
// The caller draws the early lists from commands/counts (Use::IndirectRead) and drawIds
// (Use::VertexShaderRead); with culling on it then calls buildDepthPyramid() and cullLate() and
// draws the late lists; finally readbackCullStats().
CulledDraws cullDraws(graph::RenderGraph& graph, const FrameInputs& in);
// Builds the depth pyramid from the early phase's G-buffer depth ("hiz-build").
void buildDepthPyramid(graph::RenderGraph& graph, const FrameInputs& in, graph::ImageHandle depth,
                       const CulledDraws& culled);
// Records "cull-late": occlusion against the pyramid, next frame's visibility, the late lists.
void cullLate(graph::RenderGraph& graph, const FrameInputs& in, const CulledDraws& culled);
// Copies the counts and the visibility where the host can read them after the frame
// ("readback-cull" and "host-visible-cull": bookkeeping, left out of the frame time).
void readbackCullStats(graph::RenderGraph& graph, const FrameInputs& in, const CulledDraws& culled);

// Of the last frame read back: draws rasterised (both phases, both lists), of scene.draws.size().
uint32_t visibleDraws(const GpuScene& scene);
struct CullCounts {
  uint32_t early = 0, late = 0;  // draws rasterised by each phase
};
CullCounts cullCounts(const GpuScene& scene);
// Per draw (scene.draws order): 1 if the last frame's late phase found it visible (in the frustum
// and not hidden by the early depth), else 0. Culling off leaves it untouched.
std::vector<uint8_t> drawVisibility(const GpuScene& scene);

}  // namespace rayster::render
