#include "app/sequence.h"

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/image_writer.h"
#include "app/render_command.h"
#include "core/image_io.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "rhi/fault_injection.h"
#include "rhi/vk_check.h"

namespace rayster::app {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

bool isExr(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".exr";
}

bool exists(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

// A device loss or memory exhaustion ends the process from VK_CHECK (rhi/vk_check.h). Before it
// does, the frames already rendered are written and the writes in progress renamed, so every frame
// on disk is whole and a rerun with --skip-existing renders only the rest. The process then exits
// with the failure's code; the frame that failed is never written.
std::atomic<ImageWriter*> gWriterToFinish{nullptr};
void finishWritesBeforeFatalExit(const char*) {
  if (ImageWriter* writer = gWriterToFinish.exchange(nullptr)) (void)writer->finish();
  removeTempFilesInProgress();
}

class FinishWritesOnFatalExit {
 public:
  explicit FinishWritesOnFatalExit(ImageWriter& writer) {
    gWriterToFinish = &writer;
    rhi::setFatalHook(finishWritesBeforeFatalExit);
  }
  ~FinishWritesOnFatalExit() {
    rhi::setFatalHook(nullptr);
    gWriterToFinish = nullptr;
  }
};

// Between the accumulated frames of an output frame: a SIGINT or SIGTERM drops the frame.
std::optional<Error> stopOnSignal() {
  if (const int signal = interruptSignal()) return interruptedError(signal, "");
  return std::nullopt;
}

}  // namespace

render::RenderSettings outputFrameSettings(const render::RenderSettings& settings, int64_t frame) {
  render::RenderSettings s = settings;
  const int64_t accumulated = std::max<int64_t>(1, settings.frames);
  s.frameOffset = settings.mode == render::Mode::PathTrace ? frame : frame - (accumulated - 1);
  return s;
}

Status writeFrameImages(const RenderOptions& o, const std::string& output, const std::string& hdr,
                        const render::RenderOutput& out) {
  const ExrPixels exr = o.exrFloat ? ExrPixels::Float : ExrPixels::Half;
  if (!hdr.empty())
    if (Status s = writeExr(hdr, out.hdr, exr); !s) return s;
  const std::filesystem::path outPath(output);
  for (const auto& [name, img] : out.aovs) {
    auto base = outPath.parent_path() / (outPath.stem().string() + "." + name);
    if (Status s = writeImage(base.string() + ".png", aovForDisplay(name, img)); !s) return s;
    if (Status s = writeExr(base.string() + ".exr", img, exr); !s) return s;
  }
  return isExr(output) ? writeExr(output, out.hdr, exr) : writePng(output, out.ldr);
}

nlohmann::json SequenceResult::json() const {
  const double rendered = double(written);
  return {{"frames_written", written},
          {"frames_skipped", skipped},
          {"wall_s", wallSeconds},
          {"frames_per_s", wallSeconds > 0 ? rendered / wallSeconds : 0.0},
          {"render_s", renderSeconds},
          {"encode_s", encodeSeconds},
          {"render_thread_wait_s", waitSeconds},
          {"primary", render::primaryName(primary)}};
}

Result<SequenceResult> renderSequence(render::Renderer& renderer, const RenderOptions& o,
                                      const render::RenderSettings& settings, const FrameRange& range,
                                      ProgressStyle progressStyle) {
  const Clock::time_point start = Clock::now();
  SequenceResult result;
  std::vector<int64_t> todo;
  for (uint64_t i = 0; i < range.count(); ++i) {
    const int64_t f = range.at(i);
    const bool done =
        o.skipExisting && exists(framePath(o.output, f)) && (o.hdrOutput.empty() || exists(framePath(o.hdrOutput, f)));
    if (done)
      ++result.skipped;
    else
      todo.push_back(f);
  }
  SequenceProgress progress(progressStyle, todo.size(), result.skipped);
  ImageWriter writer;
  const FinishWritesOnFatalExit finishOnFatalExit(writer);
  render::RenderSettings base = settings;
  Status failed = okStatus();
  std::optional<int64_t> dropped;  // the frame a signal stopped
  for (const int64_t f : todo) {
    if (auto e = writer.failure()) {
      failed = *e;
      break;
    }
    if (interruptSignal()) {
      dropped = f;
      break;
    }
    render::RenderSettings s = outputFrameSettings(base, f);
    s.progress = [&progress, f](uint32_t done, uint32_t total) { progress.accumulating(f, done, total); };
    s.stop = stopOnSignal;
    const Clock::time_point renderStart = Clock::now();
    renderer.restartHistories();  // nothing of the frames before carries over
    if (o.failAt && o.failAt->frame == f) rhi::failNextSubmit(o.failAt->result);
    auto out = renderer.render(s);
    result.renderSeconds += secondsSince(renderStart);
    if (!out && interruptSignal() && out.error().code == interruptExitCode(interruptSignal())) {
      dropped = f;
      break;
    }
    if (!out) {
      failed = out.error();
      break;
    }
    if (base.primary == render::Primary::Auto && base.mode != render::Mode::PathTrace) {
      // Timed once, on the first frame: every frame of the range then has the same G-buffer.
      base.primary = out->primaryUsed;
      log::info("--primary auto: {} for the whole range (give --primary for the same choice in every chunk)",
                render::primaryName(out->primaryUsed));
    }
    result.primary = out->primaryUsed;
    // The images go to a writer; the statistics stay for the summary.
    auto images = std::make_shared<render::RenderOutput>();
    images->ldr = std::move(out->ldr);
    images->hdr = std::move(out->hdr);
    images->aovs = std::move(out->aovs);
    result.last = std::move(*out);
    const std::string output = framePath(o.output, f);
    const std::string hdr = o.hdrOutput.empty() ? "" : framePath(o.hdrOutput, f);
    writer.push([&o, images, output, hdr] { return writeFrameImages(o, output, hdr, *images); });
    ++result.written;
    progress.written(f, output);
    // What bench/gpu-soak.sh samples (with -v): a leak across output frames shows here.
    log::debug("frame {}: device memory {} bytes in use, {} reserved", f, result.last.scene.deviceBytesUsed,
               result.last.scene.deviceBytesReserved);
  }
  // Also after a signal: the frames already rendered (at most the queue's) are written, and every
  // write in progress ends in its rename, so what a stopped run leaves is whole.
  Status finished = writer.finish();
  progress.finish();
  result.encodeSeconds = writer.encodeSeconds();
  result.waitSeconds = writer.waitSeconds();
  result.wallSeconds = secondsSince(start);
  if (!failed) return failed.error();
  if (!finished) return finished.error();
  if (const int signal = interruptSignal()) {
    const uint64_t done = result.written + result.skipped;
    return interruptedError(
        signal, dropped ? fmt::format("{} of {} frames of {} written, frame {} dropped (rerun with --skip-existing)",
                                      done, range.count(), o.output, *dropped)
                        : fmt::format("all {} frames of {} written", range.count(), o.output));
  }
  return result;
}

}  // namespace rayster::app
