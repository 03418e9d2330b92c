#pragma once
// `--frames-out A:B[:STEP]` and output names with `#` runs for the frame number (docs/sequences.md).
#include <cstdint>
#include <string>

#include "core/error.h"

namespace rayster::app {

struct FrameRange {
  int64_t first = 0, last = 0, step = 1;  // inclusive; frames first, first + step, ... <= last
  uint64_t count() const { return uint64_t((last - first) / step) + 1; }
  int64_t at(uint64_t i) const { return first + int64_t(i) * step; }
};

// The most frames one range may hold: past that a typo (a missing colon) is likelier than a shot.
inline constexpr int64_t kMaxFrameNumber = 9'999'999;

// "A:B" or "A:B:STEP" with 0 <= A <= B <= kMaxFrameNumber and STEP >= 1; anything else is
// ExitCode::BadArguments with a one-line cause.
Result<FrameRange> parseFrameRange(const std::string& text);

// Whether the file name (not the folders) of `path` holds a `#`.
bool hasFrameNumber(const std::string& path);

// Every run of `#` in the file name becomes the frame number, zero-padded to the run's length
// (longer numbers are written in full): shot_####.png, frame 12 -> shot_0012.png.
std::string framePath(const std::string& pattern, int64_t frame);

}  // namespace rayster::app
