#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <map>
#include <optional>
#include <span>
#include <tuple>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/half.h"
#include "core/log.h"
#include "graph/graph.h"
#include "render/gpu_scene.h"
#include "render/history.h"
#include "render/instance_motion.h"
#include "render/jitter.h"
#include "render/passes/cull.h"
#include "render/passes/denoise.h"
#include "render/passes/passes.h"
#include "render/frame_memory.h"
#include "render/path_tracer.h"
#include "render/pipelines.h"
#include "render/raster_frame.h"
#include "rhi/commands.h"
#include "rhi/context.h"
#include "rhi/memory.h"
#include "scene/animation.h"
#include "shaders/shared/types.h"

namespace rayster::render {

const std::vector<std::string>& aovNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = {"depth",           "normal",         "albedo",       "material",
                                  "emissive",        "motion",         "shadow-raw",   "shadow-denoised",
                                  "reflection-raw",  "reflection-denoised", "ao-raw",  "ao-denoised",
                                  "indirect-raw",    "indirect-denoised"};
    // Per shadowed light: layer i of the visibility arrays ("shadow-raw" is layer 0).
    for (uint32_t i = 0; i < gpu::kMaxShadowLights; ++i) n.push_back("shadow" + std::to_string(i) + "-raw");
    for (uint32_t i = 0; i < gpu::kMaxShadowLights; ++i) n.push_back("shadow" + std::to_string(i) + "-denoised");
    n.push_back("variance");  // --mode pathtrace: the per-pixel variance of the accumulated mean
    return n;
  }();
  return names;
}

namespace {

// Texel formats the AOVs come in, converted to RGBA float on the CPU.
float texel(const uint8_t* data, VkFormat format, size_t index, int channel) {
  switch (format) {
    case VK_FORMAT_R32_SFLOAT:
      return channel == 0 ? reinterpret_cast<const float*>(data)[index] : channel == 3 ? 1.0f : 0.0f;
    case VK_FORMAT_D32_SFLOAT: return channel == 3 ? 1.0f : reinterpret_cast<const float*>(data)[index];
    case VK_FORMAT_R16_SFLOAT:
      return channel == 3 ? 1.0f : halfToFloat(reinterpret_cast<const uint16_t*>(data)[index]);
    case VK_FORMAT_R16G16_SFLOAT:
      return channel < 2 ? halfToFloat(reinterpret_cast<const uint16_t*>(data)[index * 2 + channel]) : channel == 3 ? 1.0f : 0.0f;
    case VK_FORMAT_R16G16B16A16_SFLOAT: return halfToFloat(reinterpret_cast<const uint16_t*>(data)[index * 4 + channel]);
    case VK_FORMAT_R32G32B32A32_SFLOAT: return reinterpret_cast<const float*>(data)[index * 4 + channel];
    case VK_FORMAT_R16G16B16A16_SNORM:
      return std::max(-1.0f, reinterpret_cast<const int16_t*>(data)[index * 4 + channel] / 32767.0f);
    case VK_FORMAT_R8G8B8A8_UNORM: return data[index * 4 + channel] / 255.0f;
    default: return 0.0f;
  }
}

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

uint32_t texelBytes(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R16_SFLOAT: return 2;
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_R8G8B8A8_UNORM: return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_SNORM: return 8;
    default: return 16;
  }
}

// A camera that jumps between two frames starts a new shot: its history would ghost the old view.
// Real motion at any sensible frame rate stays far below these.
constexpr float kCutMoveFraction = 0.25f;  // of the distance to the target (the scene's scale)
constexpr float kCutAngleDegrees = 15.0f;  // turn of the view direction

// Timestamp regions per frame: the hybrid frame has ~35 passes with every denoiser on (each à-trous
// step is its own pass); a full pool silently drops the last passes' times.
constexpr uint32_t kMaxTimedPasses = 96;

bool isCameraCut(const scene::Camera& before, const scene::Camera& now) {
  const glm::vec3 dirBefore = before.target - before.position, dirNow = now.target - now.position;
  const float distance = glm::length(dirBefore);
  if (glm::length(now.position - before.position) > kCutMoveFraction * distance) return true;
  const float cosAngle = glm::dot(dirBefore, dirNow) / (distance * glm::length(dirNow));
  return cosAngle < std::cos(glm::radians(kCutAngleDegrees)) || now.yFov != before.yFov;
}

} // namespace

RayCount launchedRays(const std::string& pass, uint32_t width, uint32_t height, uint32_t shadowLayers,
                      uint32_t lightsPerHit, uint32_t maxDepth) {
  const uint64_t pixels = uint64_t(width) * height;
  // traceRayEXT calls per invocation, from the shaders: one primary ray (gbuffer.rgen); one shadow
  // ray per layer (shadows.rgen, one launch layer per shadowed light); one occlusion ray (ao.rgen);
  // one shadow ray to the importance-selected light (direct.rgen); a bounce ray plus a shadow ray at
  // its hit (indirect.rgen); and per traced specular bounce one ray plus a shadow ray per light shaded
  // at the hit (specular.rgen). Invocations on the background, non-specular pixels or lights behind
  // the surface return before tracing, and paths end early, so all but the primary rays are bounds.
  if (pass == "gbuffer-traced" || pass == "raw-gbuffer-traced") return {pixels, true};
  if (pass == "rt-shadows" || pass == "raw-rt-shadows") return {pixels * shadowLayers, false};
  if (pass == "rt-ao" || pass == "rt-direct") return {pixels, false};
  if (pass == "rt-indirect") return {pixels * 2, false};
  if (pass == "rt-specular") return {pixels * uint64_t(maxDepth) * (1u + lightsPerHit), false};
  return {};
}

