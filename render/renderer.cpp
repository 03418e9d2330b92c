#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/log.h"
#include "render/frame_memory.h"
#include "render/jitter.h"
#include "render/passes/cull.h"
#include "render/renderer_impl.h"
#include "render/settings_table.h"
#include "rhi/memory.h"
#include "shaders/shared/exposure.h"
#include "shaders/shared/types.h"

namespace rayster::render {

const std::vector<std::string>& aovNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = {"depth",
                                  "normal",
                                  "albedo",
                                  "material",
                                  "emissive",
                                  "specular",
                                  "motion",
                                  "shadow-raw",
                                  "shadow-denoised",
                                  "reflection-raw",
                                  "reflection-denoised",
                                  "ao-raw",
                                  "ao-denoised",
                                  "indirect-raw",
                                  "indirect-denoised"};
    // Per shadowed light: layer i of the visibility arrays ("shadow-raw" is layer 0).
    for (uint32_t i = 0; i < gpu::kMaxShadowLights; ++i) n.push_back("shadow" + std::to_string(i) + "-raw");
    for (uint32_t i = 0; i < gpu::kMaxShadowLights; ++i) n.push_back("shadow" + std::to_string(i) + "-denoised");
    n.push_back("variance");  // --mode pathtrace: the per-pixel variance of the accumulated mean
    for (const char* raw : {"raw-ao", "raw-direct", "raw-indirect", "raw-specular"}) n.push_back(raw);  // --raw-rays
    return n;
  }();
  return names;
}

const char* modeName(Mode m) {
  switch (m) {
    case Mode::PathTrace:
      return "pathtrace";
    case Mode::Raster:
      return "raster";
    default:
      return "hybrid";
  }
}

const char* indirectRateName(IndirectRate r) { return r == IndirectRate::Quarter ? "quarter" : "full"; }

const char* primaryName(Primary p) {
  switch (p) {
    case Primary::Raster:
      return "raster";
    case Primary::Traced:
      return "rt";
    default:
      return "auto";
  }
}

void Renderer::Impl::logMeteredExposure(const std::string& how) {
  const float ev = exposure.ev100();
  if (std::abs(ev - loggedEv100) < 0.005f) {
    log::debug("exposure: auto, EV100 {:.2f} ({})", ev, how);
    return;
  }
  loggedEv100 = ev;
  log::info("exposure: auto, EV100 {:.2f} ({})", ev, how);
}

