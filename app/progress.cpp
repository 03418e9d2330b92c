#include "app/progress.h"

#include <cmath>
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "core/log.h"

namespace rayster::app {
namespace {

using Clock = std::chrono::steady_clock;

struct LineProgress {
  Clock::time_point start = Clock::now();
  Clock::time_point last = start;
  uint32_t lastTenth = 0;
};

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

constexpr int kBarWidth = 24;

std::string bar(double fraction) {
  const int filled = int(std::clamp(fraction, 0.0, 1.0) * kBarWidth);
  return "[" + std::string(size_t(filled), '#') + std::string(size_t(kBarWidth - filled), '-') + "]";
}

}  // namespace

Result<ProgressStyle> parseProgress(const std::string& word, bool terminal) {
  if (word == "auto") return terminal ? ProgressStyle::Bar : ProgressStyle::Lines;
  if (word == "bar") return ProgressStyle::Bar;
  if (word == "lines") return ProgressStyle::Lines;
  if (word == "off") return ProgressStyle::Off;
  return makeError(ExitCode::BadArguments, "--progress must be auto, bar, lines or off, got '{}'", word);
}

std::string formatDuration(double seconds) {
  const long s = long(std::lround(std::max(seconds, 0.0)));
  if (s < 60) return fmt::format("{} s", s);
  if (s < 3600) return fmt::format("{}:{:02}", s / 60, s % 60);
  return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
}

std::function<void(uint32_t, uint32_t)> frameProgress(ProgressStyle style) {
  if (style == ProgressStyle::Off) return {};
  if (style == ProgressStyle::Bar) {
    const Clock::time_point start = Clock::now();
    return [start](uint32_t done, uint32_t total) {
      const double elapsed = secondsSince(start), rate = elapsed > 0 ? done / elapsed : 0.0;
      std::fprintf(stderr, "\rrayster: %s frame %u/%u, %.1f frames/s, ETA %s\033[K", bar(double(done) / total).c_str(),
                   done, total, rate, rate > 0 ? formatDuration((total - done) / rate).c_str() : "?");
      if (done == total) std::fprintf(stderr, "\r\033[K");
      std::fflush(stderr);
    };
  }
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

SequenceProgress::SequenceProgress(ProgressStyle style, uint64_t toRender, uint64_t skipped)
    : style_(style), total_(toRender), skipped_(skipped) {
  if (style_ == ProgressStyle::Lines && skipped_ > 0)
    log::info("{} output frame{} already written (--skip-existing), {} to render", skipped_, skipped_ == 1 ? "" : "s",
              total_);
}

double SequenceProgress::rate() const {
  const double elapsed = secondsSince(start_);
  return elapsed > 0 ? done_ / elapsed : 0.0;
}

void SequenceProgress::drawBar(int64_t frame, double partial) {
  const double done = double(done_) + partial, elapsed = secondsSince(start_);
  const double r = elapsed > 0 ? done / elapsed : 0.0;
  std::fprintf(stderr, "\rrayster: %s %llu/%llu frames, %.2f frames/s, ETA %s (frame %lld)\033[K",
               bar(total_ ? done / double(total_) : 1.0).c_str(), (unsigned long long)done_, (unsigned long long)total_,
               r, r > 0 ? formatDuration((double(total_) - done) / r).c_str() : "?", (long long)frame);
  std::fflush(stderr);
  drawn_ = true;
}

void SequenceProgress::accumulating(int64_t frame, uint32_t done, uint32_t total) {
  if (style_ == ProgressStyle::Bar) return drawBar(frame, total ? double(done) / total : 0.0);
  if (style_ != ProgressStyle::Lines || Clock::now() - lastLine_ < kProgressInterval) return;
  lastLine_ = Clock::now();
  log::info("frame {}: accumulated {}/{} ({} of {} output frames done, {})", frame, done, total, done_, total_,
            formatDuration(secondsSince(start_)));
}

void SequenceProgress::written(int64_t frame, const std::string& path) {
  ++done_;
  if (style_ == ProgressStyle::Bar) return drawBar(frame, 0.0);
  if (style_ != ProgressStyle::Lines) return;
  if (done_ != total_ && done_ != 1 && Clock::now() - lastLine_ < kSequenceLineInterval) return;
  lastLine_ = Clock::now();
  const double r = rate();
  log::info("frame {} -> {} ({}/{}, {}%), {:.2f} frames/s, ETA {}", frame, path, done_, total_,
            total_ ? done_ * 100 / total_ : 100, r, r > 0 ? formatDuration((total_ - done_) / r) : "?");
}

void SequenceProgress::finish() {
  if (drawn_) std::fprintf(stderr, "\r\033[K");
  drawn_ = false;
}

}  // namespace rayster::app