const char* modeName(Mode m) {
  switch (m) {
    case Mode::PathTrace: return "pathtrace";
    case Mode::Raster: return "raster";
    default: return "hybrid";
  }
}

const char* primaryName(Primary p) {
  switch (p) {
    case Primary::Raster: return "raster";
    case Primary::Traced: return "rt";
    default: return "auto";
  }
}

struct Renderer::Impl {
  rhi::Context& ctx;
  const scene::Scene& scene;
  GpuScene gpu;
  Pipelines pipelines;
  rhi::Sampler nearest, linear;
  rhi::Buffer constants;
  graph::TransientPool transients;
  rhi::CommandList commands;
  rhi::TimestampPool timers;
  // Temporal state of the denoisers: the surface (disocclusion tests), shadow and AO means, SVGF
  // colour and moments of the reflections, the indirect light and the many-light direct light;
  // and TAA's resolved colour.
  History surfaceHistory, shadowHistory, aoHistory, taaHistory;
  struct SvgfHistory {
    History color, moments;
    // Full size only while the signal exists (a 1×1 stand-in otherwise, never read).
    void ensure(rhi::Context& ctx, VkExtent2D size, bool used, const std::string& name) {
      const VkExtent2D s = used ? size : VkExtent2D{1, 1};
      color.ensure(ctx, svgfColorHistoryDesc(s), name + "-history");
      moments.ensure(ctx, svgfMomentsHistoryDesc(s), name + "-moments");
    }
    HistoryPair colorPair(graph::RenderGraph& g, const std::string& name, uint32_t f) {
      return {color.previous(g, name + "-history", f), color.next(g, name + "-history", f)};
    }
    HistoryPair momentsPair(graph::RenderGraph& g, const std::string& name, uint32_t f) {
      return {moments.previous(g, name + "-moments", f), moments.next(g, name + "-moments", f)};
    }
  } specularHistory, indirectHistory, directHistory;
  std::optional<RawRayPipelines> rawPipelines;  // created on the first render with rawRays
  RasterFrame raster;  // the raster mode's passes (render/raster_frame.h)
  uint32_t frameIndex = 0;
  uint32_t taaFrames = 0;  // frames in the TAA history since its last reset
  InstanceMotion motion;  // animation and edits (render/instance_motion.h)

