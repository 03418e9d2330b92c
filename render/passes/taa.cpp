// Pass 8a: temporal anti-aliasing on linear HDR, before the tonemap (docs/techniques.md §18).
#include <algorithm>
#include <cstring>

#include "render/passes/passes.h"
#include "render/pipelines.h"

namespace rayster::render {

namespace {
// Mirrors of the flags in shaders/taa.comp.glsl.
constexpr uint32_t kTaaHistoryValid = 1u;
constexpr uint32_t kTaaMotion = 2u;
} // namespace

graph::ImageHandle resolveTaa(graph::RenderGraph& graph, const FrameInputs& in, const TaaInputs& taa) {
  graph.addPass(
      "taa",
      [&](graph::PassBuilder& b) {
        b.read(taa.current, graph::Use::SampledCompute);
        b.read(taa.depth, graph::Use::SampledCompute);
        b.read(taa.history, graph::Use::SampledCompute);
        if (taa.motion.valid()) b.read(taa.motion, graph::Use::SampledCompute);
        b.write(taa.next, graph::Use::StorageWriteCompute);
      },
      [taa, &in](graph::PassContext& pc) {
        const rhi::Pipeline& pipe = in.pipelines.taa;
        vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe.handle());
        // Without a motion image the depth stands in at binding 4: bound, never read.
        const graph::ImageHandle motion = taa.motion.valid() ? taa.motion : taa.depth;
        rhi::DescriptorWriter()
            .uniformBuffer(0, in.constants)
            .sampledImage(1, pc.image(taa.current).view(), in.nearest.handle())
            .sampledImage(2, pc.image(taa.depth).view(), in.nearest.handle())
            .sampledImage(3, pc.image(taa.history).view(), in.linear.handle())
            .sampledImage(4, pc.image(motion).view(), in.nearest.handle())
            .storageImage(5, pc.image(taa.next).view())
            .push(pc.cmd, pipe);
        const uint32_t flags = (taa.historyFrames > 0 ? kTaaHistoryValid : 0u) | (taa.motion.valid() ? kTaaMotion : 0u);
        // After a reset the history holds few frames: average them evenly (weight 1/(n+1)) until
        // that falls to the steady-state weight, so a static view converges fast.
        const float weight = std::max(kTaaCurrentWeight, 1.0f / float(taa.historyFrames + 1));
        uint32_t push[4] = {in.size.width, in.size.height, flags, 0};
        std::memcpy(&push[3], &weight, sizeof(float));
        vkCmdPushConstants(pc.cmd, pipe.layout(), pipe.stages(), 0, sizeof(push), push);
        vkCmdDispatch(pc.cmd, (in.size.width + 7) / 8, (in.size.height + 7) / 8, 1);
      });
  return taa.next;
}

} // namespace rayster::render
