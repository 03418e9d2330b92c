// Dynamic diffuse GI from irradiance probes (DDGI; --gi probes, docs/techniques.md §16b): a probe
// grid fitted to the scene's bounds; each frame every probe traces kProbeRaysPerProbe rays in a
// randomly rotated spherical-Fibonacci set (gi-probe-trace), the rays relocate probes out of
// geometry and classify them active or not (gi-probe-classify), update each probe's
// octahedral irradiance and distance-moment tiles with hysteresis (gi-probe-update-irradiance,
// gi-probe-update-visibility; the atlases are graph histories), and every G-buffer pixel looks up
// its irradiance from the eight probes around it with Chebyshev visibility (gi-probe-sample). Probe
// rays shade their hits with the probes of the frame before, so light bounces once more every
// frame. The result takes the one-bounce path's place as the diffuse indirect light.
#include <algorithm>
#include <cmath>

#include "render/gpu_scene.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "render/settings_table.h"
#include "shaders/shared/probes.h"

namespace rayster::render {
namespace {

const PassSetting kGi{
    passChoice("gi", "Effects",
               "Diffuse indirect light where --indirect turns it on: path (one denoised bounce ray per "
               "pixel) or probes (irradiance probes, multiple bounces)",
               {"path", "probes"}, "path")};

constexpr uint32_t kMaxProbesPerAxis = 8;  // on the scene's longest axis
constexpr float kMaxHysteresis = 0.97f;    // the blend's weight of the previous atlas once converged
constexpr VkImageUsageFlags kUsage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;

// A reproducible random rotation per frame (Shoemake's uniform quaternion from three numbers).
glm::vec4 frameRotation(uint32_t frame, uint32_t seed) {
  auto hash = [](uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
  };
  const uint32_t h = hash(frame * 3u + seed * 0x9e3779b9u);
  const float u1 = float(hash(h) >> 8) / 16777216.0f, u2 = float(hash(h + 1) >> 8) / 16777216.0f,
              u3 = float(hash(h + 2) >> 8) / 16777216.0f;
  const float a = std::sqrt(1.0f - u1), b = std::sqrt(u1), t2 = 6.2831853f * u2, t3 = 6.2831853f * u3;
  return {a * std::sin(t2), a * std::cos(t2), b * std::sin(t3), b * std::cos(t3)};
}

gpu::ProbeGrid fitGrid(const scene::Aabb& sceneBounds) {
  scene::Aabb b = sceneBounds;
  if (!b.valid()) b = {glm::vec3(-1.0f), glm::vec3(1.0f)};
  const glm::vec3 extent = glm::max(b.max - b.min, glm::vec3(1e-3f));
  // Probes a little inside the bounds' faces would sit on the walls; a small margin keeps them off.
  const glm::vec3 margin = 0.02f * extent;
  b.min += margin;
  b.max -= margin;
  const glm::vec3 inner = b.max - b.min;
  const float step = std::max(inner.x, std::max(inner.y, inner.z)) / float(kMaxProbesPerAxis - 1);
  gpu::ProbeGrid g{};
  for (int a = 0; a < 3; ++a) {
    const uint32_t n = std::clamp(uint32_t(std::ceil(inner[a] / step - 1e-3f)) + 1u, 2u, kMaxProbesPerAxis);
    g.counts[a] = n;
    g.spacing[a] = std::max(inner[a] / float(n - 1), 1e-3f);
  }
  g.origin = b.min;
  g.raysPerProbe = gpu::kProbeRaysPerProbe;
  const uint32_t probes = g.counts.x * g.counts.y * g.counts.z;
  g.tilesPerRow = uint32_t(std::ceil(std::sqrt(float(probes))));
  g.normalBias = 0.05f;
  g.viewBias = 0.2f;
  g.maxDistance = 2.0f * glm::length(extent);
  return g;
}

rhi::ImageDesc atlasDesc(const gpu::ProbeGrid& g, uint32_t interior, VkFormat format) {
  const uint32_t probes = g.counts.x * g.counts.y * g.counts.z;
  const uint32_t rows = (probes + g.tilesPerRow - 1) / g.tilesPerRow;
  return {format, g.tilesPerRow * (interior + 2), rows * (interior + 2), 1, kUsage};
}

}  // namespace

graph::ImageHandle traceProbeIrradiance(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                        uint32_t frameIndex, uint32_t seed, float historyScale, ProbeLookup& lookup) {
  gpu::ProbeGrid grid = fitGrid(in.scene.bounds);
  const uint32_t probes = grid.counts.x * grid.counts.y * grid.counts.z;
  const auto irradiance =
      graph.history("gi-probe-irradiance", atlasDesc(grid, gpu::kProbeIrradianceTexels, VK_FORMAT_R16G16B16A16_SFLOAT),
                    kRadianceImage);
  const auto visibility =
      graph.history("gi-probe-visibility", atlasDesc(grid, gpu::kProbeVisibilityTexels, VK_FORMAT_R32G32_SFLOAT));
  const auto data = graph.history("gi-probe-data", {VK_FORMAT_R16G16B16A16_SFLOAT, probes, 1, 1, kUsage});
  const uint32_t frames = std::min(irradiance.frames, visibility.frames);
  grid.flags = (frames > 0 ? gpu::kProbeHistoryValid : 0u) | (data.frames > 0 ? gpu::kProbeDataValid : 0u);
  // A running mean while the history is short, then an exponential one (a cut restarts it).
  grid.hysteresis = std::min(kMaxHysteresis, float(frames) / float(frames + 1));
  grid.rotation = frameRotation(frameIndex, seed);
  grid.historyScale = historyScale;

  const graph::ImageHandle rays = graph.createImage(
      "gi-probe-rays", {VK_FORMAT_R16G16B16A16_SFLOAT, grid.raysPerProbe, probes, 1, kUsage}, kRadianceImage);
  const VkSampler linear = in.linear.handle();
  const rhi::RayTracingPipeline& trace = in.pipelines.rayTracing("probe_trace.rgen", [] {
    rhi::RayTracingPipelineDesc d;
    d.raygen = "probe_trace.rgen";
    d.miss = {"primary.rmiss", "shadow.rmiss"};  // radiance rays miss 0, shadow rays miss 1
    d.hitGroups = radianceHitGroups();
    return d;
  });
  graph.addPass(
      "gi-probe-trace",
      [&](graph::PassBuilder& b) {
        b.pipeline(trace).bind("tlas", in.tlas).bind("outRays", rays);
        b.bind("probeIrradianceTex", irradiance.previous, linear)
            .bind("probeVisibilityTex", visibility.previous, linear);
        b.bind("probeDataTex", data.previous);
        b.rays(uint64_t(probes) * grid.raysPerProbe * 2);  // a probe ray and a shadow ray at its hit
      },
      [&trace, grid, probes](graph::PassContext& pc) {
        pc.push(grid);
        trace.trace(pc.cmd, grid.raysPerProbe, probes);
      });
  graph.addPass(
      "gi-probe-classify",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("probe_classify.comp"));
        b.bind("raysTex", rays).bind("previousData", data.previous).bind("outData", data.next);
      },
      [grid, probes](graph::PassContext& pc) {
        pc.push(grid);
        vkCmdDispatch(pc.cmd, (probes + 63) / 64, 1, 1);
      });
  for (bool moments : {false, true}) {
    const graph::RenderGraph::History& atlas = moments ? visibility : irradiance;
    graph.addPass(
        moments ? "gi-probe-update-visibility" : "gi-probe-update-irradiance",
        [&](graph::PassBuilder& b) {
          b.pipeline(in.pipelines.compute(moments ? "probe_update_visibility.comp" : "probe_update.comp"));
          b.bind("raysTex", rays).bind("previousAtlas", atlas.previous).bind("outAtlas", atlas.next);
        },
        [grid, probes](graph::PassContext& pc) {
          pc.push(grid);
          vkCmdDispatch(pc.cmd, probes, 1, 1);
        });
  }
  grid.flags |= gpu::kProbeHistoryValid | gpu::kProbeDataValid;  // the lookup reads this frame's atlases
  lookup = {irradiance.next, visibility.next, data.next, grid};
  lookup.grid.flags |= gpu::kProbeLookup;
  const graph::ImageHandle out =
      graph.createImage("gi-irradiance", {kRadianceFormat, in.size.width, in.size.height, 1, kUsage}, kRadianceImage);
  graph.addPass(
      "gi-probe-sample",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("probe_sample.comp")).bind("depthTex", gb.depth).bind("normalTex", gb.normals);
        b.bind("probeIrradianceTex", irradiance.next, linear).bind("probeVisibilityTex", visibility.next, linear);
        b.bind("probeDataTex", data.next).bind("outIrradiance", out);
      },
      [grid, size = in.size](graph::PassContext& pc) {
        pc.push(grid);
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return out;
}

}  // namespace rayster::render
