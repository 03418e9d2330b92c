#pragma once
// `rayster render --frames-out A:B[:STEP] -o shot_####.png`: one image per frame of the animation
// and camera path (docs/sequences.md). Every output frame is rendered by a run of its own that
// starts from fresh histories and pre-rolls the frames before it, so its pixels are the same
// whichever chunk of the range a process renders; images are written on worker threads.
#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "app/frame_range.h"
#include "app/progress.h"
#include "core/error.h"
#include "render/renderer.h"

namespace rayster::app {

struct RenderOptions;

// The run of output frame `frame` with `settings.frames` frames: hybrid and raster runs end on
// it (the frames before it are the pre-roll its histories accumulate over, from fresh), the path
// tracer's samples all see it.
render::RenderSettings outputFrameSettings(const render::RenderSettings& settings, int64_t frame);

struct SequenceResult {
  uint64_t written = 0, skipped = 0;
  // Wall time of the whole range; of the render calls (the render thread); of encoding and writing
  // (the worker threads, summed); and the render thread's waits for a full queue or the last writes.
  double wallSeconds = 0, renderSeconds = 0, encodeSeconds = 0, waitSeconds = 0;
  render::RenderOutput last;                        // the last rendered output frame's statistics (no images)
  render::Primary primary = render::Primary::Auto;  // what --primary auto chose for the range
  nlohmann::json json() const;                      // the "sequence" object of --json
};

// Renders and writes the range; the first failure (a failed write: ExitCode::OutputFailed) stops
// it, after the frames already queued are written. Frames before it stay on disk, whole. A
// SIGINT/SIGTERM (core/interrupt.h) drops the frame being rendered, writes the queued ones and
// ends with exit 130/143 (kExitInterrupted/kExitTerminated); a device loss or memory exhaustion (which ends the
// process in VK_CHECK) writes the queued frames first. o.failAt injects one (tests).
Result<SequenceResult> renderSequence(render::Renderer& renderer, const RenderOptions& o,
                                      const render::RenderSettings& settings, const FrameRange& range,
                                      ProgressStyle progress);

// The files of one rendered frame: `output` (.png tonemapped or .exr linear), `hdr` (.exr, if not
// empty) and the AOVs beside `output`; `output` is renamed into place last, so its presence means
// the frame is complete (--skip-existing).
Status writeFrameImages(const RenderOptions& o, const std::string& output, const std::string& hdr,
                        const render::RenderOutput& out);

}  // namespace rayster::app
