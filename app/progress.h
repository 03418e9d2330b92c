#pragma once
// Progress of long work on stderr (docs/architecture.md §8: long work shows progress), as a bar on
// a terminal and as log lines anywhere else (a pipe, a log file, a batch scheduler's output).
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "core/error.h"

namespace rayster::app {

enum class ProgressStyle { Bar, Lines, Off };

// --progress auto|bar|lines|off; auto is a bar when stderr is a terminal and lines elsewhere.
Result<ProgressStyle> parseProgress(const std::string& word, bool terminal);

// Often enough that a slow CPU render visibly moves, rarely enough that a log stays readable.
inline constexpr std::chrono::seconds kProgressInterval{10};
// A sequence's lines: one per output frame, but no closer together than this (a GPU writes tens of
// frames a second; a log needs a line every few seconds, not every frame).
inline constexpr std::chrono::seconds kSequenceLineInterval{2};

// The accumulation of one image. Bar: "frame K/N" with rate and ETA redrawn in place and erased
// at the end. Lines: "rayster: frame K/N (P%), T s" every tenth of the frames or
// kProgressInterval, whichever comes first, and at the last frame. Off: nothing.
std::function<void(uint32_t done, uint32_t total)> frameProgress(ProgressStyle style);

// A sequence of output frames: a bar with the output frames done, the rate (frames/s), the ETA and
// the frame being accumulated; or one line per written frame (at most one per
// kSequenceLineInterval, and every kProgressInterval within a slow frame).
class SequenceProgress {
 public:
  using Clock = std::chrono::steady_clock;
  SequenceProgress(ProgressStyle style, uint64_t toRender, uint64_t skipped);
  void accumulating(int64_t frame, uint32_t done, uint32_t total);  // within output frame `frame`
  void written(int64_t frame, const std::string& path);             // an output frame is done
  void finish();                                                    // erases the bar

 private:
  void drawBar(int64_t frame, double partial);
  double rate() const;  // output frames per second so far

  ProgressStyle style_;
  uint64_t total_, skipped_, done_ = 0;
  Clock::time_point start_ = Clock::now(), lastLine_ = start_;
  bool drawn_ = false;
};

// "42 s", "3:07", "1:02:03".
std::string formatDuration(double seconds);

}  // namespace rayster::app
