#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "core/half.h"
#include "core/log.h"
#include "graph/graph.h"
#include "render/gpu_scene.h"
#include "render/history.h"
#include "render/passes/denoise.h"
#include "render/passes/passes.h"
#include "render/pipelines.h"
#include "rhi/commands.h"
#include "rhi/context.h"
#include "rhi/memory.h"
#include "shaders/shared/types.h"

namespace rayster::render {

const std::vector<std::string>& aovNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = {"depth",          "normal",          "albedo",        "material",
                                  "emissive",       "shadow-raw",      "shadow-denoised", "reflection-raw",
                                  "reflection-denoised"};
    // Per shadowed light: layer i of the visibility arrays ("shadow-raw" is layer 0).
    for (uint32_t i = 0; i < gpu::kMaxShadowLights; ++i) n.push_back("shadow" + std::to_string(i) + "-raw");
    for (uint32_t i = 0; i < gpu::kMaxShadowLights; ++i) n.push_back("shadow" + std::to_string(i) + "-denoised");
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
    case VK_FORMAT_R16G16B16A16_SFLOAT: return halfToFloat(reinterpret_cast<const uint16_t*>(data)[index * 4 + channel]);
    case VK_FORMAT_R32G32B32A32_SFLOAT: return reinterpret_cast<const float*>(data)[index * 4 + channel];
    case VK_FORMAT_R16G16B16A16_SNORM:
      return std::max(-1.0f, reinterpret_cast<const int16_t*>(data)[index * 4 + channel] / 32767.0f);
    case VK_FORMAT_R8G8B8A8_UNORM: return data[index * 4 + channel] / 255.0f;
    default: return 0.0f;
  }
}

