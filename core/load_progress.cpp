#include "core/load_progress.h"

#include <cstdlib>

#include "core/log.h"

namespace rayster {

double loadProgressThresholdMs() {
  if (const char* env = std::getenv("RAYSTER_PROGRESS_MS")) {
    char* end = nullptr;
    const double ms = std::strtod(env, &end);
    if (end != env && ms >= 0) return ms;
  }
  return 500.0;  // a pause a user notices; below it a line per phase would only be noise
}

LoadProgress::LoadProgress(std::string what, std::string unit, size_t total)
    : what_(std::move(what)), unit_(std::move(unit)), total_(total), start_(Clock::now()), lastPrint_(start_) {}

void LoadProgress::advance(size_t n) {
  std::lock_guard lock(mutex_);
  done_ += n;
  if (total_ == 0 || done_ >= total_) return;  // the closing line reports the end
  const Clock::time_point now = Clock::now();
  const double threshold = loadProgressThresholdMs();
  if (std::chrono::duration<double, std::milli>(now - lastPrint_).count() < threshold) return;
  lastPrint_ = now;
  printed_ = true;
  log::info("{}: {}/{} {}", what_, done_, total_, unit_);
}

double LoadProgress::finish() {
  std::lock_guard lock(mutex_);
  if (finished_) return ms_;
  finished_ = true;
  ms_ = std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  if (printed_ || ms_ >= loadProgressThresholdMs()) {
    if (total_ > 0)
      log::info("{}: {}/{} {} in {:.2f} s", what_, done_, total_, unit_, ms_ / 1000.0);
    else
      log::info("{}: {} took {:.2f} s", what_, unit_, ms_ / 1000.0);
  } else {
    if (total_ > 0)
      log::debug("{}: {}/{} {} in {:.1f} ms", what_, done_, total_, unit_, ms_);
    else
      log::debug("{}: {} in {:.1f} ms", what_, unit_, ms_);
  }
  return ms_;
}

}  // namespace rayster
