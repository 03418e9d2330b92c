// `rayster render` (a sequence of frames: app/sequence.h).
#include "app/render_command.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "app/build_info.h"
#include "app/device_option.h"
#include "app/image_writer.h"
#include "app/progress.h"
#include "app/sequence.h"
#include "app/settings_cli.h"
#include "core/image_io.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "rhi/context.h"
#include "rhi/fault_injection.h"
#include "scene/loader.h"

namespace rayster::app {
namespace {

int fail(const Error& e) {
  std::fprintf(stderr, "rayster: error: %s\n", e.message.c_str());
  return int(e.code);
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

Status checkOutputPath(const std::string& path, const char* what, std::initializer_list<const char*> exts) {
  std::string ext = lower(std::filesystem::path(path).extension().string());
  for (const char* e : exts)
    if (ext == e) return okStatus();
  return makeError(ExitCode::BadArguments, "{} '{}' must end in {}", what, path, *exts.begin());
}

// A CPU device (lavapipe) traces a few million rays per second: the GPU defaults (1280x720, 16
// frames, every effect on) take about 9 minutes for the README's command on a 2-core machine;
// these took 35 s there while two other builds ran (README's quick start).
constexpr uint32_t kCpuWidth = 640, kCpuHeight = 360, kCpuFrames = 4;

// On a CPU device, the size and frame count the user did not give become the CPU defaults, said in
// one line. Explicit flags always win; other devices keep the defaults as they are.
void applyCpuDefaults(const rhi::DeviceInfo& device, const RenderOptions& o, render::RenderSettings& s) {
  if (device.type != VK_PHYSICAL_DEVICE_TYPE_CPU || (o.sizeGiven && o.framesGiven)) return;
  std::string what, flags;
  if (!o.sizeGiven) {
    s.width = kCpuWidth;
    s.height = kCpuHeight;
    what = fmt::format("{}x{}", s.width, s.height);
    flags = "--size";
  }
  if (!o.framesGiven) {
    s.frames = kCpuFrames;
    what += fmt::format("{}{} frames", what.empty() ? "" : ", ", s.frames);
    flags += flags.empty() ? "--frames" : "/--frames";
  }
  log::info("CPU device {}: rendering {} by default ({} to override)", device.name, what, flags);
}

nlohmann::json timingsJson(const rhi::Context& ctx, const RenderOptions& o, const render::RenderSettings& s,
                           const render::RenderOutput& out) {
  nlohmann::json j;
  j["device"] = ctx.info().name;
  j["driver"] = ctx.info().driverInfo;
  j["commit"] = buildCommit();
  j["scene"] = o.scene;
  j["width"] = s.width;
  j["height"] = s.height;
  j["frames"] = s.frames;
  j["seed"] = s.seed;
  j["mode"] = render::modeName(out.modeUsed);
  j["primary"] = render::primaryName(out.primaryUsed);
  j["exposure"] = {{"mode", s.exposureMode == render::ExposureMode::Auto ? "auto"
                            : s.exposureMode == render::ExposureMode::Ev ? "ev"
                                                                         : "ev100"},
                   {"multiplier", out.exposure},
                   {"ev100", out.ev100}};
  j["tonemap"] = render::tonemapperName(s.tonemap);
  j["taa"] = s.taa;
  j["culling"] = s.culling;
  j["indirect_rate"] = render::indirectRateName(s.indirectRate);
  j["render_settings"] = settingsJson(s);  // every setting of the table (render/settings_table.h)
  if (out.visibleDraws >= 0) j["draws"] = {{"visible", out.visibleDraws}, {"total", out.totalDraws}};
  j["max_depth"] = s.maxDepth;
  if (out.rasterGBufferMs >= 0)
    j["auto"] = {{"raster_gbuffer_ms", out.rasterGBufferMs}, {"traced_gbuffer_ms", out.tracedGBufferMs}};
  j["frame_gpu_ms_median"] = out.frameMedianMs;
  const auto& st = out.scene;
  j["scene_stats"] = {{"triangles", st.triangles},
                      {"spheres", st.spheres},
                      {"blas_bytes", st.blasBytes},
                      {"blas_compacted_bytes", st.blasCompactedBytes},
                      {"tlas_bytes", st.tlasBytes},
                      {"upload_ms", st.uploadMs},
                      {"accel_build_ms", st.accelBuildMs},
                      {"device_bytes_used", st.deviceBytesUsed},
                      {"device_bytes_reserved", st.deviceBytesReserved},
                      {"frame_bytes", st.frameBytes},
                      {"transient_bytes", st.transientBytes},
                      {"transient_unaliased_bytes", st.transientUnaliasedBytes},
                      {"history_bytes", st.historyBytes}};
  for (const auto& p : out.passes)
    j["passes"].push_back({{"name", p.name},
                           {"median_ms", p.medianMs},
                           {"min_ms", p.minMs},
                           {"p95_ms", p.p95Ms},
                           {"frames", p.samples},
                           {"rays", p.info.rays}});
  return j;
}

void printTimings(const rhi::Context& ctx, const RenderOptions& o, const render::RenderSettings& settings,
                  const render::RenderOutput& out) {
  std::printf("%-20s %10s %10s %10s\n", "pass", "median ms", "min ms", "p95 ms");
  for (const auto& p : out.passes)
    std::printf("%-20s %10.3f %10.3f %10.3f\n", p.name.c_str(), p.medianMs, p.minMs, p.p95Ms);
  if (out.visibleDraws >= 0)
    std::printf("%-20s %10lld of %u (last frame, culling %s)\n", "visible draws", (long long)out.visibleDraws,
                out.totalDraws, o.settings.culling ? "on" : "off");
  std::printf("%-20s %10.3f   (%s, %s, primary %s, %ux%u)\n", "frame (GPU)", out.frameMedianMs, ctx.info().name.c_str(),
              render::modeName(out.modeUsed), render::primaryName(out.primaryUsed), settings.width, settings.height);
  const auto& st = out.scene;
  std::printf("%-20s %10.1f MiB (transients %.1f, %.1f unaliased; histories/outputs %.1f) of %.1f MiB in use\n",
              "frame resources", double(st.frameBytes) / (1 << 20), double(st.transientBytes) / (1 << 20),
              double(st.transientUnaliasedBytes) / (1 << 20), double(st.historyBytes) / (1 << 20),
              double(st.deviceBytesUsed) / (1 << 20));
}

int validationCode(const rhi::Context& ctx) {
  if (!ctx.validationEnabled() || ctx.validationErrors() == 0) return 0;
  std::fprintf(stderr, "rayster: error: %u Vulkan validation error(s)\n", ctx.validationErrors());
  return int(ExitCode::Failure);
}

}  // namespace

// The PNG of an AOV is for looking at: normals map to colours, stored sRGB albedo is decoded so the
// PNG encoder does not encode it twice, and alpha is opaque (stages keep other data there, such
// as SVGF's variance). The EXR keeps the raw values.
ImageF aovForDisplay(const std::string& name, ImageF img) {
  for (size_t i = 0; i < img.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) {
      float& v = img.rgba[i + c];
      if (name == "normal") v = v * 0.5f + 0.5f;
      if (name == "albedo") v = srgbToLinear(v);
    }
    img.rgba[i + 3] = 1.0f;
  }
  return img;
}

Result<std::vector<std::string>> parseAovs(const std::string& list) {
  std::vector<std::string> names;
  if (list.empty()) return names;
  if (list == "all") return render::aovNames();
  size_t start = 0;
  while (start <= list.size()) {
    size_t comma = list.find(',', start);
    std::string name = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    // Any image of the frame's graph is an AOV (checked against the first frame's images): here
    // only the spelling.
    const bool spelled = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == ':' || c == '.';
    });
    if (!spelled) return makeError(ExitCode::BadArguments, "--aov: '{}' is not an image name", name);
    names.push_back(name);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return names;
}

