#pragma once
// Renders a scene headless with the hybrid frame: G-buffer (raster or traced primary rays),
// ray-traced shadows and reflections denoised over frames (render/passes/denoise.h), deferred
// lighting, tonemapping, readback.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "graph/graph.h"
#include "render/tonemap_curves.h"
#include "scene/scene.h"

namespace rayster::rhi {
class Context;
class Image;
}  // namespace rayster::rhi

namespace rayster::render {

struct GpuScene;

enum class Primary { Raster, Traced, Auto };
// Exposure (render/exposure.h): metered from the frame's luminance, or fixed as a multiplier 2^EV
// (--exposure EV) or photographically (--ev100 N: 1 / (1.2 · 2^N)).
enum class ExposureMode { Auto, Ev, Ev100 };
const char* primaryName(Primary p);

// What renders the frame: the hybrid pipeline, the reference path tracer, or rasterisation only
// (the baseline, and the fallback on devices without ray-tracing pipelines).
enum class Mode { Hybrid, PathTrace, Raster };
const char* modeName(Mode m);

// How many pixels rt-indirect traces per frame: all, or one of each 2×2 block (rotating through the
// block over 4 frames, the rest filled depth- and normal-aware from traced neighbours before SVGF).
enum class IndirectRate { Full, Quarter };
const char* indirectRateName(IndirectRate r);

struct RenderSettings {
  uint32_t width = 1280, height = 720;
  uint32_t frames = 16;  // frames rendered; a static camera's denoisers accumulate them all
  // The first warmupFrames of `frames` are rendered but left out of the timing statistics (pipeline
  // and cache warm-up, clocks ramping up); benchmarks set it, images are unaffected.
  uint32_t warmupFrames = 0;
  // Also trace each frame's primary and shadow rays with trivial shaders (passes "raw-gbuffer-traced",
  // "raw-rt-shadows"), the device's raw rate for those rays; left out of the frame's GPU time.
  bool rawRays = false;
  uint32_t seed = 0;
  Mode mode = Mode::Hybrid;
  Primary primary = Primary::Auto;
  ExposureMode exposureMode = ExposureMode::Auto;
  float exposureEv = 0.0f;            // ExposureMode::Ev
  float ev100 = 0.0f;                 // ExposureMode::Ev100
  float exposureCompensation = 0.0f;  // EV added to the metered exposure (auto only)
  Tonemapper tonemap = Tonemapper::Aces;
  // Temporal anti-aliasing: jitters the primaries by a sub-pixel Halton(2,3) offset each frame and
  // resolves against a reprojected history, so a static view converges to a supersampled image.
  bool taa = true;
  // GPU frustum culling of the raster G-buffer's draws (render/passes/cull.h); off draws every one.
  bool culling = true;
  // Frames that start a new shot: the TAA history restarts there, besides the cuts the renderer
  // detects itself (a camera jump between frames) and the first frame of every render().
  std::vector<uint32_t> cuts;
  std::string camera;  // name; empty: the scene's first camera
  // Scenes with at most this many lights (<= gpu::kMaxShadowLights) trace a shadow layer per light;
  // with more, every pixel picks one light by importance (many-light mode).
  uint32_t shadowLights = 8;
  // Follow the scene's camera path at pathFps frames per second (the camera above supplies the
  // field of view and clip planes). A moving camera denoises with capped histories (αmin 0.2).
  bool cameraPath = false;
  // Intermediate images to return (names in aovNames()), read back after the last frame.
  std::vector<std::string> aovs;
  // The values of settings that pass files declare for themselves (render/settings_table.h
  // PassSetting), as text by name; a setting not here has its default.
  std::map<std::string, std::string, std::less<>> passSettings;
  float pathFps = 60.0f;  // frames per second of camera-path and animation playback
  // The run's frame f shows frame frameOffset + f of the animation and the camera path (the pose at
  // time + (frameOffset + f) / pathFps); frames before 0 show frame 0. A sequence pre-rolls each
  // output frame from the frames before it (app/sequence.h, docs/sequences.md).
  int64_t frameOffset = 0;
  // glTF node animations play from `time` seconds, one frame per 1/pathFps, looping; false holds
  // the pose at `time`.
  bool animate = true;
  float time = 0.0f;
  // Glossy reflections (docs/techniques.md §13): first surfaces at most mirrorRoughness rough reflect as
  // perfect mirrors (negative: none, every opaque reflection is VNDF-sampled); up to glossyThreshold
  // one GGX VNDF sample per pixel; rougher ones fade to the environment approximation over 0.1.
  float mirrorRoughness = 0.1f;
  float glossyThreshold = 0.5f;
  // Lights cast shadows (--shadows): the hybrid's rt-shadows layers (or many-light mode's rt-direct)
  // and the shadow rays at the hits of its bounce loops; the raster mode's shadow maps. Off, every
  // light reaches whatever faces it and no pass traces a shadow ray (gpu::kEffectShadows).
  bool shadows = true;
  // Ray-traced reflections and refractions (--reflections, the hybrid's rt-specular). Off, mirrors,
  // glossy surfaces and glass take the environment approximation (gpu::kEffectReflections).
  bool reflections = true;
  // Ray-traced ambient occlusion (docs/techniques.md §15) of ambient and environment light.
  bool ao = true;
  // The hybrid's denoisers (shadows, AO, reflections, indirect, many-light direct light); off:
  // lighting takes every effect's raw signal and the frame keeps no denoiser history.
  bool denoise = true;
  float aoRadius = -1.0f;  // world units; <= 0: kAoRadiusFraction × the scene bounds' diagonal
  bool indirect = true;    // ray-traced diffuse indirect light (--indirect; --gi picks how)
  IndirectRate indirectRate = IndirectRate::Quarter;  // --indirect-rate
  // Surface interactions along a path after the camera ray (--max-depth). The path tracer's paths
  // end after this many vertices (`frames` is then the samples per pixel, one per frame); the
  // hybrid's reflection/refraction loop starts at the G-buffer surface and traces up to
  // maxDepth − 1 more rays (at least 1, at most gpu::kMaxSpecularBounces).
  uint32_t maxDepth = 8;
  // Scripted edits (--move-instance): at frame `frame` of the run, the named scene instance's
  // translation becomes `position` (it stays there); it moves with motion vectors like animation.
  struct Move {
    std::string instance;
    glm::vec3 position{0.0f};
    uint32_t frame = 0;
  };
  std::vector<Move> moves;
  // Called after each frame with (frames done, frames in all), e.g. to show progress.
  std::function<void(uint32_t, uint32_t)> progress;
  // Asked after each frame but the last: an error ends the run with it (a SIGTERM stops a long
  // accumulation at the next frame: core/interrupt.h).
  std::function<std::optional<Error>()> stop;
};

// The default AO radius as a fraction of the scene's bounding-box diagonal: large enough for contact
// and crease shadows between objects, short of darkening whole rooms.
inline constexpr float kAoRadiusFraction = 0.1f;

struct PassStats {
  std::string name;
  double medianMs = 0, minMs = 0, p95Ms = 0;
  uint32_t samples = 0;
  std::vector<double> samplesMs;  // per measured frame, in frame order (for significance tests)
  // What the pass declared (graph::PassInfo): its kind, the pass a twin replays, and the rays it
  // launches per frame (launch size × traceRayEXT calls per invocation, an upper bound where an
  // invocation may return early; `info.raysExact` when the figure is exact; 0: traces nothing).
  graph::PassInfo info;
};

// Names accepted by RenderSettings::aovs, in the order `--aov all` writes them.
const std::vector<std::string>& aovNames();

struct RenderOutput {
  Image8 ldr;                                        // tonemapped, sRGB-encoded
  ImageF hdr;                                        // linear radiance
  std::vector<std::pair<std::string, ImageF>> aovs;  // raw values, RGBA float (see aovNames())
  Mode modeUsed = Mode::Hybrid;
  Primary primaryUsed = Primary::Raster;
  // The exposure of the last frame: the linear multiplier the light was rendered with, and its EV100.
  float exposure = 1.0f, ev100 = 0.0f;
  double rasterGBufferMs = -1, tracedGBufferMs = -1;  // measured by --primary auto, else -1
  std::vector<PassStats> passes;                      // GPU time per pass over all frames
  double frameMedianMs = 0;                           // sum of the passes' medians
  // Per measured frame (after warm-up): GPU ms (sum of the passes), CPU ms recording and submitting
  // the frame, and wall ms including the wait for the GPU.
  std::vector<double> frameGpuMs, frameCpuMs, frameWallMs;
  uint32_t shadowLayers = 0;  // lights with their own shadow layer (0: many-light mode)
  // The raster G-buffer's draws after culling in the last frame, of totalDraws (-1: not rasterised).
  int64_t visibleDraws = -1;
  uint32_t totalDraws = 0;
  struct SceneStats {
    uint64_t triangles = 0, spheres = 0;
    uint64_t blasBytes = 0, blasCompactedBytes = 0, tlasBytes = 0;
    double uploadMs = 0, accelBuildMs = 0;  // CPU wall time, including waits for the GPU
    uint64_t deviceBytesUsed = 0, deviceBytesReserved = 0;
    // deviceBytesUsed by rhi::MemoryCategory: images, device buffers, acceleration structures, host-visible.
    uint64_t imageBytes = 0, bufferBytes = 0, accelBytes = 0, hostBytes = 0;
    // Frame resources (the last frame's graph, graph/transient_pool.h): the transient images'
    // aliased heaps (G-buffer, targets, intermediates), what they would take unaliased, and the
    // imported images (histories, presented output). frameBytes = transientBytes + historyBytes;
    // it is part of imageBytes.
    uint64_t frameBytes = 0, transientBytes = 0, transientUnaliasedBytes = 0, historyBytes = 0;
    std::string frameMemoryReport;  // one image per line (rayster render --memory-report)
    uint32_t lights = 0;
  } scene;
};

// What may change from one frame of a run to the next (the viewer drives these).
struct FrameControl {
  std::optional<scene::Camera> camera;  // overrides the settings' camera and path for this frame
  bool cut = false;                     // start a new shot: every history restarts
  bool moving = false;                  // the camera moves: denoisers keep short histories
  bool readback = false;                // read the LDR, HDR and AOVs back (endRun returns them)
  bool present = false;                 // copy the LDR image into outputImage()
  // Auto exposure: seconds since the previous frame (0: 1/pathFps), what the exposure adapts over.
  float dtSeconds = 0.0f;
  // A metering frame of a headless run (Impl::render): a first frame whose only product is the
  // exposure reading; left out of the run's frame count and statistics.
  bool meter = false;
};

// One frame's GPU time per pass, from the graph's timestamps.
struct FrameStats {
  std::vector<graph::RenderGraph::PassTiming> passes;  // the reported ones (PassInfo::reported())
  double gpuMs = 0;
  Primary primaryUsed = Primary::Raster;
  int64_t visibleDraws = -1;  // raster G-buffer draws after culling (-1: traced primaries)
  scene::Camera camera;       // the camera the frame was rendered with
  float exposure = 1.0f;      // the frame's exposure (render/exposure.h)
};

class Renderer {
 public:
  static Result<std::unique_ptr<Renderer>> create(rhi::Context& ctx, const scene::Scene& scene);
  ~Renderer();
  // Renders settings.frames frames headless: beginRun, renderFrame for each, endRun (hybrid and
  // raster modes); Mode::PathTrace renders the reference (render/path_tracer.h).
  Result<RenderOutput> render(const RenderSettings& settings);

