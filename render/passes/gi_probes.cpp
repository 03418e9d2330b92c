// Dynamic diffuse GI from irradiance probes (DDGI; --gi probes, docs/techniques.md §16b): a probe
// grid fitted to the scene's bounds, and in a large scene finer cascades of it around the camera
// (fitProbeGrid; their windows scroll with it, only the probes that enter one start afresh). Each
// frame every probe traces kProbeRaysPerProbe rays in a randomly rotated spherical-Fibonacci set
// (gi-probe-trace), the rays relocate probes out of geometry and classify them active or not
// (gi-probe-classify), update each probe's octahedral irradiance and distance-moment tiles with
// hysteresis (gi-probe-update-irradiance, gi-probe-update-visibility; the atlases are graph
// histories), and every G-buffer pixel looks up its irradiance from the eight probes around it
// with Chebyshev visibility (gi-probe-sample). Probe rays shade their hits with the probes of the
// frame before, so light bounces once more every frame. The result takes the one-bounce path's
// place as the diffuse indirect light.
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
               "Diffuse indirect light where --indirect turns it on: probes (irradiance probes, multiple "
               "bounces) or path (one denoised bounce ray per pixel, its hits lit by the probes)",
               {"path", "probes"}, "probes")};

const PassSetting kCascades{
    passChoice("probe-cascades", "Effects",
               "Probe cascades: auto (in a scene larger than about 17 m, as many as bring the finest probe "
               "spacing to 2.5 m, the finer ones following the camera) or 1..4",
               {"auto", "1", "2", "3", "4"}, "auto")};

constexpr uint32_t kMaxProbesPerAxis = 8;  // per cascade, on the scene's longest axis
// --probe-cascades auto: cascades are added (each halving the spacing) until the finest spacing is
// at most this, in scene units (glTF: metres): a scene longer than about 7 × this on some axis is
// large and gets cascades around the camera (the built-in whitted and cornell scenes do not).
constexpr float kProbeTargetSpacing = 2.5f;
constexpr uint32_t kMinCascadeCounts = 4;   // probes per axis and cascade once there are several
constexpr float kMaxHysteresis = 0.97f;     // the blend's weight of the previous atlas once converged
constexpr float kMovingHysteresis = 0.85f;  // while the camera or an object moves: follow in a few frames
// The light that came through the probes: multiple bounces converge at a rate of about
// h + (1 − h)·ρ per frame (ρ the scene's interreflection, 0.6–0.85 indoors), so 0.97 would take
// hundreds of frames; 0.5 settles a room within ~30 (docs/techniques.md §16b). That share is
// smooth (irradiance seen at the hits), so the low hysteresis adds little flicker.
constexpr float kBounceHysteresis = 0.5f;
// For the first frames after a cut it is 0: each frame's bounce share is the last atlas seen once
// more through this frame's rays (a power iteration, error × ρ per frame).
constexpr uint32_t kBounceSettleFrames = 16;
constexpr uint32_t kWarmupUpdates = 8;  // probe updates before a cut's first frame (see below)
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

}  // namespace

uint32_t probeCount(const gpu::ProbeGrid& g) { return g.counts.x * g.counts.y * g.counts.z * g.cascades; }

uint32_t probeCascadesSetting(const RenderSettings& settings) {
  const std::string v = passSettingText(settings, "probe-cascades");
  return v == "auto" ? 0u : uint32_t(std::stoul(v));
}