Status parseMoves(const std::vector<std::string>& args, std::vector<render::RenderSettings::Move>& moves) {
  for (const std::string& a : args) {
    const size_t colon = a.rfind(':'), at = a.rfind('@');
    render::RenderSettings::Move m;
    unsigned frame = 0;
    char extra = 0;
    if (colon == std::string::npos || at == std::string::npos || at < colon || colon == 0 ||
        std::sscanf(a.c_str() + colon + 1, "%f,%f,%f@%u%c", &m.position.x, &m.position.y, &m.position.z, &frame,
                    &extra) != 4)
      return makeError(ExitCode::BadArguments, "--move-instance must be NAME:X,Y,Z@FRAME, got '{}'", a);
    m.instance = a.substr(0, colon);
    m.frame = frame;
    moves.push_back(std::move(m));
  }
  return okStatus();
}

namespace {

// What --frames-out needs of the other options, checked before any GPU work.
Result<std::optional<FrameRange>> checkSequence(const RenderOptions& o) {
  if (o.framesOut.empty()) {
    if (o.skipExisting) return makeError(ExitCode::BadArguments, "--skip-existing needs --frames-out");
    return std::optional<FrameRange>{};
  }
  auto range = parseFrameRange(o.framesOut);
  if (!range) return range.error();
  if (range->count() > 1) {
    if (!hasFrameNumber(o.output))
      return makeError(ExitCode::BadArguments,
                       "--frames-out {} writes {} frames: -o '{}' needs # for the frame number (e.g. shot_####.png)",
                       o.framesOut, range->count(), o.output);
    if (!o.hdrOutput.empty() && !hasFrameNumber(o.hdrOutput))
      return makeError(ExitCode::BadArguments, "--frames-out {}: --hdr '{}' needs # for the frame number", o.framesOut,
                       o.hdrOutput);
  }
  // Scripted edits outlast a run (Renderer::setInstanceTransform): a chunk that starts after the
  // edit's frame would never make it, so its frames would differ from the whole range's.
  if (!o.settings.moves.empty())
    return makeError(ExitCode::BadArguments, "--move-instance cannot be combined with --frames-out");
  return std::optional<FrameRange>{*range};
}

// --json of a sequence: the last rendered frame's timings and settings, and the range's summary.
Status writeSequenceJson(const rhi::Context& ctx, const RenderOptions& o, const render::RenderSettings& s,
                         const FrameRange& range, const SequenceResult& r) {
  nlohmann::json j = timingsJson(ctx, o, s, r.last);
  j["primary"] = render::primaryName(r.primary);
  nlohmann::json seq = r.json();
  seq["first"] = range.first;
  seq["last"] = range.last;
  seq["step"] = range.step;
  seq["frames_in_range"] = range.count();
  seq["output"] = o.output;
  seq["accumulated_frames"] = s.frames;
  j["sequence"] = seq;
  return writeFileAtomically(o.jsonOutput, j.dump(2) + "\n");
}

Status renderRange(const rhi::Context& ctx, render::Renderer& renderer, const RenderOptions& o,
                   const render::RenderSettings& settings, const FrameRange& range, ProgressStyle progress) {
  auto seq = renderSequence(renderer, o, settings, range, progress);
  if (!seq) return seq.error();
  if (o.printTimings) printTimings(ctx, o, settings, seq->last);
  if (o.memoryReport) std::fputs(seq->last.scene.frameMemoryReport.c_str(), stdout);
  if (!o.jsonOutput.empty())
    if (Status s = writeSequenceJson(ctx, o, settings, range, *seq); !s) return s;
  log::info(
      "wrote {} of {} frames of {} ({} skipped; {}x{}, {} frames each; {:.1f} s, {:.2f} frames/s; encoding "
      "{:.2f} s on {} worker threads, the render thread waited {:.2f} s for them)",
      seq->written, range.count(), o.output, seq->skipped, settings.width, settings.height, settings.frames,
      seq->wallSeconds, seq->wallSeconds > 0 ? double(seq->written) / seq->wallSeconds : 0.0, seq->encodeSeconds,
      writerThreads(), seq->waitSeconds);
  return okStatus();
}

// A signal while the image accumulates drops it (nothing is written); one after it is rendered
// lets it be written, whole, before the run ends with the signal's code.
Status renderStill(const rhi::Context& ctx, render::Renderer& renderer, const RenderOptions& o,
                   render::RenderSettings settings, ProgressStyle progress) {
  const auto t0 = std::chrono::steady_clock::now();
  if (settings.frames > 1) settings.progress = frameProgress(progress);
  settings.stop = []() -> std::optional<Error> {
    if (const int signal = interruptSignal()) return interruptedError(signal, "");
    return std::nullopt;
  };
  if (interruptSignal()) return interruptedError(interruptSignal(), o.output + " not rendered");
  if (o.failAt && o.failAt->frame == 0) rhi::failNextSubmit(o.failAt->result);
  auto out = renderer.render(settings);
  if (!out && interruptSignal() && out.error().code == interruptExitCode(interruptSignal()))
    return interruptedError(interruptSignal(), fmt::format("{} not written (stopped while accumulating)", o.output));
  if (!out) return out.error();
  const double wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (Status s = writeFrameImages(o, o.output, o.hdrOutput, *out); !s) return s;
  if (o.printTimings) printTimings(ctx, o, settings, *out);
  if (o.memoryReport) std::fputs(out->scene.frameMemoryReport.c_str(), stdout);
  if (!o.jsonOutput.empty())
    if (Status s = writeFileAtomically(o.jsonOutput, timingsJson(ctx, o, settings, *out).dump(2) + "\n"); !s) return s;
  log::info("wrote {} ({}x{}, {} frames, primary {}, {:.0f} ms)", o.output, settings.width, settings.height,
            settings.frames, render::primaryName(out->primaryUsed), wallMs);
  if (const int signal = interruptSignal()) return interruptedError(signal, o.output + " written before stopping");
  return okStatus();
}

}  // namespace

