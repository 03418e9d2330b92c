#pragma once
// Frame progress of a long render on stderr (docs/architecture.md §8: long work shows progress).
#include <cstdint>
#include <functional>

namespace rayster::app {

// On a terminal the line is redrawn in place and erased at the end. Anywhere else (a pipe, a log
// file, a batch scheduler's output) it prints "rayster: frame K/N (P%), T s" lines: every tenth of
// the frames or kProgressInterval, whichever comes first, and at the last frame.
std::function<void(uint32_t done, uint32_t total)> frameProgress(bool terminal);

}  // namespace rayster::app