gpu::ProbeGrid fitProbeGrid(glm::vec3 boundsMin, glm::vec3 boundsMax, glm::vec3 eye, uint32_t cascades) {
  scene::Aabb b{boundsMin, boundsMax};
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
  // Cascades: each finer one halves the spacing on every axis still coarser than the finest
  // spacing wanted (auto: kProbeTargetSpacing, or what kMaxProbeCascades reach; n asked for: the
  // longest axis' spacing ÷ 2^(n−1)).
  const float coarsest = std::max(g.spacing.x, std::max(g.spacing.y, g.spacing.z));
  const uint32_t maxLevel = gpu::kMaxProbeCascades - 1u;
  const float finest = cascades == 0 ? std::max(kProbeTargetSpacing, coarsest / float(1u << maxLevel))
                                     : coarsest / float(1u << (std::min(cascades, gpu::kMaxProbeCascades) - 1u));
  auto levelsFor = [&](const glm::vec3& spacing) {
    glm::uvec3 levels{0u};
    for (int a = 0; a < 3; ++a)
      if (spacing[a] > finest)
        levels[a] = std::min(maxLevel, uint32_t(std::ceil(std::log2(spacing[a] / finest) - 1e-3f)));
    return levels;
  };
  glm::uvec3 levels = levelsFor(g.spacing);
  const uint32_t deepest = std::max(levels.x, std::max(levels.y, levels.z));
  g.cascades = cascades == 0 ? 1u + deepest : std::clamp(cascades, 1u, gpu::kMaxProbeCascades);
  if (g.cascades > 1) {
    // A finer window of 2 probes on an axis would cover one cell of it: a large flat scene's height.
    // Such axes get kMinCascadeCounts probes in every cascade (the finer ones may then need no
    // subdivision on them at all).
    for (int a = 0; a < 3; ++a)
      if (g.counts[a] < kMinCascadeCounts) {
        g.counts[a] = kMinCascadeCounts;
        g.spacing[a] = std::max(inner[a] / float(kMinCascadeCounts - 1), 1e-3f);
      }
    levels = levelsFor(g.spacing);
  }
  for (uint32_t k = 0; k < g.cascades; ++k) {
    // Cascade k's lattice has 2^shift cells per coarsest cell on each axis; its window of counts
    // probes is centred on the eye, snapped to its lattice and kept inside the coarsest window.
    uint32_t packed = 0, slots = 0;
    for (int a = 0; a < 3; ++a) {
      const uint32_t shift = uint32_t(std::max(0, int(levels[a]) - int(k)));  // k = 0: the finest
      const uint32_t scale = 1u << shift;
      const float spacing = g.spacing[a] / float(scale);
      const int last = int((g.counts[a] - 1u) * (scale - 1u));  // the window's furthest start
      const float centred = (eye[a] - g.origin[a]) / spacing - 0.5f * float(g.counts[a] - 1u);
      const int cell = std::clamp(int(std::lround(centred)), 0, last);
      packed |= uint32_t(cell) << (8 * a) | shift << (24 + 2 * a);
      slots |= (uint32_t(cell) % g.counts[a]) << (3 * a);
    }
    g.cascadeCells[k] = {packed, slots};
  }
  g.raysPerProbe = gpu::kProbeRaysPerProbe;
  g.tilesPerRow = uint32_t(std::ceil(std::sqrt(float(probeCount(g)))));
  g.normalBias = 0.05f;
  g.viewBias = 0.2f;
  g.maxDistance = 2.0f * glm::length(extent);
  return g;
}

namespace {

rhi::ImageDesc atlasDesc(const gpu::ProbeGrid& g, uint32_t interior, VkFormat format) {
  const uint32_t probes = probeCount(g);
  const uint32_t rows = (probes + g.tilesPerRow - 1) / g.tilesPerRow;
  return {format, g.tilesPerRow * (interior + 2), rows * (interior + 2), 1, kUsage};
}

}  // namespace

