#pragma once
// SIGINT and SIGTERM for batch renders (docs/sequences.md, "Signals"): a scheduler that stops a
// job (Slurm sends SIGTERM, then SIGKILL after its KillWait) must find every file either complete
// or absent. The handler only sets an atomic flag, which the render loop reads between frames and
// between a frame's accumulated frames; a second signal exits at once, removing the temporary
// files of writes in progress first. Outside an InterruptScope a signal exits at once too: before
// rendering starts there is nothing to finish.
#include <filesystem>

#include "core/error.h"

namespace rayster {

// Installs the SIGINT/SIGTERM handlers (idempotent).
void installInterruptHandlers();

// While one lives, the first signal only sets the flag (interruptSignal) for the caller to stop at
// its next check; without one, a signal ends the process as a second signal does.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
};

// The signal received (SIGINT, SIGTERM), 0 if none.
int interruptSignal();
// A render a signal stopped exits with 128 + the signal, as a shell reports a process the signal
// ended (and as schedulers read it): 130 for SIGINT, 143 for SIGTERM. Beside ExitCode's list.
inline constexpr ExitCode kExitInterrupted = ExitCode(130), kExitTerminated = ExitCode(143);
ExitCode interruptExitCode(int signal);
// The error a run stopped by `signal` ends with: "interrupted by SIGTERM: <what>" and its code.
Error interruptedError(int signal, const std::string& what);

// A temporary file being written: a second signal (or a fatal exit that calls
// removeTempFilesInProgress) unlinks it. Paths longer than the slots hold, or more files at once
// than there are slots, are not tracked (a rename or remove still cleans them up normally).
class TempFileInProgress {
 public:
  explicit TempFileInProgress(const std::filesystem::path& path);
  ~TempFileInProgress();
  TempFileInProgress(const TempFileInProgress&) = delete;
  TempFileInProgress& operator=(const TempFileInProgress&) = delete;

 private:
  int slot_ = -1;
};

// Unlinks every tracked temporary file; async-signal-safe. Returns how many it unlinked.
int removeTempFilesInProgress();

// Tests only: clears the received signal.
void resetInterruptForTesting();

}  // namespace rayster
