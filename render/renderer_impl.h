#pragma once
// The renderer's private state (render/renderer.h's Renderer::Impl), shared by its three sources:
//   renderer.cpp         runs: settings, cameras, frame constants, histories, `auto` primaries
//   renderer_frame.cpp   one frame: the hybrid (or raster) passes recorded into a render graph
//   renderer_output.cpp  what leaves a run: AOV stages, readback, per-pass statistics
#include <chrono>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "graph/graph.h"
#include "render/exposure.h"
#include "render/gpu_scene.h"
#include "render/instance_motion.h"
#include "render/neutral_images.h"
#include "render/passes/denoise.h"
#include "render/passes/passes.h"
#include "render/path_tracer.h"
#include "render/pipelines.h"
#include "render/raster_frame.h"
#include "render/renderer.h"
#include "rhi/commands.h"
#include "rhi/context.h"

namespace rayster::render {

using Clock = std::chrono::steady_clock;
inline double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Timestamp regions per frame: the hybrid frame has ~35 passes with every denoiser on (each à-trous
// step is its own pass); a full pool silently drops the last passes' times.
inline constexpr uint32_t kMaxTimedPasses = 96;

// Auto exposure of a headless run (Impl::render): metering frames before the first output frame,
// until the reading lies within kMeterSettled EV of the exposure it was taken at (the path tracer
// meters with the hybrid's metering frames too).
inline constexpr uint32_t kMeterFrames = 3;
inline constexpr float kMeterSettled = 0.5f;

// What one frame's passes produced, for lighting, TAA and the AOVs: each effect's raw and
// denoised image (the same handle when the effect is off or the raster mode made it), the HDR
// image before TAA.
struct FrameImages {
  graph::ImageHandle shadowRaw, shadow, specularRaw, specular, aoRaw, ao, indirectRaw, indirect, hdr;
  RawTwinImages rawTwins;  // --raw-rays
  uint32_t aoLayer = 0;    // AO's layer of aoRaw and ao (FrameConstants::aoLayer: after the lights when they share)
};

struct Renderer::Impl {
  rhi::Context& ctx;
  const scene::Scene& scene;
  GpuScene gpu;
  // What the hybrid and raster modes approximate of the scene's material layers (empty: nothing);
  // said once, on the first frame of such a mode (layersApproximated(), render/gpu_materials.cpp).
  std::string layerWarning;
  rhi::PipelineLibrary pipelines;  // created on first use by the passes (rhi/pipeline_library.h)
  rhi::Sampler nearest, linear;
  rhi::Buffer constants;
  graph::TransientPool transients;
  rhi::CommandList commands;
  rhi::TimestampPool timers;
  // Temporal histories of the denoisers (the surface for disocclusion tests, shadow and AO means,
  // SVGF colour and moments of reflections, indirect and many-light direct light) and of TAA: graph
  // resources that outlive each frame's graph (graph/history.h).
  graph::HistoryStore histories;
  NeutralImages neutral;            // what lighting reads for an effect that records no pass
  const SpecularSurfaces specular;  // whether any material is smooth or transmissive enough to trace
  RasterFrame raster;               // the raster mode's passes (render/raster_frame.h)
  uint32_t frameIndex = 0;
  ProbeCascadeState probeCascades;  // where the probe cascades' windows were (render/passes/gi_probes.cpp)
  SpecularQueue specularQueue;      // the specular paths' continuation queue (render/passes/rt_specular.cpp)
  InstanceMotion motion;            // animation and edits (render/instance_motion.h)
  bool manyLights = false;          // more lights than shadow layers: stochastic direct light (lib/light_select.glsl)
  bool shadows = true;              // the run's RenderSettings::shadows (beginRun)
  // The exposure of each frame (render/exposure.h), and auto exposure's histogram: GPU-side, and
  // its host-visible copy, read after the frame's fence.
  ExposureControl exposure;
  // The EV100 the last "exposure: auto" line gave: a sequence's output frames, each metered afresh,
  // log it again only when it changes (else one line per frame floods a job's log).
  float loggedEv100 = -1e9f;
  void logMeteredExposure(const std::string& how);
  rhi::Buffer exposureHistogram, exposureReadback;
  graph::ResourceState exposureHistogramState, exposureReadbackState;
  std::unique_ptr<PathTracer> pathTracer;  // created by the first path-traced render

  // State of one run (render() or a viewer session): what beginRun sets up and each frame advances.
  struct Run {
    RenderSettings settings;
    const scene::Camera* cam = nullptr;
    RenderOutput out;
    uint32_t frame = 0;
    bool animated = false, movedBefore = false;
    uint32_t stillFrames = 0;  // frames in a row with neither the camera nor an instance moving (TaaInputs)
    // Auto exposure follows the frames (a viewer, a camera path, an animation, moved instances);
    // a headless still keeps the exposure its metering frames found.
    bool adaptExposure = false;
    float meterDistance = 0.0f;  // the last metering frame's reading from its own exposure (EV)
    glm::mat4 prevClipFromWorld{1.0f};
    scene::Camera prevCamera;
    rhi::Buffer ldrReadback, hdrReadback;
    graph::ResourceState ldrState, hdrState;
    struct AovReadback {
      std::string name;
      VkFormat format;
      uint32_t width, height, layer;
      rhi::Buffer buffer;
      bool radiance = false;  // pre-exposed light (lib/frame.glsl): divided by the exposure on the host
    };
    std::vector<AovReadback> aovReadback;
    std::deque<graph::ResourceState> aovStates;  // stable addresses for the graph
    std::map<std::string, std::vector<double>> passTimes;
    std::vector<std::string> passOrder;
    std::map<std::string, graph::PassInfo> passInfo;  // what each reported pass declared
    std::optional<Error> failure;                     // set by a frame (an unknown AOV): the run ends with it
  };
  std::optional<Run> run;
  // The presentable copy of the last frame's LDR image (FrameControl::present).
  rhi::Image output;
  graph::ResourceState outputState;

  Impl(rhi::Context& c, const scene::Scene& s, GpuScene g);

  // --- renderer.cpp: settings, cameras, constants, histories
  bool indirectOn(const RenderSettings& s) const { return s.indirect; }
  // rt-indirect traces one pixel per 2×2 block (gpu::kEffectIndirectQuarter).
  bool indirectQuarter(const RenderSettings& s) const {
    return s.mode != Mode::Raster && indirectOn(s) && s.indirectRate == IndirectRate::Quarter;
  }
  float aoRadius(const RenderSettings& s) const;
  int32_t findInstance(const std::string& name) const;
  // Lights with a shadow layer: none with --shadows off or in many-light mode.
  uint32_t shadowLights() const {
    return !shadows || manyLights ? 0u : std::min(gpu.lightCount, gpu::kMaxShadowLights);
  }
  // Shadow rays at a bounce hit: one per light, one for the light picked by importance (many-light
  // mode), none with --shadows off.
  uint32_t shadowRaysPerHit() const { return !shadows ? 0u : manyLights ? 1u : gpu.lightCount; }
  // The hybrid with AO traces it into the shadow visibility image's layer shadowLights() and
  // denoises it with the lights in one shadow-denoiser run (renderer_frame.cpp recordHybrid).
  static bool aoInShadowImage(const RenderSettings& s) { return s.mode != Mode::Raster && s.ao; }
  // Whether any surface of the scene gets traced specular light (lib/specular_weight.glsl
  // tracedSpecularWeight > 0, with a margin for the G-buffer's 8-bit roughness): otherwise the
  // hybrid records no specular pass.
  bool specularOn(const RenderSettings& s) const {
    if (!s.reflections) return false;
    return specular.transmission ||
           specular.minRoughness <= std::max(s.mirrorRoughness, s.glossyThreshold + gpu::kGlossyBlend) + 1.0f / 255.0f;
  }
  // Whether any opaque surface is a glossy one traced at half rate (lib/specular_weight.glsl
  // halfRateGlossy(): rougher than max(mirrorRoughness, kHalfRateRoughness), traced up to the glossy
  // threshold + blend; with the G-buffer's 8-bit margin): otherwise rt-specular records no fill.
  bool specularFillOn(const RenderSettings& s) const {
    const float lo = std::max(s.mirrorRoughness, gpu::kHalfRateRoughness) - 1.0f / 255.0f;
    const float hi = s.glossyThreshold + gpu::kGlossyBlend + 1.0f / 255.0f;
    for (const auto& [a, b] : specular.opaqueRoughness)
      if (b > lo && a < hi) return true;
    return false;
  }
  // Rays of the hybrid's reflection/refraction loop after the G-buffer surface (RenderSettings::maxDepth).
  static uint32_t specularBounces(const RenderSettings& s) {
    return std::clamp(s.maxDepth > 1 ? s.maxDepth - 1 : 1u, 1u, gpu::kMaxSpecularBounces);
  }
  // Writes the frame's constants; `jitter` is the NDC offset of the primaries, `prevClipFromWorld`
  // the previous frame's unjittered matrix (none: the first frame of a shot, so no motion).
  // Returns this frame's unjittered clipFromWorld.
  glm::mat4 writeConstants(const RenderSettings& s, const scene::Camera& cam, glm::vec2 jitter,
                           const glm::mat4* prevClipFromWorld);
  // Times one G-buffer producer alone: a warm-up frame, then a measured one.
  double timeProducer(const RenderSettings& s, Primary p);
  // The camera at `frame` along the scene's path: linear between keys, clamped at the ends.
  scene::Camera cameraOnPath(const scene::Camera& base, const RenderSettings& s, uint32_t frame) const;
  Result<const scene::Camera*> findCamera(const RenderSettings& s) const;
  RenderOutput::SceneStats sceneStats() const;
  // The reference (render/path_tracer.h): the scene's rest pose seen from the (static) camera.
  Result<RenderOutput> renderPathTraced(const RenderSettings& s);
  // Auto exposure's start: the guess from the scene's lights (render/exposure.h estimateEv100).
  void beginExposure(const RenderSettings& s, const scene::Camera& cam);
  Status beginRun(const RenderSettings& s);
  Result<RenderOutput> render(const RenderSettings& s);

  // --- renderer_frame.cpp: one frame
  FrameStats renderFrame(const FrameControl& control);
  // The ray-traced effects and their denoisers, then lighting.
  FrameImages recordHybrid(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                           const scene::Camera& camera, bool moving);

  // --- renderer_output.cpp: AOVs, readback, statistics
  // Readback of the LDR and HDR images and of the run's AOVs (RenderSettings::aovs) in this frame.
  void addReadbacks(graph::RenderGraph& graph, const GBuffer& gb, const FrameImages& images, graph::ImageHandle ldr);
  // What `--aov NAME` reads this frame: an alias (aovNames()) or any graph image, "NAME[:LAYER]".
  struct AovSource {
    graph::ImageHandle image;
    uint32_t layer = 0;
  };
  std::optional<AovSource> resolveAov(const graph::RenderGraph& graph, const GBuffer& gb, const FrameImages& images,
                                      const std::string& name) const;
  // The first frame's check of the requested AOVs: a name that is neither an alias nor an image of
  // the frame fails the run before it renders the rest.
  std::optional<Error> checkAovs(const graph::RenderGraph& graph, const GBuffer& gb, const FrameImages& images) const;
  RenderOutput endRun();
  // The images of the last frame rendered with readback, and the scene's statistics.
  void readImages(RenderOutput& out);
  // Copies the tonemapped image into `output` and leaves it ready as a transfer source, so the
  // caller's next submission can blit it (the next frame's copy waits for that read).
  void copyToOutput(graph::RenderGraph& graph, graph::ImageHandle ldr);
};

}  // namespace rayster::render
