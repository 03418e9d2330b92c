// Pass 8a: temporal anti-aliasing on linear HDR, before the tonemap (docs/techniques.md §18).
#include <algorithm>

#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "shaders/shared/push.h"

namespace rayster::render {

namespace {
// Mirrors of the flags in shaders/taa.comp.glsl.
constexpr uint32_t kTaaHistoryValid = 1u;
constexpr uint32_t kTaaMotion = 2u;
constexpr uint32_t kTaaStill = 4u;
}  // namespace

graph::ImageHandle resolveTaa(graph::RenderGraph& graph, const FrameInputs& in, const TaaInputs& taa) {
  // Without a motion image the depth stands in for it: bound, never read.
  const graph::ImageHandle motion = taa.motion.valid() ? taa.motion : taa.depth;
  graph.addPass(
      "taa",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("taa.comp"));
        b.bind("currentTex", taa.current)
            .bind("depthTex", taa.depth)
            .bind("historyTex", taa.history, in.linear.handle());
        b.bind("motionTex", motion).bind("outHistory", taa.next);
      },
      [taa, size = in.size](graph::PassContext& pc) {
        const bool still = taa.stillFrames > 0 && taa.historyFrames > 0;
        const uint32_t flags = (taa.historyFrames > 0 ? kTaaHistoryValid : 0u) |
                               (taa.motion.valid() ? kTaaMotion : 0u) | (still ? kTaaStill : 0u);
        // After a reset the history holds few frames: average them evenly (weight 1/(n+1)) until
        // that falls to the steady-state weight. A still view keeps averaging, with weights rising
        // linearly with the frame's number (2/(n+2)): the mean converges as an even one would
        // (4/3 of its variance) while the first frames, before the denoisers' and the probes'
        // histories settle, count little. n: the frames since the cut, or after motion the
        // 1/kTaaCurrentWeight frames an exponential mean is worth.
        float weight = std::max(kTaaCurrentWeight, 1.0f / float(taa.historyFrames + 1));
        if (still) {
          const uint32_t settled = uint32_t(std::lround(1.0f / kTaaCurrentWeight));
          const uint32_t n = std::min({taa.historyFrames, taa.stillFrames - 1 + settled, kTaaMaxStillFrames});
          weight = 2.0f / float(n + 2);
        }
        pc.push(gpu::TaaPush{{size.width, size.height}, flags, weight});
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return taa.next;
}

}  // namespace rayster::render