uint32_t texelBytes(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R16_SFLOAT: return 2;
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_R8G8B8A8_UNORM: return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_SNORM: return 8;
    default: return 16;
  }
}

} // namespace

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
  rhi::Sampler nearest;
  rhi::Buffer constants;
  graph::TransientPool transients;
  rhi::CommandList commands;
  rhi::TimestampPool timers;
  // Temporal state of the denoisers: the surface (disocclusion tests), shadow means, SVGF colour
  // and moments of the reflections.
  History surfaceHistory, shadowHistory, specularColorHistory, specularMomentsHistory;
  uint32_t frameIndex = 0;

  Impl(rhi::Context& c, const scene::Scene& s, GpuScene g)
      : ctx(c), scene(s), gpu(std::move(g)), pipelines(Pipelines::create(c, gpu.bindless->layout())),
        nearest(c, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE),
        constants(c, sizeof(gpu::FrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, rhi::MemoryUsage::Upload,
                  "frame-constants"),
        commands(c), timers(c, 32) {}

  uint32_t shadowLights() const { return std::min(gpu.lightCount, gpu::kMaxShadowLights); }

  void writeConstants(const RenderSettings& s, const scene::Camera& cam) {
    gpu::FrameConstants fc{};
    const float aspect = float(s.width) / float(s.height);
    glm::mat4 view = glm::lookAt(cam.position, cam.target, cam.up);
    // Reversed Z (near → 1, far → 0): swapping the planes in a [0,1]-depth projection does it.
    glm::mat4 proj = glm::perspective(cam.yFov, aspect, cam.zFar, cam.zNear);
    proj[1][1] *= -1.0f;  // Vulkan clip space: y points down
    fc.clipFromWorld = proj * view;
    fc.worldFromClip = glm::inverse(fc.clipFromWorld);
    fc.cameraPosition = glm::vec4(cam.position, 1.0f);
    fc.ambient = glm::vec4(scene.ambient, 0.0f);
    fc.size = {s.width, s.height};
    fc.frameIndex = frameIndex;
    fc.seed = s.seed;
    fc.lightCount = gpu.lightCount;
    fc.shadowLightCount = shadowLights();
    fc.exposure = std::exp2(s.exposureEv);
    fc.geometries = gpu.geometries.address();
    fc.instances = gpu.instances.address();
    fc.materials = gpu.materials.address();
    fc.lights = gpu.lights.address();
    const scene::Environment& env = scene.environment;
    fc.environmentKind = gpu.environment.kind;
    fc.environment = glm::vec4(glm::vec3(env.intensity), env.rotation);
    fc.environmentSlot = gpu.environment.slot;
    fc.skyZenith = env.zenith;
    fc.skyHorizon = env.horizon;
    fc.skyGround = env.ground;
    for (int k = 0; k < 9; ++k) fc.irradianceSh[k] = glm::vec4(gpu.environment.irradianceSh[k], 0.0f);
    fc.sceneFlags = gpu.anyAlphaTested ? gpu::kSceneAlphaTested : 0u;
    std::memcpy(constants.mapped(), &fc, sizeof(fc));
  }

  void ensureHistory(const RenderSettings& s) {
    const VkExtent2D size{s.width, s.height};
    surfaceHistory.ensure(ctx, surfaceDesc(size), "surface-history");
    shadowHistory.ensure(ctx, shadowHistoryDesc(size, shadowLights()), "shadow-history");
    specularColorHistory.ensure(ctx, svgfColorHistoryDesc(size), "specular-history");
    specularMomentsHistory.ensure(ctx, svgfMomentsHistoryDesc(size), "specular-moments");
  }

  // Times one G-buffer producer alone: a warm-up frame, then a measured one.
  double timeProducer(const RenderSettings& s, Primary p) {
    double ms = 0;
    for (int run = 0; run < 2; ++run) {
      graph::RenderGraph graph(&ctx, &transients);
      FrameInputs in{pipelines, gpu, constants, nearest, {s.width, s.height}, gpu.bindless->set()};
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

  Result<RenderOutput> render(const RenderSettings& s) {
    if (s.cameraPath && scene.cameraPath.empty())
      return makeError(ExitCode::BadArguments, "--camera-path: scene '{}' has no camera path", scene.name);
    const scene::Camera* cam = &scene.cameras.front();
    if (!s.camera.empty()) {
      auto it = std::find_if(scene.cameras.begin(), scene.cameras.end(),
                             [&](const scene::Camera& c) { return c.name == s.camera; });
      if (it == scene.cameras.end()) return makeError(ExitCode::BadArguments, "the scene has no camera named '{}'", s.camera);
      cam = &*it;
    }
    RenderOutput out;
    frameIndex = 0;
    writeConstants(s, *cam);
    out.primaryUsed = s.primary;
    if (s.primary == Primary::Auto) {
      // On the H100 the raster G-buffer costs many times the traced one; elsewhere raster is cheap.
      out.rasterGBufferMs = timeProducer(s, Primary::Raster);
      out.tracedGBufferMs = timeProducer(s, Primary::Traced);
      out.primaryUsed = out.tracedGBufferMs >= 0 && out.tracedGBufferMs < out.rasterGBufferMs ? Primary::Traced
                                                                                            : Primary::Raster;
      log::info("primary: auto chose {} (raster G-buffer {:.3f} ms, traced {:.3f} ms)", primaryName(out.primaryUsed),
                out.rasterGBufferMs, out.tracedGBufferMs);
    }

    ensureHistory(s);
    const size_t pixels = size_t(s.width) * s.height;
    rhi::Buffer ldrReadback(ctx, pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "ldr-readback");
    rhi::Buffer hdrReadback(ctx, pixels * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT, rhi::MemoryUsage::Readback, "hdr-readback");
    graph::ResourceState ldrState, hdrState;
    struct AovReadback {
      std::string name;
      VkFormat format;
      uint32_t layer;
      rhi::Buffer buffer;
    };
    std::vector<AovReadback> aovReadback;
    std::deque<graph::ResourceState> aovStates;  // stable addresses for the graph
    for (const std::string& name : s.aovs)
      if (std::find(aovNames().begin(), aovNames().end(), name) == aovNames().end())
        return makeError(ExitCode::BadArguments, "unknown AOV '{}'", name);
    std::map<std::string, std::vector<double>> passTimes;
    std::vector<std::string> passOrder;

    for (uint32_t f = 0; f < s.frames; ++f) {
      frameIndex = f;
      const scene::Camera frameCamera = s.cameraPath ? cameraOnPath(*cam, s, f) : *cam;
      writeConstants(s, frameCamera);
      const bool last = f + 1 == s.frames;
      graph::RenderGraph graph(&ctx, &transients);
      FrameInputs in{pipelines, gpu, constants, nearest, {s.width, s.height}, gpu.bindless->set()};

      GBuffer gb = out.primaryUsed == Primary::Traced ? traceGBuffer(graph, in) : rasterGBuffer(graph, in);
      // Every run starts without history (a camera cut does too); a camera path moves every frame.
      const TemporalState temporal{s.cameraPath, f == 0 || !surfaceHistory.valid};
      const DenoiseInputs dn{pipelines.denoise, nearest.handle(), in.size};
      const SurfacePair surface{
          writeSurface(graph, dn, gb.depth, gb.normals, gb.id, surfaceHistory.next(graph, "surface", f),
                       frameCamera.zNear, frameCamera.zFar),
          surfaceHistory.previous(graph, "surface", f)};
      // Interim: no motion vectors in the G-buffer yet (static scenes); gb.motion replaces this.
      const graph::ImageHandle motion = zeroMotion(graph, in.size);

      graph::ImageHandle raw = traceShadows(graph, in, gb, shadowLights());
      const ShadowDenoised shadows =
          denoiseShadows(graph, dn, surface, motion, raw,
                         {shadowHistory.previous(graph, "shadow-history", f), shadowHistory.next(graph, "shadow-history", f)},
                         temporal);
      graph::ImageHandle visibility = shadows.denoised;
      graph::ImageHandle specularRaw = traceSpecular(graph, in, gb);
      const RadianceDenoised reflections = denoiseRadiance(
          graph, dn, "reflection", surface, motion, gb.material, specularRaw,
          {specularColorHistory.previous(graph, "specular-history", f), specularColorHistory.next(graph, "specular-history", f)},
          {specularMomentsHistory.previous(graph, "specular-moments", f),
           specularMomentsHistory.next(graph, "specular-moments", f)},
          temporal);
      graph::ImageHandle specular = reflections.denoised;
      graph::ImageHandle hdr = shadeLighting(graph, in, gb, visibility, specular);
      graph::ImageHandle ldr = tonemap(graph, in, hdr, std::exp2(s.exposureEv), s.seed);
      if (last) {
        readback(graph, ldr, graph.importBuffer("ldr-readback", &ldrReadback, &ldrState));
        readback(graph, hdr, graph.importBuffer("hdr-readback", &hdrReadback, &hdrState));
        // "denoised" stages are the temporal accumulation until the denoisers exist.
        // Stage → (image, layer); the visibility arrays hold one layer per shadowed light.
        std::map<std::string, std::pair<graph::ImageHandle, uint32_t>> stages = {
            {"depth", {gb.depth, 0}},       {"normal", {gb.normals, 0}},          {"albedo", {gb.albedo, 0}},
            {"material", {gb.material, 0}}, {"emissive", {gb.emissive, 0}},       {"shadow-raw", {raw, 0}},
            {"shadow-denoised", {visibility, 0}}, {"reflection-raw", {specularRaw, 0}},
            {"reflection-denoised", {specular, 0}}};
        for (uint32_t i = 0; i < shadowLights(); ++i) {
          stages["shadow" + std::to_string(i) + "-raw"] = {raw, i};
          stages["shadow" + std::to_string(i) + "-denoised"] = {visibility, i};
        }
        for (const std::string& name : s.aovs) {
          auto it = stages.find(name);
          if (it == stages.end()) {  // a light the scene does not have
            log::info("AOV '{}' skipped: the scene has {} shadowed light(s)", name, shadowLights());
            continue;
          }
          const rhi::ImageDesc& d = graph.imageDesc(it->second.first);
          aovReadback.push_back({name, d.format, it->second.second,
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
      ctx.wait(commands.submit());
      for (History* h : {&surfaceHistory, &shadowHistory, &specularColorHistory, &specularMomentsHistory}) h->valid = true;
      for (auto& t : timers.read()) {
        if (t.name == "readback" || t.name == "host-visible") continue;
        if (!passTimes.count(t.name)) passOrder.push_back(t.name);
        passTimes[t.name].push_back(t.ms);
      }
      ctx.collectGarbage();
      if (s.progress) s.progress(f + 1, s.frames);
    }

    out.scene = {gpu.triangleCount, gpu.sphereCount, gpu.accelStats.builtBytes, gpu.accelStats.compactedBytes,
                 gpu.accelStats.tlasBytes, gpu.uploadMs, gpu.accelBuildMs, 0, 0};
    const rhi::MemoryStats mem = ctx.memory().stats();
    out.scene.deviceBytesUsed = mem.usedBytes;
    out.scene.deviceBytesReserved = mem.reservedBytes;
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

    for (const std::string& name : passOrder) {
      std::vector<double> v = passTimes[name];
      std::sort(v.begin(), v.end());
      PassStats ps{name, v[v.size() / 2], v.front(), v[std::min(v.size() - 1, size_t(std::ceil(0.95 * v.size())) - 1)],
                   uint32_t(v.size())};
      out.frameMedianMs += ps.medianMs;
      out.passes.push_back(ps);
    }
    return out;
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

Result<RenderOutput> Renderer::render(const RenderSettings& settings) { return impl_->render(settings); }

} // namespace rayster::render
