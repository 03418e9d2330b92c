#include "app/progress.h"

#include <chrono>
#include <cstdio>
#include <memory>

#include "core/log.h"

namespace rayster::app {
namespace {

using Clock = std::chrono::steady_clock;

// Often enough that a slow CPU render visibly moves, rarely enough that a log stays readable.
constexpr std::chrono::seconds kProgressInterval{10};

struct LineProgress {
  Clock::time_point start = Clock::now();
  Clock::time_point last = start;
  uint32_t lastTenth = 0;
};

}  // namespace

std::function<void(uint32_t, uint32_t)> frameProgress(bool terminal) {
  if (terminal)
    return [](uint32_t done, uint32_t total) {
      std::fprintf(stderr, "\rrayster: frame %u/%u", done, total);
      if (done == total) std::fprintf(stderr, "\r\033[K");
    };
  auto state = std::make_shared<LineProgress>();
  return [state](uint32_t done, uint32_t total) {
    const Clock::time_point now = Clock::now();
    const uint32_t tenth = uint32_t(uint64_t(done) * 10 / total);
    if (done != total && tenth == state->lastTenth && now - state->last < kProgressInterval) return;
    state->last = now;
    state->lastTenth = tenth;
    log::info("frame {}/{} ({}%), {:.1f} s", done, total, uint64_t(done) * 100 / total,
              std::chrono::duration<double>(now - state->start).count());
  };
}

}  // namespace rayster::app