int renderCommand(const RenderOptions& options) {
  // Until rendering starts a signal ends the process at once (there is nothing to finish);
  // while it renders, the loop stops at its next check (core/interrupt.h).
  installInterruptHandlers();
  RenderOptions o = options;
  auto failAt = injectedRenderFailure();
  if (!failAt) return fail(failAt.error());
  o.failAt = *failAt;
  // Check everything about the outputs before any GPU work, so bad arguments fail fast.
  if (auto s = checkOutputPath(o.output, "output", {".png", ".exr"}); !s) return fail(s.error());
  if (!o.hdrOutput.empty())
    if (auto s = checkOutputPath(o.hdrOutput, "--hdr", {".exr"}); !s) return fail(s.error());
  if (!o.jsonOutput.empty())
    if (auto s = checkOutputPath(o.jsonOutput, "--json", {".json"}); !s) return fail(s.error());
  auto sequence = checkSequence(o);
  if (!sequence) return fail(sequence.error());
  auto progress = parseProgress(o.progress, isatty(STDERR_FILENO));
  if (!progress) return fail(progress.error());

  auto aovs = parseAovs(o.aovs);
  if (!aovs) return fail(aovs.error());
  auto loadStart = std::chrono::steady_clock::now();
  auto scene = scene::loadScene(o.scene);
  if (!scene) return fail(scene.error());
  if (!o.variant.empty())
    if (Status s = scene::selectVariant(*scene, o.variant); !s) return fail(s.error());
  log::info("loaded {} ({} triangles, {} instances) in {:.0f} ms", o.scene, scene->triangleCount(),
            scene->instances.size(),
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - loadStart).count());
  auto ctx = rhi::Context::create({o.validation, o.requireRt, deviceSelector(o.device), o.debugLabels});
  if (!ctx) return fail(ctx.error());
  render::RenderSettings settings = o.settings;
  // Without ray-tracing pipelines every mode falls back to rasterisation, said in one line.
  if (settings.mode != render::Mode::Raster && !(*ctx)->caps().rayTracing()) {
    log::info("device {} has no ray-tracing pipelines: rendering with --mode raster", (*ctx)->info().name);
    settings.mode = render::Mode::Raster;
  }
  applyCpuDefaults((*ctx)->info(), o, settings);
  log::debug("device: {} ({}), driver {}", (*ctx)->info().name, (*ctx)->info().typeName(), (*ctx)->info().driverInfo);

  {
    const auto uploadStart = std::chrono::steady_clock::now();
    auto renderer = render::Renderer::create(**ctx, *scene);
    if (!renderer) return fail(renderer.error());
    // Load time = the "loaded" line above + this (BENCHMARKS.md, "Loading big scenes").
    log::debug("scene on the device in {:.0f} ms",
               std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - uploadStart).count());
    settings.aovs = *aovs;
    const InterruptScope interruptible;
    Status done = *sequence ? renderRange(**ctx, **renderer, o, settings, **sequence, *progress)
                            : renderStill(**ctx, **renderer, o, settings, *progress);
    if (!done) return fail(done.error());
  }
  return validationCode(**ctx);  // after the renderer is gone: its teardown is validated too
}

}  // namespace rayster::app
