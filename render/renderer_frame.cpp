// One frame of a run (render/renderer_impl.h): camera and motion, then the G-buffer, the
// ray-traced effects and their denoisers (or the raster mode's passes), lighting, TAA, tonemap.
#include <algorithm>
#include <cmath>

#include "render/deform.h"
#include "render/jitter.h"
#include "render/passes/cull.h"
#include "render/renderer_impl.h"
#include "render/settings_table.h"
#include "shaders/shared/exposure.h"

namespace rayster::render {

// Passes used only here, declared next to their one caller.
graph::ImageHandle traceSkyVisibility(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb);
graph::ImageHandle drawProbeView(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                 graph::ImageHandle hdr, const ProbeLookup& probes);
// Probe trace, classification and atlas updates; then the G-buffer's lookup (gi-probe-sample: the
// irradiance image it returns, and lookup.specularIrradiance).
void traceProbeIrradiance(graph::RenderGraph& graph, const FrameInputs& in, const ProbeFrame& frame,
                          ProbeLookup& lookup);
graph::ImageHandle sampleProbeIrradiance(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                         ProbeLookup& lookup);

namespace {

// A camera that jumps between two frames starts a new shot: its history would ghost the old view.
// Real motion at any sensible frame rate stays far below these.
constexpr float kCutMoveFraction = 0.25f;  // of the distance to the target (the scene's scale)
constexpr float kCutAngleDegrees = 15.0f;  // turn of the view direction

bool isCameraCut(const scene::Camera& before, const scene::Camera& now) {
  const glm::vec3 dirBefore = before.target - before.position, dirNow = now.target - now.position;
  const float distance = glm::length(dirBefore);
  if (glm::length(now.position - before.position) > kCutMoveFraction * distance) return true;
  const float cosAngle = glm::dot(dirBefore, dirNow) / (distance * glm::length(dirNow));
  return cosAngle < std::cos(glm::radians(kCutAngleDegrees)) || now.yFov != before.yFov;
}

bool sameView(const scene::Camera& a, const scene::Camera& b) {
  return a.position == b.position && a.target == b.target && a.up == b.up && a.yFov == b.yFov;
}

}  // namespace

FrameStats Renderer::Impl::renderFrame(const FrameControl& control) {
  Run& r = *run;
  const RenderSettings& s = r.settings;
  RenderOutput& out = r.out;
  const uint32_t f = control.meter ? 0u : r.frame++;  // a metering frame is the shot's first, again
  const bool rasterMode = s.mode == Mode::Raster;
  FrameStats stats;
  const Clock::time_point frameStart = Clock::now();
  frameIndex = f;
  for (const RenderSettings::Move& m : s.moves)  // before the constants: the first edit may move the table
    if (m.frame == f) {
      const uint32_t i = uint32_t(findInstance(m.instance));
      glm::mat4 w = motion.get(scene, i);
      w[3] = glm::vec4(m.position, 1.0f);
      motion.set(ctx, gpu, i, w);
    }
  // The pose of this frame first: a camera on an animated node follows it.
  const uint32_t shown = uint32_t(std::max<int64_t>(0, s.frameOffset + f));  // of the animation and path
  const InstanceMotion::Update posed =
      motion.update(gpu, r.animated, s.time + (s.animate ? float(shown) / s.pathFps : 0.0f), f == 0);
  const bool moved0 = posed.moved;
  const scene::Camera& base = motion.camera(scene, *r.cam, r.animated);
  const scene::Camera camera = control.camera ? *control.camera : s.cameraPath ? cameraOnPath(base, s, shown) : base;
  // A cut (the first frame of a run, a jump of the camera, or a listed frame) restarts every history.
  const bool cut = f == 0 || control.cut || isCameraCut(r.prevCamera, camera) ||
                   std::find(s.cuts.begin(), s.cuts.end(), f) != s.cuts.end();
  const bool viewHeld = !cut && sameView(r.prevCamera, camera);
  histories.beginFrame(f, cut);
  exposure.beginFrame(cut);
  const glm::vec2 jitter = s.taa ? jitterNdc(f, s.width, s.height) : glm::vec2(0.0f);
  r.prevClipFromWorld = writeConstants(s, camera, jitter, cut ? nullptr : &r.prevClipFromWorld);
  r.prevCamera = camera;
  graph::RenderGraph graph(&ctx, &transients, &histories);
  const graph::AccelHandle tlas = beginFrameGraph(graph, gpu, constants, nearest);
  const FrameInputs in{pipelines, gpu, constants, nearest, linear, {s.width, s.height}, tlas};
  bool moving = s.cameraPath || control.moving || posed.lightsMoved;
  {
    bool moved = moved0;
    // Skinned and morphed meshes take the pose on the first frame and, while animated, every frame
    // (render/deform.h); playing, they move even where no instance transform does.
    const bool deform = gpu.deformers && (r.animated || f == 0);
    if (deform)
      deformMeshes(graph, in, scene, motion.pose(scene, r.animated), f == 0,
                   !rasterMode && gpu.tlas.handle() != VK_NULL_HANDLE);
    moved = moved || (deform && r.animated && s.animate && f > 0);
    // Motion vectors of this frame still show last frame's motion after the pose stops.
    moving = moving || moved || r.movedBefore;
    r.movedBefore = moved;
    r.stillFrames = viewHeld && !moving ? r.stillFrames + 1 : 0;
    const bool tlasStale = motion.takeTlasRefit(!rasterMode) || deform;  // a deformed BLAS moves the TLAS's boxes
    if (tlasStale && !rasterMode)                                        // the raster mode refits when it leaves
      updateTlas(graph, in, gpu.tlas.prepare(gpu.tlasInstances));
  }

  // Without clear coats and sheens the G-buffer has no layers target: lighting reads zeros.
  const graph::ImageHandle zeroLayers = gpu.layeredGBuffer ? graph::ImageHandle{} : neutral.layers(graph);
  const GBuffer gb =
      out.primaryUsed == Primary::Traced ? traceGBuffer(graph, in, zeroLayers) : rasterGBuffer(graph, in, zeroLayers);
  FrameImages images;
  if (rasterMode) {
    // Shadow maps look from the lights where they are now (lights on animated nodes move).
    const RasterFrameOutput o =
        raster.record(graph, in, gb, motion.pose(scene, r.animated), camera,
                      {shadowLights(), s.reflections, neutral.white(graph), neutral.black(graph)});
    images = {o.visibility, o.visibility, o.specular, o.specular, o.ao, o.ao, o.indirect, o.indirect, o.hdr};
  } else {
    images = recordHybrid(graph, in, gb, camera, moving);
  }
  graph::ImageHandle hdr = images.hdr;
  if (s.taa) {
    const graph::RenderGraph::History taa =
        graph.history("taa-history",
                      {kTaaHistoryFormat, s.width, s.height, 1,
                       VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
                      kRadianceImage);
    hdr = resolveTaa(graph, in, {hdr, gb.depth, taa.previous, taa.next, gb.motion, taa.frames, r.stillFrames});
  }
  images.hdr = hdr;
  const bool meter = exposure.automatic() && (control.meter || r.adaptExposure);
  if (meter)
    meterExposure(graph, in, hdr, gb, exposure.exposure(),
                  graph.importBuffer("exposure-histogram", &exposureHistogram, &exposureHistogramState),
                  graph.importBuffer("exposure-readback", &exposureReadback, &exposureReadbackState));
  graph::ImageHandle ldr = tonemap(graph, in, hdr, {s.tonemap, s.seed});
  if (control.present)
    copyToOutput(graph, ldr);
  else if (!control.readback)
    // Every frame's image counts as consumed, as a presented one would be: otherwise the graph
    // culls tonemapping in all frames but the last (whose readback uses it) and its timings miss them.
    graph.addPass(
        "output",
        [&](graph::PassBuilder& b) {
          b.read(ldr, graph::Use::TransferSrc);
          b.sideEffect();
          b.kind(graph::PassKind::Utility);
        },
        [](graph::PassContext&) {});
  if (f == 0 && !s.aovs.empty()) r.failure = checkAovs(graph, gb, images);
  if (control.readback) addReadbacks(graph, gb, images, ldr);

  VkCommandBuffer cmd = commands.begin();
  timers.reset(cmd);
  graph.execute(cmd, &timers);
  const uint64_t submitted = commands.submit();
  const double cpuMs = msSince(frameStart);
  ctx.wait(submitted);
  const double wallMs = msSince(frameStart);
  histories.endFrame();
  if (meter) {
    const auto* bins = static_cast<const uint32_t*>(exposureReadback.mapped());
    const float dt = control.dtSeconds > 0.0f ? control.dtSeconds : 1.0f / s.pathFps;
    r.meterDistance =
        exposure.meter({bins, gpu::kExposureHistograms * gpu::kExposureBins}, dt, /*snap*/ control.meter || cut);
  }
  // never an empty sample; metering frames are not the run's
  const bool measured = (f >= s.warmupFrames || s.warmupFrames >= s.frames) && !control.meter;
  double gpuMs = 0;
  for (auto& t : graph.readTimings(timers)) {
    if (!t.info.reported()) continue;
    if (t.info.kind == graph::PassKind::Frame) gpuMs += t.ms;  // raw-rate twins are not part of the frame
    if (measured) {
      if (!r.passTimes.count(t.name)) r.passOrder.push_back(t.name);
      r.passTimes[t.name].push_back(t.ms);
      r.passInfo[t.name] = t.info;
    }
    stats.passes.push_back(std::move(t));
  }
  stats.gpuMs = gpuMs;
  if (measured) {
    out.frameGpuMs.push_back(gpuMs);
    out.frameCpuMs.push_back(cpuMs);
    out.frameWallMs.push_back(wallMs);
  }
  ctx.collectGarbage();
  stats.primaryUsed = out.primaryUsed;
  out.visibleDraws = stats.visibleDraws = out.primaryUsed == Primary::Raster ? int64_t(visibleDraws(gpu)) : -1;
  out.totalDraws = uint32_t(gpu.draws.size());
  stats.camera = camera;
  stats.exposure = exposure.exposure();
  return stats;
}

FrameImages Renderer::Impl::recordHybrid(graph::RenderGraph& graph, const FrameInputs& in, const GBuffer& gb,
                                         const scene::Camera& camera, bool moving) {
  const RenderSettings& s = run->settings;
  // Off means gone: an effect that is switched off or has nothing to do (no shadowed light, no
  // surface smooth or transmissive enough to trace) records no pass and no image; lighting reads
  // the neutral value in its place (render/neutral_images.h).
  const uint32_t lights = shadowLights();
  const bool ao = aoInShadowImage(s), indirect = indirectOn(s), specularPass = specularOn(s);
  const bool sky = passSwitchOn(s, "sky-visibility");
  const bool probes = indirect && passSettingText(s, "gi") == "probes";  // probes in the one-bounce path's place
  const bool denoise = s.denoise && (lights > 0 || ao || specularPass || indirect || manyLights || sky);
  FrameImages o;
  const graph::ImageHandle white = neutral.white(graph), black = neutral.black(graph);
  o.shadowRaw = o.shadow = o.aoRaw = o.ao = white;
  o.specularRaw = o.specular = o.indirectRaw = o.indirect = black;

  // The surface (depth, normal, id) the denoisers test disocclusions against, and the quarter-rate
  // indirect fill its neighbours' weights: last frame's is a history, kept only while denoising.
  // Every run starts without history, and so does a camera cut (the history store resets them all),
  // and a history that is new (an effect just switched on, a resize); while the camera or an
  // object moves, the denoisers keep short histories.
  const DenoiseInputs dn{pipelines, nearest.handle(), in.size};
  const graph::ImageHandle motion = gb.motion;
  graph::RenderGraph::History surfaceHistory;
  SurfacePair surface;
  if (denoise || indirectQuarter(s)) {
    if (denoise)
      surfaceHistory = graph.history("surface", surfaceDesc(in.size));
    else
      surfaceHistory.next = graph.createImage("surface", surfaceDesc(in.size));
    surface = {writeSurface(graph, dn, gb.depth, gb.normals, gb.id, gb.material, surfaceHistory.next, camera.zNear,
                            camera.zFar),
               surfaceHistory.previous};
  }
  auto temporalFor = [&](uint32_t frames) {
    return TemporalState{moving, surfaceHistory.frames == 0 || frames == 0, exposure.ratio()};
  };
  // An SVGF signal's colour and moments histories ("<name>-history", "<name>-moments").
  auto svgf = [&](const std::string& name, graph::ImageHandle raw) {
    if (!denoise) return raw;
    const graph::RenderGraph::History color =
        graph.history(name + "-history", svgfColorHistoryDesc(in.size), kRadianceImage);
    const graph::RenderGraph::History moments = graph.history(name + "-moments", svgfMomentsHistoryDesc(in.size));
    return denoiseRadiance(graph, dn, name == "specular" ? "reflection" : name, surface, motion, raw,
                           {color.previous, color.next}, {moments.previous, moments.next},
                           temporalFor(std::min(color.frames, moments.frames)))
        .denoised;
  };

  // With shadowed lights and AO, rt-ao fills the shadow image's last layer, and one shadow-denoiser
  // run (one guide fetch per tap, one history) takes the lights and AO; AO alone has an image of
  // its own. Many-light mode shadows no layer: its direct light is a pass of its own.
  if (lights > 0) {
    o.shadowRaw = traceShadows(graph, in, gb, lights, ao ? 1u : 0u);
    if (ao) o.aoRaw = traceAo(graph, in, gb, o.shadowRaw, aoHalfRate(s));
  } else if (ao) {
    o.aoRaw = traceAo(graph, in, gb, {}, aoHalfRate(s));
  }
  o.aoLayer = ao ? lights : 0u;
  o.shadow = o.shadowRaw;
  o.ao = o.aoRaw;
  if (denoise && (lights > 0 || ao)) {
    const graph::ImageHandle raw = lights > 0 ? o.shadowRaw : o.aoRaw;
    const graph::RenderGraph::History history =
        graph.history("shadow-history", shadowHistoryDesc(in.size, lights + (ao ? 1u : 0u)));
    const graph::ImageHandle denoised =
        denoiseShadows(graph, dn, surface, motion, raw, {history.previous, history.next}, temporalFor(history.frames))
            .denoised;
    if (lights > 0) o.shadow = denoised;
    if (ao) o.ao = denoised;
  }
  if (sky) {  // an output only: kept by a utility pass, so it is computed (and timed) every frame
    graph::ImageHandle v = traceSkyVisibility(graph, in, gb);
    if (denoise) {
      const auto h = graph.history("sky-visibility-history", shadowHistoryDesc(in.size, 1));
      v = denoiseShadows(graph, dn, surface, motion, v, {h.previous, h.next}, temporalFor(h.frames), "sky-visibility")
              .denoised;
    }
    graph.addPass(
        "sky-visibility-output",
        [&](graph::PassBuilder& b) {
          b.read(v, graph::Use::TransferSrc);
          b.sideEffect();
          b.kind(graph::PassKind::Utility);
        },
        [](graph::PassContext&) {});
  }
  if (s.rawRays) {
    traceRawPrimary(graph, in);
    traceRawShadows(graph, in, gb, lights);
    o.rawTwins = traceRawTwins(graph, in, gb, {ao, manyLights, indirect && !probes, specularPass}, indirectQuarter(s),
                               aoHalfRate(s), shadowRaysPerHit());
  }
  // Probes first: the reflection bounce loop lights its hits from them too.
  // With --gi path they run too: the one-bounce rays' hits take their irradiance (every later
  // bounce); the G-buffer's lookup (gi-probe-sample) is then unused, and the graph culls it.
  ProbeLookup probeLookup;
  if (indirect)
    traceProbeIrradiance(
        graph, in,
        {frameIndex, s.seed, exposure.ratio(), moving, camera.position, probeCascadesSetting(s), &probeCascades},
        probeLookup);
  if (specularPass) {
    specularQueue.ctx = &ctx;
    o.specularRaw = traceSpecular(graph, in, gb, specularBounces(s), shadowRaysPerHit(), specularFillOn(s), probeLookup,
                                  useSpecularQueue(ctx, s, in.size) ? &specularQueue : nullptr);
    o.specular = svgf("specular", o.specularRaw);
  }
  const graph::ImageHandle direct = manyLights ? svgf("direct", traceDirect(graph, in, gb)) : black;
  if (indirect && !probes) {
    o.indirectRaw = traceIndirect(graph, in, gb, surface.current, indirectQuarter(s), probeLookup);
    o.indirect = svgf("indirect", o.indirectRaw);
  }
  if (indirect && probes) o.indirectRaw = o.indirect = sampleProbeIrradiance(graph, in, gb, probeLookup);
  o.hdr = shadeLighting(
      graph, in, gb,
      {o.shadow, o.specular, o.ao, o.indirect, direct, probes ? probeLookup.specularIrradiance : graph::ImageHandle{}});
  if (probes && passSwitchOn(s, "probe-view")) o.hdr = drawProbeView(graph, in, gb, o.hdr, probeLookup);
  return o;
}

}  // namespace rayster::render