void traceProbeIrradiance(graph::RenderGraph& graph, const FrameInputs& in, const ProbeFrame& frame,
                          ProbeLookup& lookup) {
  gpu::ProbeGrid grid = fitProbeGrid(in.scene.bounds.min, in.scene.bounds.max, frame.eye, frame.cascades);
  const uint32_t probes = probeCount(grid);
  const auto irradiance =
      graph.history("gi-probe-irradiance", atlasDesc(grid, gpu::kProbeIrradianceTexels, VK_FORMAT_R16G16B16A16_SFLOAT),
                    kRadianceImage);
  const auto visibility =
      graph.history("gi-probe-visibility", atlasDesc(grid, gpu::kProbeVisibilityTexels, VK_FORMAT_R32G32_SFLOAT));
  const auto bounce = graph.history(
      "gi-probe-bounce", atlasDesc(grid, gpu::kProbeIrradianceTexels, VK_FORMAT_R16G16B16A16_SFLOAT), kRadianceImage);
  const auto data = graph.history("gi-probe-data", {VK_FORMAT_R16G16B16A16_SFLOAT, probes, 1, 1, kUsage});
  const uint32_t frames = std::min({irradiance.frames, visibility.frames, bounce.frames});
  // Where the windows were at the last update: the probes that entered a window since start without
  // history (probeFresh() in lib/probes.glsl).
  if (frame.state) {
    ProbeCascadeState& state = *frame.state;
    const bool known = frames > 0 && state.cascades == grid.cascades;
    for (uint32_t k = 0; k < grid.cascades; ++k) {
      const uint32_t now = grid.cascadeCells[k].x & 0xffffffu;
      if (known && state.windows[k] != now) {
        // How far the window moved on each axis, clamped to ±8 (a window of at most 8 probes: all
        // of them fresh beyond that), stored + 8 in 5 bits.
        uint32_t moved = 0;
        for (int a = 0; a < 3; ++a) {
          const int d = int((now >> (8 * a)) & 0xffu) - int((state.windows[k] >> (8 * a)) & 0xffu);
          moved |= uint32_t(std::clamp(d, -8, 8) + 8) << (9 + 5 * a);
        }
        grid.cascadeCells[k].x |= gpu::kProbeWindowMoved;
        grid.cascadeCells[k].y |= moved;
      }
      state.windows[k] = now;
    }
    state.cascades = grid.cascades;
  }
  grid.rotation = frameRotation(frame.index, frame.seed);
  grid.historyScale = frame.historyScale;
  const VkSampler linear = in.linear.handle();
  const rhi::RayTracingPipeline& trace = in.pipelines.rayTracing("probe_trace.rgen", [] {
    rhi::RayTracingPipelineDesc d;
    d.raygen = "probe_trace.rgen";
    d.miss = {"primary.rmiss", "shadow.rmiss"};  // radiance rays miss 0, shadow rays miss 1
    d.hitGroups = radianceHitGroups();
    return d;
  });
  const rhi::ImageDesc rayDesc{VK_FORMAT_R16G16B16A16_SFLOAT, grid.raysPerProbe, probes, 1, kUsage};

  // One update of the probes: trace their rays, relocate and classify the probes, update the
  // distance moments and the irradiance. `n`: updates since the cut (the hysteresis schedule);
  // `suffix` names a warm-up iteration's passes and images.
  struct Atlases {
    graph::ImageHandle irradiance, bounce, visibility, data;
  };
  auto update = [&](const Atlases& src, const Atlases& dst, uint32_t n, const std::string& suffix) {
    gpu::ProbeGrid g = grid;
    g.flags = n > 0 ? gpu::kProbeHistoryValid | gpu::kProbeDataValid : 0u;
    // A running mean while the history is short, then an exponential one (a cut restarts it).
    const float runningMean = float(n) / float(n + 1);
    g.hysteresis = std::min(frame.moving ? kMovingHysteresis : kMaxHysteresis, runningMean);
    g.bounceHysteresis = n < kBounceSettleFrames ? 0.0f : kBounceHysteresis;
    if (!suffix.empty()) g.rotation = frameRotation(frame.index * 64u + n + 1u, frame.seed ^ 0x5bd1e995u);
    const graph::ImageHandle rays = graph.createImage("gi-probe-rays" + suffix, rayDesc, kRadianceImage);
    const graph::ImageHandle bounceRays = graph.createImage("gi-probe-bounce-rays" + suffix, rayDesc, kRadianceImage);
    graph.addPass(
        "gi-probe-trace" + suffix,
        [&](graph::PassBuilder& b) {
          b.pipeline(trace).bind("tlas", in.tlas).bind("outRays", rays).bind("outBounceRays", bounceRays);
          b.bind("probeIrradianceTex", src.irradiance, linear).bind("probeVisibilityTex", src.visibility, linear);
          b.bind("probeDataTex", src.data);
          b.rays(uint64_t(probes) * grid.raysPerProbe * 2);  // a probe ray and a shadow ray at its hit
        },
        [&trace, g, probes](graph::PassContext& pc) {
          pc.push(g);
          trace.trace(pc.cmd, g.raysPerProbe, probes);
        });
    graph.addPass(
        "gi-probe-classify" + suffix,
        [&](graph::PassBuilder& b) {
          b.pipeline(in.pipelines.compute("probe_classify.comp"));
          b.bind("raysTex", rays).bind("previousData", src.data).bind("outData", dst.data);
        },
        [g, probes](graph::PassContext& pc) {
          pc.push(g);
          vkCmdDispatch(pc.cmd, (probes + 63) / 64, 1, 1);
        });
    for (bool moments : {false, true}) {
      graph.addPass(
          (moments ? "gi-probe-update-visibility" : "gi-probe-update-irradiance") + suffix,
          [&](graph::PassBuilder& b) {
            b.pipeline(in.pipelines.compute(moments ? "probe_update_visibility.comp" : "probe_update.comp"));
            b.bind("raysTex", rays)
                .bind("previousAtlas", moments ? src.visibility : src.irradiance)
                .bind("outAtlas", moments ? dst.visibility : dst.irradiance);
            if (!moments)
              b.bind("bounceRaysTex", bounceRays).bind("previousBounce", src.bounce).bind("outBounce", dst.bounce);
          },
          [g, probes](graph::PassContext& pc) {
            pc.push(g);
            vkCmdDispatch(pc.cmd, probes, 1, 1);
          });
    }
  };

  // After a cut the probes are updated kWarmupUpdates times before this frame's update, so multiple
  // bounces have settled (to ρ^kWarmupUpdates) before the first image: a still of a few frames, or
  // the first frames after a jump, are not missing the light of the later bounces, and the probes
  // have moved out of the walls (relocation) before their light is averaged.
  Atlases src{irradiance.previous, bounce.previous, visibility.previous, data.previous};
  const Atlases dst{irradiance.next, bounce.next, visibility.next, data.next};
  if (frames == 0) {
    auto atlas = [&](const std::string& name, uint32_t interior, VkFormat format, bool radiance) {
      return graph.createImage(name, atlasDesc(grid, interior, format), radiance ? kRadianceImage : 0u);
    };
    for (uint32_t i = 0; i < kWarmupUpdates; ++i) {
      const std::string suffix = "-warmup" + std::to_string(i);
      Atlases next;
      next.visibility =
          atlas("gi-probe-visibility" + suffix, gpu::kProbeVisibilityTexels, VK_FORMAT_R32G32_SFLOAT, false);
      next.data = graph.createImage("gi-probe-data" + suffix, {VK_FORMAT_R16G16B16A16_SFLOAT, probes, 1, 1, kUsage});
      next.irradiance =
          atlas("gi-probe-irradiance" + suffix, gpu::kProbeIrradianceTexels, VK_FORMAT_R16G16B16A16_SFLOAT, true);
      next.bounce = atlas("gi-probe-bounce" + suffix, gpu::kProbeIrradianceTexels, VK_FORMAT_R16G16B16A16_SFLOAT, true);
      update(src, next, i, suffix);
      src = next;
    }
  }
  update(src, dst, frames + kWarmupUpdates, "");
  grid.flags |= gpu::kProbeHistoryValid | gpu::kProbeDataValid;  // the lookup reads this frame's atlases
  for (glm::uvec2& w : grid.cascadeCells) w = {w.x & ~gpu::kProbeWindowMoved, w.y & 0x1ffu};  // and sees no probe fresh
  lookup = {irradiance.next, visibility.next, data.next, grid};
  lookup.grid.flags |= gpu::kProbeLookup;
}

