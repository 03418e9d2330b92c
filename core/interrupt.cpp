#include "core/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstring>

namespace rayster {
namespace {

std::atomic<int> gSignal{0};
std::atomic<int> gScopes{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads these atomics");

// Two writer threads and the render thread each write one file at a time; the slack covers
// callers of core/image_io.h beyond the sequence writer.
constexpr int kTempSlots = 16;
constexpr size_t kTempPathBytes = 1024;
enum SlotState : int { kFree = 0, kFilling = 1, kTracked = 2 };
struct TempSlot {
  std::atomic<int> state{kFree};
  char path[kTempPathBytes] = {};
};
TempSlot gTempSlots[kTempSlots];

const char* signalName(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "a signal";
  }
}

// Only async-signal-safe calls: atomics, unlink, write, _exit.
void onSignal(int signal) {
  int none = 0;
  if (gScopes.load() > 0 && gSignal.compare_exchange_strong(none, signal)) return;  // the loop stops
  removeTempFilesInProgress();
  const char* line =
      signal == SIGINT ? "rayster: error: interrupted by SIGINT\n" : "rayster: error: interrupted by SIGTERM\n";
  const ssize_t ignored = ::write(STDERR_FILENO, line, std::strlen(line));
  (void)ignored;
  ::_exit(128 + signal);
}

}  // namespace

void installInterruptHandlers() {
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // the render and writer threads' system calls carry on
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

InterruptScope::InterruptScope() { gScopes.fetch_add(1); }
InterruptScope::~InterruptScope() { gScopes.fetch_sub(1); }

int interruptSignal() { return gSignal.load(); }

ExitCode interruptExitCode(int signal) { return ExitCode(128 + signal); }
static_assert(128 + SIGINT == int(kExitInterrupted) && 128 + SIGTERM == int(kExitTerminated));

Error interruptedError(int signal, const std::string& what) {
  return makeError(interruptExitCode(signal), "interrupted by {}: {}", signalName(signal), what);
}

TempFileInProgress::TempFileInProgress(const std::filesystem::path& path) {
  const std::string& text = path.native();
  if (text.size() >= kTempPathBytes) return;
  for (int i = 0; i < kTempSlots; ++i) {
    int expected = kFree;
    if (!gTempSlots[i].state.compare_exchange_strong(expected, kFilling)) continue;
    std::memcpy(gTempSlots[i].path, text.c_str(), text.size() + 1);
    gTempSlots[i].state.store(kTracked);
    slot_ = i;
    return;
  }
}

TempFileInProgress::~TempFileInProgress() {
  if (slot_ >= 0) gTempSlots[slot_].state.store(kFree);
}

int removeTempFilesInProgress() {
  int removed = 0;
  for (TempSlot& slot : gTempSlots)
    if (slot.state.load() == kTracked && ::unlink(slot.path) == 0) ++removed;
  return removed;
}

void resetInterruptForTesting() { gSignal.store(0); }

}  // namespace rayster
