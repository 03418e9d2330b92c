#pragma once
// Progress of scene loading on stderr (DESIGN.md §5: long work shows progress). A phase says
// nothing unless it runs past a threshold (0.5 s; RAYSTER_PROGRESS_MS overrides it, 0 prints
// every phase), so small scenes load silently; a long one prints
//   rayster: loading sponza.gltf: 35/70 textures decoded
// at most every threshold, and a last line with its time. Lines go through the log (stderr), one
// write each, so job logs see them; nothing is redrawn in place. Every phase's time is also logged
// at debug level (`rayster -v`), which is how BENCHMARKS.md's per-phase figures are read.
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace rayster {

// The threshold, in milliseconds.
double loadProgressThresholdMs();

class LoadProgress {
 public:
  // what: "loading sponza.gltf"; unit: "textures decoded" (total > 0) or a phase name such as
  // "BLAS build" (total 0: only the closing line, when slow).
  LoadProgress(std::string what, std::string unit, size_t total = 0);
  ~LoadProgress() { finish(); }
  LoadProgress(const LoadProgress&) = delete;
  LoadProgress& operator=(const LoadProgress&) = delete;

  // n more items done; safe from any thread.
  void advance(size_t n = 1);
  // Ends the phase (also done by the destructor): the closing line when it ran long, and the debug
  // line. Returns its milliseconds.
  double finish();

 private:
  using Clock = std::chrono::steady_clock;
  std::string what_, unit_;
  size_t total_ = 0, done_ = 0;
  Clock::time_point start_, lastPrint_;
  bool printed_ = false, finished_ = false;
  double ms_ = 0;
  std::mutex mutex_;
};

}  // namespace rayster