  Impl(rhi::Context& c, const scene::Scene& s, GpuScene g)
      : ctx(c), scene(s), gpu(std::move(g)), pipelines(Pipelines::create(c, gpu.bindless->layout())),
        nearest(c, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE),
        linear(c, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE),
        constants(c, sizeof(gpu::FrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, rhi::MemoryUsage::Upload,
                  "frame-constants"),
        commands(c), timers(c, kMaxTimedPasses), raster(c) {}

  bool manyLights = false;  // more lights than shadow layers: stochastic direct light (lib/light_select.glsl)
  bool indirectOn(const RenderSettings& s) const { return s.indirect.value_or(scene.indirectByDefault); }
  float aoRadius(const RenderSettings& s) const {
    if (s.aoRadius > 0.0f) return s.aoRadius;
    const scene::Aabb b = scene.bounds();
    const float diagonal = b.valid() ? glm::length(b.max - b.min) : 0.0f;
    return diagonal > 0.0f ? kAoRadiusFraction * diagonal : 1.0f;
  }

  int32_t findInstance(const std::string& name) const {
    for (size_t i = 0; i < scene.instances.size(); ++i)
      if (scene.instances[i].name == name && gpu.instanceRowOf[i] >= 0) return int32_t(i);
    return -1;
  }

  uint32_t shadowLights() const { return manyLights ? 0u : std::min(gpu.lightCount, gpu::kMaxShadowLights); }

  // Writes the frame's constants; `jitter` is the NDC offset of the primaries, `prevClipFromWorld`
  // the previous frame's unjittered matrix (none: the first frame of a shot, so no motion).
  // Returns this frame's unjittered clipFromWorld.
  glm::mat4 writeConstants(const RenderSettings& s, const scene::Camera& cam, glm::vec2 jitter,
                           const glm::mat4* prevClipFromWorld) {
    gpu::FrameConstants fc{};
    const float aspect = float(s.width) / float(s.height);
    glm::mat4 view = glm::lookAt(cam.position, cam.target, cam.up);
    // Reversed Z (near → 1, far → 0): swapping the planes in a [0,1]-depth projection does it.
    glm::mat4 proj = glm::perspective(cam.yFov, aspect, cam.zFar, cam.zNear);
    proj[1][1] *= -1.0f;  // Vulkan clip space: y points down
    fc.unjitteredClipFromWorld = proj * view;
    fc.prevClipFromWorld = prevClipFromWorld ? *prevClipFromWorld : fc.unjitteredClipFromWorld;
    fc.jitter = jitter;
    // Raster and traced primaries (and every position reconstructed from depth) follow the jitter.
    fc.clipFromWorld = jitteredClipFromWorld(fc.unjitteredClipFromWorld, jitter);
    fc.worldFromClip = glm::inverse(fc.clipFromWorld);
    fc.cameraPosition = glm::vec4(cam.position, 1.0f);
    fc.ambient = glm::vec4(scene.ambient, 0.0f);
    fc.size = {s.width, s.height};
    fc.frameIndex = frameIndex;
    fc.seed = s.seed;
    fc.lightCount = gpu.lightCount;
    fc.shadowLightCount = shadowLights();
    fc.manyLights = manyLights ? 1u : 0u;
    fc.exposure = std::exp2(s.exposureEv);
    fc.geometries = gpu.geometries.address();
    fc.instances = gpu.instances.address();
    fc.materials = gpu.materials.address();
    fc.lights = gpu.lights.address();
    const scene::Environment& env = scene.environment;
    fc.environmentKind = gpu.environment.kind;
    fc.environment = glm::vec4(glm::vec3(env.intensity), env.rotation);
    fc.environmentSlot = gpu.environment.slot;
    fc.prefilteredSlot = gpu.environment.prefilteredSlot;
    fc.skyZenith = env.zenith;
    fc.skyHorizon = env.horizon;
    fc.skyGround = env.ground;
    for (int k = 0; k < 9; ++k) fc.irradianceSh[k] = glm::vec4(gpu.environment.irradianceSh[k], 0.0f);
    fc.sceneFlags = gpu.anyAlphaTested ? gpu::kSceneAlphaTested : 0u;
    fc.mirrorRoughness = s.mirrorRoughness;
    fc.glossyThreshold = s.glossyThreshold;
    fc.aoRadius = aoRadius(s);
    // Untraced glossy light (rougher than the glossy threshold) comes from the GGX-prefiltered
    // environment in both modes. The raster mode has neither AO nor indirect light: ambient and the
    // SH environment stand in.
    fc.effectFlags = gpu::kEffectPrefilteredEnv |
                     (s.mode == Mode::Raster ? 0u : (s.ao ? gpu::kEffectAo : 0u) | (indirectOn(s) ? gpu::kEffectIndirect : 0u));
    fc.dfgSlot = gpu.dfgSlot;
    fc.emissiveTriangles = gpu.emissiveTriangles.address();
    fc.environmentCdf = gpu.environmentCdf.address();
    fc.emissiveTriangleCount = gpu.emissiveTriangleCount;
    fc.emissiveArea = gpu.emissiveArea;
    fc.environmentCdfWidth = gpu.environment.cdfWidth;
    fc.environmentCdfHeight = gpu.environment.cdfHeight;
    fc.maxDepth = std::max(1u, s.maxDepth);
    fc.maxSpecularBounces = specularBounces(s);
    std::memcpy(constants.mapped(), &fc, sizeof(fc));
    return fc.unjitteredClipFromWorld;
  }

  void ensureHistory(const RenderSettings& s) {
    const VkExtent2D size{s.width, s.height};
    surfaceHistory.ensure(ctx, surfaceDesc(size), "surface-history");
    shadowHistory.ensure(ctx, shadowHistoryDesc(size, shadowLights()), "shadow-history");
    aoHistory.ensure(ctx, shadowHistoryDesc(s.ao ? size : VkExtent2D{1, 1}, 1), "ao-history");
    specularHistory.ensure(ctx, size, true, "specular");
    indirectHistory.ensure(ctx, size, indirectOn(s), "indirect");
    directHistory.ensure(ctx, size, manyLights, "direct");
    taaHistory.ensure(ctx,
                      {kTaaHistoryFormat, s.width, s.height, 1,
                       VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
                      "taa-history");
  }

  // Times one G-buffer producer alone: a warm-up frame, then a measured one.
  double timeProducer(const RenderSettings& s, Primary p) {
    double ms = 0;
    for (int run = 0; run < 2; ++run) {
      graph::RenderGraph graph(&ctx, &transients);
      FrameInputs in{pipelines, gpu, constants, nearest, linear, {s.width, s.height}, gpu.bindless->set()};
      GBuffer gb = p == Primary::Traced ? traceGBuffer(graph, in) : rasterGBuffer(graph, in);
      graph.addPass("keep", [&](graph::PassBuilder& b) {
        b.read(gb.normals, graph::Use::SampledCompute);
        b.sideEffect();
      }, [](graph::PassContext&) {});
      VkCommandBuffer cmd = commands.begin();
      timers.reset(cmd);
      graph.execute(cmd, &timers);
      ctx.wait(commands.submit());
      for (auto& t : timers.read())
        if (t.name.rfind("gbuffer-", 0) == 0) ms = t.ms;
    }
    return ms;
  }

  // The camera at `frame` along the scene's path: linear between keys, clamped at the ends.
  scene::Camera cameraOnPath(const scene::Camera& base, const RenderSettings& s, uint32_t frame) const {
    const auto& keys = scene.cameraPath;
    const float t = keys.front().time + float(frame) / s.pathFps;
    scene::Camera cam = base;
    size_t k = 0;
    while (k + 1 < keys.size() && keys[k + 1].time <= t) ++k;
    if (k + 1 >= keys.size()) {
      cam.position = keys.back().position;
      cam.target = keys.back().target;
    } else {
      const float a = (t - keys[k].time) / (keys[k + 1].time - keys[k].time);
      cam.position = glm::mix(keys[k].position, keys[k + 1].position, a);
      cam.target = glm::mix(keys[k].target, keys[k + 1].target, a);
    }
    return cam;
  }

  Result<const scene::Camera*> findCamera(const RenderSettings& s) const {
    if (s.camera.empty()) return &scene.cameras.front();
    auto it = std::find_if(scene.cameras.begin(), scene.cameras.end(),
                           [&](const scene::Camera& c) { return c.name == s.camera; });
    if (it == scene.cameras.end()) return makeError(ExitCode::BadArguments, "the scene has no camera named '{}'", s.camera);
    return &*it;
  }

  RenderOutput::SceneStats sceneStats() const {
    RenderOutput::SceneStats st{gpu.triangleCount, gpu.sphereCount, gpu.accelStats.builtBytes,
                                gpu.accelStats.compactedBytes, gpu.accelStats.tlasBytes, gpu.uploadMs,
                                gpu.accelBuildMs, 0, 0};
    const rhi::MemoryStats mem = ctx.memory().stats();
    st.deviceBytesUsed = mem.usedBytes;
    st.deviceBytesReserved = mem.reservedBytes;
    st.imageBytes = mem.bytes(rhi::MemoryCategory::Image);
    st.bufferBytes = mem.bytes(rhi::MemoryCategory::Buffer);
    st.accelBytes = mem.bytes(rhi::MemoryCategory::Accel);
    st.hostBytes = mem.bytes(rhi::MemoryCategory::Host);
    setFrameMemory(st, transients.report());
    st.lights = gpu.lightCount;
    return st;
  }

  // Rays of the hybrid's reflection/refraction loop after the G-buffer surface (RenderSettings::maxDepth).
  static uint32_t specularBounces(const RenderSettings& s) {
    return std::clamp(s.maxDepth > 1 ? s.maxDepth - 1 : 1u, 1u, gpu::kMaxSpecularBounces);
  }

  std::unique_ptr<PathTracer> pathTracer;  // created by the first path-traced render

  // The reference (render/path_tracer.h): the scene's rest pose seen from the (static) camera.
  Result<RenderOutput> renderPathTraced(const RenderSettings& s) {
    auto cam = findCamera(s);
    if (!cam) return cam.error();
    if (s.cameraPath || (scene.animated() && s.animate))
      log::info("--mode pathtrace renders the static camera and the rest pose");
    if (!pathTracer) pathTracer = std::make_unique<PathTracer>(ctx, gpu.bindless->layout());
    manyLights = false;
    const PathTraceResources r{ctx, gpu, pipelines, constants, nearest, linear, transients, commands, timers};
    auto out = pathTracer->render(s, r, [&](uint32_t f) {
      frameIndex = f;
      writeConstants(s, **cam, glm::vec2(0.0f), nullptr);
    });
    if (out) out->scene = sceneStats();
    return out;
  }

  // State of one run (render() or a viewer session): what beginRun sets up and each frame advances.
  struct Run {
    RenderSettings settings;
    const scene::Camera* cam = nullptr;
    RenderOutput out;
    uint32_t frame = 0;
    bool animated = false, movedBefore = false;
    glm::mat4 prevClipFromWorld{1.0f};
    scene::Camera prevCamera;
    rhi::Buffer ldrReadback, hdrReadback;
    graph::ResourceState ldrState, hdrState;
    struct AovReadback {
      std::string name;
      VkFormat format;
      uint32_t layer;
      rhi::Buffer buffer;
    };
    std::vector<AovReadback> aovReadback;
    std::deque<graph::ResourceState> aovStates;  // stable addresses for the graph
    std::map<std::string, std::vector<double>> passTimes;
    std::vector<std::string> passOrder;
  };
  std::optional<Run> run;
  // The presentable copy of the last frame's LDR image (FrameControl::present).
  rhi::Image output;
  graph::ResourceState outputState;

  Status beginRun(const RenderSettings& s) {
    if (s.cameraPath && scene.cameraPath.empty())
      return makeError(ExitCode::BadArguments, "--camera-path: scene '{}' has no camera path", scene.name);
    auto camera = findCamera(s);
    if (!camera) return camera.error();
    const scene::Camera* cam = *camera;
    run.reset();
    run.emplace();
    run->settings = s;
    run->cam = cam;
    gpu.cull->enabled = s.culling;
    RenderOutput& out = run->out;
    frameIndex = 0;
    const bool rasterMode = s.mode == Mode::Raster;
    out.modeUsed = s.mode;
    // The raster mode shadows the first shadowLights lights from shadow maps and leaves the rest
    // unshadowed: stochastic light selection needs shadow rays.
    manyLights = !rasterMode && gpu.lightCount > std::min(s.shadowLights, gpu::kMaxShadowLights);
    if (manyLights)
      log::info("{} lights, {} shadow layers: one light per pixel by importance", gpu.lightCount,
                std::min(s.shadowLights, gpu::kMaxShadowLights));
    writeConstants(s, *cam, glm::vec2(0.0f), nullptr);
    out.primaryUsed = rasterMode ? Primary::Raster : s.primary;
    if (out.primaryUsed == Primary::Auto) {
      // On the H100 the raster G-buffer costs many times the traced one; elsewhere raster is cheap.
      out.rasterGBufferMs = timeProducer(s, Primary::Raster);
      out.tracedGBufferMs = timeProducer(s, Primary::Traced);
      out.primaryUsed = out.tracedGBufferMs >= 0 && out.tracedGBufferMs < out.rasterGBufferMs ? Primary::Traced
                                                                                            : Primary::Raster;
      log::info("primary: auto chose {} (raster G-buffer {:.3f} ms, traced {:.3f} ms)", primaryName(out.primaryUsed),
                out.rasterGBufferMs, out.tracedGBufferMs);
    }

    ensureHistory(s);
    run->animated = scene.animated() && !gpu.instanceRecords.empty();
    motion.beginRun(scene, run->animated);
    for (const RenderSettings::Move& m : s.moves)
      if (findInstance(m.instance) < 0)
        return makeError(ExitCode::BadArguments, "--move-instance: scene '{}' has no instance '{}'", scene.name, m.instance);
    taaHistory.valid = false;  // every run starts its own history
    run->prevCamera = *cam;
    const size_t pixels = size_t(s.width) * s.height;
    run->ldrReadback = rhi::Buffer(ctx, pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "ldr-readback");
    run->hdrReadback = rhi::Buffer(ctx, pixels * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "hdr-readback");
    for (const std::string& name : s.aovs)
      if (std::find(aovNames().begin(), aovNames().end(), name) == aovNames().end())
        return makeError(ExitCode::BadArguments, "unknown AOV '{}'", name);
    return okStatus();
  }

  FrameStats renderFrame(const FrameControl& control) {
    Run& r = *run;
    const RenderSettings& s = r.settings;
    RenderOutput& out = r.out;
    const uint32_t f = r.frame++;
    const bool animated = r.animated;
    bool& movedBefore = r.movedBefore;
    glm::mat4& prevClipFromWorld = r.prevClipFromWorld;
    scene::Camera& prevCamera = r.prevCamera;
    auto [ldrReadback, hdrReadback, ldrState, hdrState, aovReadback, aovStates] =
        std::tie(r.ldrReadback, r.hdrReadback, r.ldrState, r.hdrState, r.aovReadback, r.aovStates);
    const bool rasterMode = s.mode == Mode::Raster;
    FrameStats stats;
    {
      const Clock::time_point frameStart = Clock::now();
      frameIndex = f;
      for (const RenderSettings::Move& m : s.moves)  // before the constants: the first edit may move the table
        if (m.frame == f) {
          const uint32_t i = uint32_t(findInstance(m.instance));
          glm::mat4 w = motion.get(scene, i);
          w[3] = glm::vec4(m.position, 1.0f);
          motion.set(ctx, gpu, i, w);
        }
      const scene::Camera camera = control.camera  ? *control.camera
                                   : s.cameraPath ? cameraOnPath(*r.cam, s, f)
                                                  : *r.cam;
      // A cut (the first frame of a run, a jump of the camera, or a listed frame) restarts every history.
      const bool cut = f == 0 || control.cut || isCameraCut(prevCamera, camera) ||
                       std::find(s.cuts.begin(), s.cuts.end(), f) != s.cuts.end();
      if (cut || !taaHistory.valid) taaFrames = 0;
      const glm::vec2 jitter = s.taa ? jitterNdc(f, s.width, s.height) : glm::vec2(0.0f);
      prevClipFromWorld = writeConstants(s, camera, jitter, cut ? nullptr : &prevClipFromWorld);
      prevCamera = camera;
      const bool last = control.readback;
      graph::RenderGraph graph(&ctx, &transients);
      FrameInputs in{pipelines, gpu, constants, nearest, linear, {s.width, s.height}, gpu.bindless->set()};
      bool moving = s.cameraPath || control.moving;
      {
        const bool moved =
            motion.update(gpu, animated, s.time + (s.animate ? float(f) / s.pathFps : 0.0f), f == 0).moved;
        // Motion vectors of this frame still show last frame's motion after the pose stops.
        moving = moving || moved || movedBefore;
        movedBefore = moved;
        if (motion.takeTlasRefit(!rasterMode) && !rasterMode)  // the raster mode refits when it leaves
          graph.addPass("tlas-update", [](graph::PassBuilder& b) { b.sideEffect(); },
                        [this](graph::PassContext& pc) { gpu.tlas.update(pc.cmd, gpu.tlasInstances); });
      }

      GBuffer gb = out.primaryUsed == Primary::Traced ? traceGBuffer(graph, in) : rasterGBuffer(graph, in);
      graph::ImageHandle raw, visibility, specularRaw, specular, aoRaw, ao, indirectRaw, indirect, hdr;
      if (rasterMode) {
        const RasterFrameOutput r = raster.record(graph, in, gb, scene, camera, shadowLights());
        raw = visibility = r.visibility;
        specularRaw = specular = r.specular;
        aoRaw = ao = r.ao;
        indirectRaw = indirect = r.indirect;
        hdr = r.hdr;
      } else {
        // Every run starts without history, and so does a camera cut; while the camera or an object
        // moves, the denoisers keep short histories.
        const TemporalState temporal{moving, f == 0 || cut || !surfaceHistory.valid};
        const DenoiseInputs dn{pipelines.denoise, nearest.handle(), in.size};
        const SurfacePair surface{
            writeSurface(graph, dn, gb.depth, gb.normals, gb.id, surfaceHistory.next(graph, "surface", f),
                         camera.zNear, camera.zFar),
            surfaceHistory.previous(graph, "surface", f)};
        const graph::ImageHandle motion = gb.motion;

        raw = traceShadows(graph, in, gb, shadowLights());
        if (s.rawRays) {
          if (!rawPipelines) rawPipelines = RawRayPipelines::create(ctx, gpu.bindless->layout());
          traceRawPrimary(graph, in, *rawPipelines);
          traceRawShadows(graph, in, gb, shadowLights(), *rawPipelines);
        }
        // Many-light mode traces no shadow layers: lighting reads none, so nothing to denoise.
        visibility = raw;
        if (shadowLights() > 0)
          visibility = denoiseShadows(graph, dn, surface, motion, raw,
                                      {shadowHistory.previous(graph, "shadow-history", f),
                                       shadowHistory.next(graph, "shadow-history", f)},
                                      temporal)
                           .denoised;
        specularRaw = traceSpecular(graph, in, gb);
        specular =
            denoiseRadiance(graph, dn, "reflection", surface, motion, gb.material, specularRaw,
                            specularHistory.colorPair(graph, "specular", f),
                            specularHistory.momentsPair(graph, "specular", f), temporal)
                .denoised;
        graph::ImageHandle direct;
        if (manyLights)
          direct = denoiseRadiance(graph, dn, "direct", surface, motion, gb.material, traceDirect(graph, in, gb),
                                   directHistory.colorPair(graph, "direct", f),
                                   directHistory.momentsPair(graph, "direct", f), temporal)
                       .denoised;
        // When an effect is off its raw image is constant and goes to lighting as is.
        aoRaw = traceAo(graph, in, gb);
        ao = aoRaw;
        if (s.ao)
          ao = denoiseShadows(graph, dn, surface, motion, aoRaw,
                              {aoHistory.previous(graph, "ao-history", f), aoHistory.next(graph, "ao-history", f)},
                              temporal, "ao")
                   .denoised;
        indirectRaw = traceIndirect(graph, in, gb);
        indirect = indirectRaw;
        if (indirectOn(s))
          indirect = denoiseRadiance(graph, dn, "indirect", surface, motion, gb.material, indirectRaw,
                                     indirectHistory.colorPair(graph, "indirect", f),
                                     indirectHistory.momentsPair(graph, "indirect", f), temporal)
                         .denoised;
        hdr = shadeLighting(graph, in, gb, {visibility, specular, ao, indirect, direct});
      }
      if (s.taa)
        hdr = resolveTaa(graph, in,
                         {hdr, gb.depth, taaHistory.previous(graph, "taa-history", f),
                          taaHistory.next(graph, "taa-history", f), gb.motion, taaFrames});
      graph::ImageHandle ldr = tonemap(graph, in, hdr, {std::exp2(s.exposureEv), s.tonemap, s.seed});
      if (control.present)
        copyToOutput(graph, ldr);
      else if (!last)
        // Every frame's image counts as consumed, as a presented one would be: otherwise the graph
        // culls tonemapping in all frames but the last (whose readback uses it) and its timings miss them.
        graph.addPass("output", [&](graph::PassBuilder& b) {
          b.read(ldr, graph::Use::TransferSrc);
          b.sideEffect();
        }, [](graph::PassContext&) {});
      if (last) {
        aovReadback.clear();  // only the latest readback frame's AOVs are kept
        aovStates.clear();
        readback(graph, ldr, graph.importBuffer("ldr-readback", &ldrReadback, &ldrState));
        readback(graph, hdr, graph.importBuffer("hdr-readback", &hdrReadback, &hdrState));
        // "denoised" stages are the temporal accumulation until the denoisers exist.
        // Stage → (image, layer); the visibility arrays hold one layer per shadowed light.
        std::map<std::string, std::pair<graph::ImageHandle, uint32_t>> stages = {
            {"depth", {gb.depth, 0}},       {"normal", {gb.normals, 0}},          {"albedo", {gb.albedo, 0}},
            {"material", {gb.material, 0}}, {"emissive", {gb.emissive, 0}},       {"motion", {gb.motion, 0}},
            {"shadow-raw", {raw, 0}},       {"shadow-denoised", {visibility, 0}}, {"reflection-raw", {specularRaw, 0}},
            {"reflection-denoised", {specular, 0}}, {"ao-raw", {aoRaw, 0}},       {"ao-denoised", {ao, 0}},
            {"indirect-raw", {indirectRaw, 0}},     {"indirect-denoised", {indirect, 0}}};
        for (uint32_t i = 0; i < shadowLights(); ++i) {
          stages["shadow" + std::to_string(i) + "-raw"] = {raw, i};
          stages["shadow" + std::to_string(i) + "-denoised"] = {visibility, i};
        }
        for (const std::string& name : s.aovs) {
          auto it = stages.find(name);
          if (name == "variance") {
            log::info("AOV 'variance' skipped: only --mode pathtrace has it");
            continue;
          }
          if (it == stages.end()) {  // a light the scene does not have
            log::info("AOV '{}' skipped: the scene has {} shadowed light(s)", name, shadowLights());
            continue;
          }
          const rhi::ImageDesc& d = graph.imageDesc(it->second.first);
          aovReadback.push_back(Run::AovReadback{name, d.format, it->second.second,
                                 rhi::Buffer(ctx, size_t(d.width) * d.height * texelBytes(d.format) * d.layers,
                                             VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback,
                                             "aov-readback")});
          aovStates.emplace_back();
        }
        for (size_t i = 0; i < aovReadback.size(); ++i)
          readback(graph, stages.at(aovReadback[i].name).first,
                   graph.importBuffer("aov-readback", &aovReadback[i].buffer, &aovStates[i]));
      }

      VkCommandBuffer cmd = commands.begin();
      timers.reset(cmd);
      graph.execute(cmd, &timers);
      const uint64_t submitted = commands.submit();
      const double cpuMs = msSince(frameStart);
      ctx.wait(submitted);
      const double wallMs = msSince(frameStart);
      for (History* h : {&surfaceHistory, &shadowHistory, &aoHistory}) h->valid = true;
      const bool measured = f >= s.warmupFrames || s.warmupFrames >= s.frames;  // never an empty sample
      double gpuMs = 0;
      for (auto& t : timers.read()) {
        if (t.name.rfind("readback", 0) == 0 || t.name.rfind("host-visible", 0) == 0 || t.name.rfind("output", 0) == 0)
          continue;
        stats.passes.emplace_back(t.name, t.ms);
        if (t.name.rfind("raw-", 0) != 0) gpuMs += t.ms;  // raw-rate passes are not part of the frame
        if (!measured) continue;
        if (!r.passTimes.count(t.name)) r.passOrder.push_back(t.name);
        r.passTimes[t.name].push_back(t.ms);
      }
      stats.gpuMs = gpuMs;
      if (measured) {
        out.frameGpuMs.push_back(gpuMs);
        out.frameCpuMs.push_back(cpuMs);
        out.frameWallMs.push_back(wallMs);
      }
      ctx.collectGarbage();
      if (s.taa) {
        taaHistory.valid = true;
        ++taaFrames;
      }
      stats.primaryUsed = out.primaryUsed;
      out.visibleDraws = stats.visibleDraws = out.primaryUsed == Primary::Raster ? int64_t(visibleDraws(gpu)) : -1;
      out.totalDraws = uint32_t(gpu.draws.size());
      stats.camera = camera;
    }
    return stats;
  }

  RenderOutput endRun() {
    Run& r = *run;
    RenderOutput out = std::move(r.out);
    readImages(out);
    auto [passTimes, passOrder] = std::tie(r.passTimes, r.passOrder);

    const RenderSettings& s = r.settings;
    const uint32_t lightsPerHit = manyLights ? 1u : gpu.lightCount;
    const uint32_t bounces = specularBounces(s);
    for (const std::string& name : passOrder) {
      std::vector<double> v = passTimes[name];
      std::sort(v.begin(), v.end());
      PassStats ps{name, v[v.size() / 2], v.front(), v[std::min(v.size() - 1, size_t(std::ceil(0.95 * v.size())) - 1)],
                   uint32_t(v.size())};
      ps.samplesMs = passTimes[name];
      RayCount rc = launchedRays(name, s.width, s.height, shadowLights(), lightsPerHit, bounces);
      if ((name == "rt-ao" && !s.ao) || (name == "rt-indirect" && !indirectOn(s))) rc = {};  // the shader returns at once
      ps.rays = rc.rays;
      ps.raysExact = rc.exact;
      if (name.rfind("raw-", 0) != 0) out.frameMedianMs += ps.medianMs;
      out.passes.push_back(ps);
    }
    run.reset();
    return out;
  }

  // The images of the last frame rendered with readback, and the scene's statistics.
  void readImages(RenderOutput& out) {
    Run& r = *run;
    const RenderSettings& s = r.settings;
    const size_t pixels = size_t(s.width) * s.height;
    auto [ldrReadback, hdrReadback, aovReadback] = std::tie(r.ldrReadback, r.hdrReadback, r.aovReadback);
    out.scene = sceneStats();
    out.shadowLayers = shadowLights();
    out.ldr = Image8::make(int(s.width), int(s.height));
    std::memcpy(out.ldr.rgba.data(), ldrReadback.mapped(), pixels * 4);
    out.hdr = ImageF::make(int(s.width), int(s.height));
    const uint16_t* halves = static_cast<const uint16_t*>(hdrReadback.mapped());
    for (size_t i = 0; i < pixels * 4; ++i) out.hdr.rgba[i] = halfToFloat(halves[i]);
    for (auto& [name, format, layer, buffer] : aovReadback) {
      ImageF img = ImageF::make(int(s.width), int(s.height));
      const uint8_t* data = static_cast<const uint8_t*>(buffer.mapped()) + size_t(layer) * pixels * texelBytes(format);
      for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 4; ++c) img.rgba[i * 4 + c] = texel(data, format, i, c);
      out.aovs.emplace_back(name, std::move(img));
    }
  }

  // Copies the tonemapped image into `output` and leaves it ready as a transfer source, so the
  // caller's next submission can blit it (the next frame's copy waits for that read).
  void copyToOutput(graph::RenderGraph& graph, graph::ImageHandle ldr) {
    const rhi::ImageDesc& d = graph.imageDesc(ldr);
    const rhi::ImageDesc desc{d.format, d.width, d.height, 1,
                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT};
    if (!output || !(output.desc() == desc)) {
      output = rhi::Image(ctx, desc, "output");
      outputState = {};
    }
    graph::ImageHandle dst = graph.importImage("output", &output, &outputState);
    graph.addPass(
        "output-copy",
        [&](graph::PassBuilder& b) {
          b.read(ldr, graph::Use::TransferSrc);
          b.write(dst, graph::Use::TransferDst);
        },
        [ldr, dst](graph::PassContext& pc) {
          const rhi::Image& src = pc.image(ldr);
          VkImageCopy region{};
          region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
          region.extent = {src.desc().width, src.desc().height, 1};
          vkCmdCopyImage(pc.cmd, src.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, pc.image(dst).handle(),
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        });
    graph.addPass(
        "output-ready",
        [&](graph::PassBuilder& b) {
          b.read(dst, graph::Use::TransferSrc);
          b.sideEffect();
        },
        [](graph::PassContext&) {});
  }

  Result<RenderOutput> render(const RenderSettings& s) {
    if (auto begun = beginRun(s); !begun) return begun.error();
    for (uint32_t f = 0; f < s.frames; ++f) {
      renderFrame({.readback = f + 1 == s.frames});
      if (s.progress) s.progress(f + 1, s.frames);
    }
    return endRun();
  }
};

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;

Result<std::unique_ptr<Renderer>> Renderer::create(rhi::Context& ctx, const scene::Scene& scene) {
  if (scene.cameras.empty()) return makeError(ExitCode::BadInput, "scene '{}' has no camera", scene.name);
  auto gpu = uploadScene(ctx, scene);
  if (!gpu) return gpu.error();
  log::debug("scene '{}': {} triangles, BLAS {} KiB (compacted from {} KiB), built in {:.1f} ms", scene.name,
             gpu->triangleCount, gpu->accelStats.compactedBytes / 1024, gpu->accelStats.builtBytes / 1024,
             gpu->accelBuildMs);
  return std::unique_ptr<Renderer>(new Renderer(std::make_unique<Impl>(ctx, scene, std::move(gpu.value()))));
}

Result<RenderOutput> Renderer::render(const RenderSettings& settings) {
  // Callers fall back to the raster mode themselves (the CLI says so in one line).
  if (settings.mode != Mode::Raster && !impl_->ctx.caps().rayTracing())
    return makeError(ExitCode::MissingCapability, "{} has no ray-tracing pipelines: --mode {} needs them",
                     impl_->ctx.info().name, modeName(settings.mode));
  if (settings.mode == Mode::PathTrace) return impl_->renderPathTraced(settings);
  return impl_->render(settings);
}

Status Renderer::beginRun(const RenderSettings& settings) {
  if (settings.mode != Mode::Hybrid)
    return makeError(ExitCode::BadArguments, "--mode {} is not implemented yet", modeName(settings.mode));
  return impl_->beginRun(settings);
}

FrameStats Renderer::renderFrame(const FrameControl& control) { return impl_->renderFrame(control); }
RenderOutput Renderer::endRun() { return impl_->endRun(); }
const rhi::Image& Renderer::outputImage() const { return impl_->output; }

RenderOutput Renderer::readbackImages() {
  RenderOutput out;
  impl_->readImages(out);
  return out;
}

void Renderer::refreshLights() {
  Impl& m = *impl_;
  std::vector<gpu::LightRecord> rows;
  for (const scene::Light& l : m.scene.lights) rows.push_back(toRecord(l));
  if (rows.empty() || rows.size() != m.gpu.lightCount) return;  // edits only, never a new count
  m.gpu.lights = rhi::createBufferWithData(m.ctx, std::as_bytes(std::span(rows)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                           "lights");
}

void Renderer::setInstanceTransform(uint32_t sceneInstance, const glm::mat4& worldFromObject) {
  impl_->motion.set(impl_->ctx, impl_->gpu, sceneInstance, worldFromObject);
}

void Renderer::reloadPipelines() {
  impl_->ctx.waitIdle();
  impl_->pipelines = Pipelines::create(impl_->ctx, impl_->gpu.bindless->layout());
  impl_->rawPipelines.reset();
  impl_->pathTracer.reset();
}

glm::mat4 Renderer::instanceTransform(uint32_t sceneInstance) const {
  return impl_->motion.get(impl_->scene, sceneInstance);
}

uint64_t Renderer::deviceBytesUsed() const { return impl_->ctx.memory().stats().usedBytes; }

} // namespace rayster::render