// Recorded just before lighting, its one reader: its two full-size outputs then live from here to
// lighting only, not through the reflection denoiser's peak of transient memory.
graph::ImageHandle sampleProbeIrradiance(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                         ProbeLookup& lookup) {
  const gpu::ProbeGrid grid = lookup.grid;
  const VkSampler linear = in.linear.handle();
  const graph::ImageHandle out =
      graph.createImage("gi-irradiance", {kRadianceFormat, in.size.width, in.size.height, 1, kUsage}, kRadianceImage);
  lookup.specularIrradiance = graph.createImage(
      "gi-irradiance-specular", {kRadianceFormat, in.size.width, in.size.height, 1, kUsage}, kRadianceImage);
  graph.addPass(
      "gi-probe-sample",
      [&](graph::PassBuilder& b) {
        b.pipeline(in.pipelines.compute("probe_sample.comp")).bind("depthTex", gb.depth).bind("normalTex", gb.normals);
        b.bind("probeIrradianceTex", lookup.irradiance, linear).bind("probeVisibilityTex", lookup.visibility, linear);
        b.bind("probeDataTex", lookup.data).bind("outIrradiance", out);
        b.bind("outSpecularIrradiance", lookup.specularIrradiance);
      },
      [grid, size = in.size](graph::PassContext& pc) {
        pc.push(grid);
        vkCmdDispatch(pc.cmd, (size.width + 7) / 8, (size.height + 7) / 8, 1);
      });
  return out;
}

}  // namespace rayster::render