Renderer::Impl::Impl(rhi::Context& c, const scene::Scene& s, GpuScene g)
    : ctx(c),
      scene(s),
      gpu(std::move(g)),
      pipelines(c, gpu.bindless->layout()),
      nearest(c, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE),
      linear(c, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE),
      constants(c, sizeof(gpu::FrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, rhi::MemoryUsage::Upload,
                "frame-constants"),
      commands(c),
      timers(c, kMaxTimedPasses),
      neutral(c),
      specular(specularSurfaces(s)),
      raster(c) {}

float Renderer::Impl::aoRadius(const RenderSettings& s) const {
  if (s.aoRadius > 0.0f) return s.aoRadius;
  const scene::Aabb& b = gpu.bounds;
  const float diagonal = b.valid() ? glm::length(b.max - b.min) : 0.0f;
  return diagonal > 0.0f ? kAoRadiusFraction * diagonal : 1.0f;
}

int32_t Renderer::Impl::findInstance(const std::string& name) const {
  for (size_t i = 0; i < scene.instances.size(); ++i)
    if (scene.instances[i].name == name && gpu.instanceRowOf[i] >= 0) return int32_t(i);
  return -1;
}

glm::mat4 Renderer::Impl::writeConstants(const RenderSettings& s, const scene::Camera& cam, glm::vec2 jitter,
                                         const glm::mat4* prevClipFromWorld) {
  gpu::FrameConstants fc{};
  const float aspect = float(s.width) / float(s.height);
  // In double, then rounded once: with a near plane of 1 mm the projection's depth row is ~1e-3 of
  // the others, and a float product and inverse lose enough digits to bend every position the
  // G-buffer reconstructs from depth (self-shadowing streaks on traced primaries).
  const glm::dmat4 view = glm::lookAt(glm::dvec3(cam.position), glm::dvec3(cam.target), glm::dvec3(cam.up));
  // Reversed Z (near → 1, far → 0): swapping the planes in a [0,1]-depth projection does it.
  glm::dmat4 proj = glm::perspective(double(cam.yFov), double(aspect), double(cam.zFar), double(cam.zNear));
  proj[1][1] *= -1.0;  // Vulkan clip space: y points down
  const glm::dmat4 clipFromWorld = proj * view;
  fc.unjitteredClipFromWorld = glm::mat4(clipFromWorld);
  fc.prevClipFromWorld = prevClipFromWorld ? *prevClipFromWorld : fc.unjitteredClipFromWorld;
  fc.jitter = jitter;
  // Raster and traced primaries (and every position reconstructed from depth) follow the jitter.
  const glm::dmat4 jittered = jitteredClipFromWorld(clipFromWorld, glm::dvec2(jitter));
  fc.clipFromWorld = glm::mat4(jittered);
  fc.worldFromClip = glm::mat4(glm::inverse(jittered));
  fc.cameraPosition = glm::vec4(cam.position, 1.0f);
  // Every source is pre-exposed (lib/frame.glsl: lights and emission in the shaders, the rest here).
  const float exposure = this->exposure.exposure();
  fc.ambient = glm::vec4(scene.ambient * exposure, 0.0f);
  fc.size = {s.width, s.height};
  fc.frameIndex = frameIndex;
  fc.seed = s.seed;
  fc.lightCount = gpu.lightCount;
  fc.shadowLightCount = shadowLights();
  fc.aoLayer = aoInShadowImage(s) ? shadowLights() : 0u;
  fc.manyLights = manyLights ? 1u : 0u;
  fc.exposure = exposure;
  fc.exposureRatio = this->exposure.ratio();
  fc.geometries = gpu.geometries.address();
  fc.instances = gpu.instances.address();
  fc.materials = gpu.materials.address();
  fc.lights = gpu.lights.address();
  const scene::Environment& env = scene.environment;
  fc.environmentKind = gpu.environment.kind;
  fc.environment = glm::vec4(glm::vec3(env.intensity * exposure), env.rotation);
  fc.environmentSlot = gpu.environment.slot;
  fc.prefilteredSlot = gpu.environment.prefilteredSlot;
  fc.skyZenith = env.zenith;
  fc.skyHorizon = env.horizon;
  fc.skyGround = env.ground;
  for (int k = 0; k < 9; ++k) fc.irradianceSh[k] = glm::vec4(gpu.environment.irradianceSh[k] * exposure, 0.0f);
  fc.sceneFlags = gpu.anyHit ? gpu::kSceneAnyHit : 0u;
  fc.mirrorRoughness = s.mirrorRoughness;
  fc.glossyThreshold = s.glossyThreshold;
  fc.aoRadius = aoRadius(s);
  // Untraced glossy light (rougher than the glossy threshold) comes from the GGX-prefiltered
  // environment in both modes. The raster mode has neither AO nor indirect light: ambient and the
  // SH environment stand in.
  fc.effectFlags =
      gpu::kEffectPrefilteredEnv |
      (s.mode == Mode::Raster ? 0u : (s.ao ? gpu::kEffectAo : 0u) | (indirectOn(s) ? gpu::kEffectIndirect : 0u)) |
      (indirectQuarter(s) ? gpu::kEffectIndirectQuarter : 0u) | (aoHalfRate(s) ? gpu::kEffectAoHalf : 0u) |
      (s.mode != Mode::Raster && indirectOn(s) && passSettingText(s, "gi") == "probes" ? gpu::kEffectIndirectSpecular
                                                                                       : 0u) |
      (s.shadows ? gpu::kEffectShadows : 0u) | (s.reflections ? gpu::kEffectReflections : 0u);
  fc.dfgSlot = gpu.dfgSlot;
  fc.sheenSlot = gpu.sheenSlot;
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

double Renderer::Impl::timeProducer(const RenderSettings& s, Primary p) {
  double ms = 0;
  for (int run = 0; run < 2; ++run) {
    ms = 0;
    graph::RenderGraph graph(&ctx, &transients);
    const graph::AccelHandle tlas = beginFrameGraph(graph, gpu, constants, nearest);
    FrameInputs in{pipelines, gpu, constants, nearest, linear, {s.width, s.height}, tlas};
    GBuffer gb = p == Primary::Traced ? traceGBuffer(graph, in) : rasterGBuffer(graph, in);
    graph.addPass(
        "keep",
        [&](graph::PassBuilder& b) {
          b.read(gb.normals, graph::Use::SampledCompute);
          b.sideEffect();
          b.kind(graph::PassKind::Utility);
        },
        [](graph::PassContext&) {});
    VkCommandBuffer cmd = commands.begin();
    timers.reset(cmd);
    graph.execute(cmd, &timers);
    ctx.wait(commands.submit());
    for (const auto& t : graph.readTimings(timers))  // the producer's passes (raster: culling and draws too)
      if (t.info.kind == graph::PassKind::Frame) ms += t.ms;
  }
  return ms;
}

scene::Camera Renderer::Impl::cameraOnPath(const scene::Camera& base, const RenderSettings& s, uint32_t frame) const {
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

Result<const scene::Camera*> Renderer::Impl::findCamera(const RenderSettings& s) const {
  if (s.camera.empty()) return &scene.cameras.front();
  auto it = std::find_if(scene.cameras.begin(), scene.cameras.end(),
                         [&](const scene::Camera& c) { return c.name == s.camera; });
  if (it == scene.cameras.end())
    return makeError(ExitCode::BadArguments, "the scene has no camera named '{}'", s.camera);
  return &*it;
}

RenderOutput::SceneStats Renderer::Impl::sceneStats() const {
  RenderOutput::SceneStats st{gpu.triangleCount,
                              gpu.sphereCount,
                              gpu.accelStats.builtBytes,
                              gpu.accelStats.compactedBytes,
                              gpu.accelStats.tlasBytes,
                              gpu.uploadMs,
                              gpu.accelBuildMs,
                              0,
                              0};
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

Result<RenderOutput> Renderer::Impl::renderPathTraced(const RenderSettings& s) {
  auto cam = findCamera(s);
  if (!cam) return cam.error();
  if ((s.cameraPath || (scene.animated() && s.animate)) && s.frameOffset == 0)
    log::info("--mode pathtrace renders one image: the camera and the pose at --time ({} s)", s.time);
  if (!pathTracer) pathTracer = std::make_unique<PathTracer>();
  beginExposure(s, **cam);
  const PathTraceResources r{ctx, gpu, pipelines, constants, nearest, linear, transients, histories, commands, timers};
  auto write = [&](uint32_t f) {
    frameIndex = f;
    exposure.beginFrame(true);  // one exposure for the whole accumulation
    writeConstants(s, **cam, glm::vec2(0.0f), nullptr);
  };
  // A hybrid frame poses the scene at --time for the path tracer (instance table, TLAS, deformed
  // meshes: they stay as that frame leaves them) and meters the exposure.
  const bool posed = scene.animated() || gpu.deformers;
  if (exposure.automatic() || posed) {
    // Metered as the hybrid meters the same view (its metering frames, traced primaries): the
    // reference and the hybrid render a scene at one exposure, so their images compare as they are.
    RenderSettings meter = s;
    meter.mode = Mode::Hybrid;
    meter.primary = Primary::Traced;
    meter.aovs.clear();
    if (Status begun = beginRun(meter); !begun) return begun.error();
    for (uint32_t k = 0; k < kMeterFrames; ++k)
      if (renderFrame({.meter = true}); !exposure.automatic() || run->meterDistance <= kMeterSettled) break;
    run.reset();
    if (exposure.automatic()) {
      exposure.beginFrame(true);
      logMeteredExposure("metered by the hybrid");
    }
  }
  // Emitters that are animated or deform light from that pose too.
  poseEmissiveTriangles(ctx, scene, motion.pose(scene, scene.animated() && !gpu.instanceRecords.empty()), gpu);
  // A camera on an animated node: where the posing frame left it; on the camera path, at its frame.
  scene::Camera posedCamera = motion.camera(scene, **cam, scene.animated() && !gpu.instanceRecords.empty());
  if (s.cameraPath && !scene.cameraPath.empty())
    posedCamera = cameraOnPath(posedCamera, s, uint32_t(std::max<int64_t>(0, s.frameOffset)));
  *cam = &posedCamera;
  manyLights = false;
  auto out = pathTracer->render(s, r, exposure.exposure(), write);
  if (out) out->scene = sceneStats();
  return out;
}

void Renderer::Impl::beginExposure(const RenderSettings& s, const scene::Camera& cam) {
  const float environment = 0.282095f * glm::dot(gpu.environment.irradianceSh[0], glm::vec3(0.2126f, 0.7152f, 0.0722f));
  exposure.begin(s, estimateEv100(scene, cam, std::max(environment, 0.0f)));
  if (!exposure.automatic() || exposureHistogram.handle() != VK_NULL_HANDLE) return;
  const VkDeviceSize bytes = gpu::kExposureHistograms * gpu::kExposureBins * sizeof(uint32_t);
  exposureHistogram = rhi::Buffer(
      ctx, bytes,
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
      rhi::MemoryUsage::GpuOnly, "exposure-histogram");
  exposureReadback =
      rhi::Buffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "exposure-readback");
}

Status Renderer::Impl::beginRun(const RenderSettings& s) {
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
  beginExposure(s, *cam);
  const bool rasterMode = s.mode == Mode::Raster;
  out.modeUsed = s.mode;
  // The raster mode shadows the first shadowLights lights from shadow maps and leaves the rest
  // unshadowed: stochastic light selection needs shadow rays.
  shadows = s.shadows;
  manyLights = shadows && !rasterMode && gpu.lightCount > std::min(s.shadowLights, gpu::kMaxShadowLights);
  if (manyLights)
    log::info("{} lights, {} shadow layers: one light per pixel by importance", gpu.lightCount,
              std::min(s.shadowLights, gpu::kMaxShadowLights));
  writeConstants(s, *cam, glm::vec2(0.0f), nullptr);
  out.primaryUsed = rasterMode ? Primary::Raster : s.primary;
  if (out.primaryUsed == Primary::Auto) {
    // On the H100 the raster G-buffer costs many times the traced one; elsewhere raster is cheap.
    out.rasterGBufferMs = timeProducer(s, Primary::Raster);
    out.tracedGBufferMs = timeProducer(s, Primary::Traced);
    out.primaryUsed =
        out.tracedGBufferMs >= 0 && out.tracedGBufferMs < out.rasterGBufferMs ? Primary::Traced : Primary::Raster;
    log::info("primary: auto chose {} (raster G-buffer {:.3f} ms, traced {:.3f} ms)", primaryName(out.primaryUsed),
              out.rasterGBufferMs, out.tracedGBufferMs);
  }

  run->animated = scene.animated() && !gpu.instanceRecords.empty();
  motion.beginRun(ctx, scene, run->animated);
  for (const RenderSettings::Move& m : s.moves)
    if (findInstance(m.instance) < 0)
      return makeError(ExitCode::BadArguments, "--move-instance: scene '{}' has no instance '{}'", scene.name,
                       m.instance);
  run->prevCamera = *cam;
  const size_t pixels = size_t(s.width) * s.height;
  run->ldrReadback =
      rhi::Buffer(ctx, pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "ldr-readback");
  run->hdrReadback =
      rhi::Buffer(ctx, pixels * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "hdr-readback");
  return okStatus();  // AOV names are checked against the first frame's images (checkAovs)
}

Result<RenderOutput> Renderer::Impl::render(const RenderSettings& s) {
  if (auto begun = beginRun(s); !begun) return begun.error();
  run->adaptExposure = s.cameraPath || run->animated || !s.moves.empty();
  if (exposure.automatic()) {
    // The first frame of the shot, rendered until its metered exposure holds (a frame rendered far
    // from its exposure clips in fp16 and in the firefly clamps, so its reading is re-taken at the
    // exposure it gave): every output frame then starts from the same exposure, whatever came before.
    uint32_t k = 0;
    while (k < kMeterFrames) {
      renderFrame({.meter = true});
      ++k;
      if (run->failure || run->meterDistance <= kMeterSettled) break;
    }
    logMeteredExposure(fmt::format("metered in {} frame{}", k, k == 1 ? "" : "s"));
    gpu.cull->visibilityFresh = true;  // the first output frame culls as if nothing came before
  }
  for (uint32_t f = 0; f < s.frames || run->failure; ++f) {
    if (!run->failure) renderFrame({.readback = f + 1 == s.frames});
    if (run->failure) {
      Error e = *run->failure;
      ctx.waitIdle();
      run.reset();
      return e;
    }
    if (s.progress) s.progress(f + 1, s.frames);
    if (s.stop && f + 1 < s.frames && !run->failure) run->failure = s.stop();
  }
  return endRun();
}

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;

Result<std::unique_ptr<Renderer>> Renderer::create(rhi::Context& ctx, const scene::Scene& scene) {
  if (scene.cameras.empty()) return makeError(ExitCode::BadInput, "scene '{}' has no camera", scene.name);
  auto gpu = uploadScene(ctx, scene);
  if (!gpu) return gpu.error();
  log::debug("scene '{}': {} triangles, BLAS {} KiB (compacted from {} KiB), built in {:.1f} ms", scene.name,
             gpu->triangleCount, gpu->accelStats.compactedBytes / 1024, gpu->accelStats.builtBytes / 1024,
             gpu->accelBuildMs);
  auto impl = std::make_unique<Impl>(ctx, scene, std::move(gpu.value()));
  impl->layerWarning = layersApproximated(scene);
  return std::unique_ptr<Renderer>(new Renderer(std::move(impl)));
}

namespace {
void warnLayersOnce(std::string& warning) {
  if (warning.empty()) return;
  log::warn("{}", warning);
  warning.clear();
}
}  // namespace

Result<RenderOutput> Renderer::render(const RenderSettings& settings) {
  // Callers fall back to the raster mode themselves (the CLI says so in one line).
  if (settings.mode != Mode::Raster && !impl_->ctx.caps().rayTracing())
    return makeError(ExitCode::MissingCapability, "{} has no ray-tracing pipelines: --mode {} needs them",
                     impl_->ctx.info().name, modeName(settings.mode));
  if (settings.mode == Mode::PathTrace) return impl_->renderPathTraced(settings);
  warnLayersOnce(impl_->layerWarning);
  return impl_->render(settings);
}

Status Renderer::beginRun(const RenderSettings& settings) {
  if (settings.mode != Mode::Hybrid)
    return makeError(ExitCode::BadArguments, "--mode {} is not implemented yet", modeName(settings.mode));
  warnLayersOnce(impl_->layerWarning);
  Status begun = impl_->beginRun(settings);
  if (begun) impl_->run->adaptExposure = true;  // an interactive run: the exposure follows the view
  return begun;
}

void Renderer::restartHistories() {
  impl_->exposure.forget();
  impl_->gpu.cull->visibilityFresh = true;
}

void Renderer::updateSettings(const RenderSettings& settings) {
  if (!impl_->run) return;
  for (const Setting& s : settingsTable())
    if (!s.restarts) (void)s.set(impl_->run->settings, s.get(settings));  // the value came from a valid setting
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
  m.gpu.lights =
      rhi::createBufferWithData(m.ctx, std::as_bytes(std::span(rows)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "lights");
}

void Renderer::setInstanceTransform(uint32_t sceneInstance, const glm::mat4& worldFromObject) {
  impl_->motion.set(impl_->ctx, impl_->gpu, sceneInstance, worldFromObject);
}

void Renderer::reloadPipelines() {
  impl_->ctx.waitIdle();
  impl_->pipelines.clear();  // the next frame creates the pipelines it uses from the new shaders
  impl_->pathTracer.reset();
}

glm::mat4 Renderer::instanceTransform(uint32_t sceneInstance) const {
  return impl_->motion.get(impl_->scene, sceneInstance);
}

uint64_t Renderer::deviceBytesUsed() const { return impl_->ctx.memory().stats().usedBytes; }
const GpuScene& Renderer::gpuScene() const { return impl_->gpu; }

}  // namespace rayster::render
