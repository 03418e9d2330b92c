#include "render/path_tracer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/log.h"
#include "graph/graph.h"
#include "render/exposure.h"
#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "rhi/commands.h"
#include "rhi/context.h"

namespace rayster::render {

Result<RenderOutput> PathTracer::render(const RenderSettings& s, const PathTraceResources& r, float exposure,
                                        const std::function<void(uint32_t)>& writeConstants) {
  if (s.frames == 0) return makeError(ExitCode::BadArguments, "--mode pathtrace needs at least one sample");
  const size_t skipped =
      size_t(std::count_if(s.aovs.begin(), s.aovs.end(), [](const std::string& n) { return n != "variance"; }));
  if (skipped > 0) log::info("{} AOV(s) skipped: --mode pathtrace writes only 'variance'", skipped);
  const bool variance = std::find(s.aovs.begin(), s.aovs.end(), "variance") != s.aovs.end();
  const rhi::ImageDesc desc{kPathAccumulationFormat, s.width, s.height, 1,
                            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT};

  const size_t pixels = size_t(s.width) * s.height;
  rhi::Buffer ldrReadback(r.ctx, pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback,
                          "ldr-readback");
  rhi::Buffer meanReadback(r.ctx, pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback,
                           "pt-readback");
  rhi::Buffer momentsReadback(r.ctx, variance ? pixels * 16 : 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                              rhi::MemoryUsage::Readback, "pt-moments-readback");
  graph::ResourceState ldrState, meanState, momentsState;
  std::map<std::string, std::vector<double>> passTimes;
  std::vector<std::string> passOrder;
  std::map<std::string, graph::PassInfo> passInfo;

  for (uint32_t f = 0; f < s.frames; ++f) {
    writeConstants(f);
    r.histories.beginFrame(f, f == 0);
    graph::RenderGraph graph(&r.ctx, &r.transients, &r.histories);
    const graph::AccelHandle tlas = beginFrameGraph(graph, r.scene, r.constants, r.nearest);
    FrameInputs in{r.pipelines, r.scene, r.constants, r.nearest, r.linear, {s.width, s.height}, tlas};
    const graph::RenderGraph::History meanHistory = graph.history("pt-mean", desc, kRadianceImage);
    const graph::RenderGraph::History momentsHistory = graph.history("pt-moments", desc);
    const PathAccumulation acc{meanHistory.previous, momentsHistory.previous, meanHistory.next, momentsHistory.next};
    const graph::ImageHandle mean = tracePaths(graph, in, acc);
    if (f + 1 == s.frames) {
      const graph::ImageHandle ldr = tonemap(graph, in, mean, {s.tonemap, s.seed});
      readback(graph, ldr, graph.importBuffer("ldr-readback", &ldrReadback, &ldrState));
      readback(graph, mean, graph.importBuffer("pt-readback", &meanReadback, &meanState));
      if (variance)
        readback(graph, acc.moments, graph.importBuffer("pt-moments-readback", &momentsReadback, &momentsState));
    }
    VkCommandBuffer cmd = r.commands.begin();
    r.timers.reset(cmd);
    graph.execute(cmd, &r.timers);
    r.ctx.wait(r.commands.submit());
    r.histories.endFrame();
    for (const auto& t : graph.readTimings(r.timers)) {
      if (!t.info.reported()) continue;
      if (!passTimes.count(t.name)) passOrder.push_back(t.name);
      passTimes[t.name].push_back(t.ms);
      passInfo[t.name] = t.info;
    }
    r.ctx.collectGarbage();
    if (s.progress) s.progress(f + 1, s.frames);
    if (s.stop && f + 1 < s.frames)
      if (std::optional<Error> stopped = s.stop()) return *stopped;
  }

  RenderOutput out;
  out.modeUsed = Mode::PathTrace;
  out.primaryUsed = Primary::Traced;
  out.ldr = Image8::make(int(s.width), int(s.height));
  std::memcpy(out.ldr.rgba.data(), ldrReadback.mapped(), pixels * 4);
  out.hdr = ImageF::make(int(s.width), int(s.height));
  std::memcpy(out.hdr.rgba.data(), meanReadback.mapped(), pixels * 16);
  if (variance) {
    // Variance of the mean: (E[x²] − E[x]²) · n/(n − 1) / n per channel; 0 with one sample.
    ImageF v = ImageF::make(int(s.width), int(s.height));
    const float* sq = static_cast<const float*>(momentsReadback.mapped());
    const float n = float(s.frames);
    for (size_t i = 0; i < pixels; ++i) {
      for (int c = 0; c < 3; ++c) {
        const float m = out.hdr.rgba[i * 4 + c];
        v.rgba[i * 4 + c] =
            n > 1.0f ? std::max(0.0f, sq[i * 4 + c] - m * m) / (n - 1.0f) / (exposure * exposure) : 0.0f;
      }
      v.rgba[i * 4 + 3] = 1.0f;
    }
    out.aovs.emplace_back("variance", std::move(v));
  }
  out.exposure = exposure;
  out.ev100 = ev100FromExposure(exposure);
  unexpose(out.hdr, exposure);  // the sources were pre-exposed (lib/frame.glsl)
  summarisePasses(passOrder, passTimes, passInfo, out);
  return out;
}

}  // namespace rayster::render