  // Incremental rendering, one frame at a time (the viewer). beginRun restarts every history.
  Status beginRun(const RenderSettings& settings);
  // The next run starts as this renderer's first would: auto exposure from its estimate instead of
  // the last run's reading, culling with every draw visible. Every other history restarts at any
  // run's first frame already; with this, a run's images do not depend on the runs before it.
  void restartHistories();
  FrameStats renderFrame(const FrameControl& control);
  // Takes the settings-table entries that do not restart accumulation (render/settings_table.h
  // Setting::restarts, e.g. the tonemapper) into the current run, from the next frame on.
  void updateSettings(const RenderSettings& settings);
  RenderOutput endRun();          // images of the last frame rendered with readback, stats over the run
  RenderOutput readbackImages();  // the same images (no stats) without ending the run
  // The last frame rendered with `present`: RGBA8 holding sRGB-encoded values, in
  // TRANSFER_SRC_OPTIMAL layout, readable by the next submission on the queue.
  const rhi::Image& outputImage() const;
  uint64_t deviceBytesUsed() const;
  // The scene as uploaded, with its draws and the culling state of the last frame (tests read the
  // per-draw visibility through render/passes/cull.h).
  const GpuScene& gpuScene() const;
  // The scene's lights were edited in place (same number): uploads them again. The next frame
  // should be a cut, or the denoisers' histories show the old lighting for a while.
  void refreshLights();
  // Moves scene instance `sceneInstance` (an index into scene.instances) from the next frame on:
  // the instance table (prevWorldFromObject = the last frame's transform, so motion vectors and the
  // denoisers follow) and the TLAS (refit). Call between frames; the first edit of a static scene
  // waits for the device while its instance table becomes host-visible. Edits outlast runs.
  void setInstanceTransform(uint32_t sceneInstance, const glm::mat4& worldFromObject);
  glm::mat4 instanceTransform(uint32_t sceneInstance) const;  // as edited, posed or loaded
  // Creates every pipeline again from shaders::get (shader hot reload); waits for the device.
  // Start a new run afterwards (beginRun).
  void reloadPipelines();

 private:
  struct Impl;
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace rayster::render
