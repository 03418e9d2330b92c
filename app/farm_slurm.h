#pragma once
// `rayster farm slurm`: the text of an sbatch job array (docs/farm.md). Each array task renders one
// chunk of a frame range (or runs one shard of a bench plan) with `--skip-existing`, on one GPU, and
// asks Slurm to requeue it when rayster stops for a reason worth retrying (kRetryableExitCodes).
// Rayster schedules nothing itself: the script is all it adds to Slurm.
#include <cstdint>
#include <string>
#include <vector>

#include "app/frame_range.h"
#include "core/error.h"

namespace rayster::app {

// Render exit codes a task retries on another run (core/error.h, `rayster --help`): no device (4),
// device lost (6), out of memory (7), output not written (8) can be the node's fault or passing.
// Every other code is permanent (bad arguments or input, a missing capability: a rerun fails the
// same way); a rayster killed by a signal (128 + N: the kernel's OOM killer, a kill by hand) is
// retried too.
inline constexpr int kRetryableExitCodes[] = {4, 6, 7, 8};
// How many times a task requeues itself before it gives up (SLURM_RESTART_COUNT counts them).
inline constexpr uint32_t kDefaultMaxRetries = 3;

struct SlurmJob {
  std::string rayster;         // absolute path of the binary every task runs
  std::string workDir;         // absolute: tasks run there, so relative paths in renderArgs mean what they did
  std::string name;            // --job-name
  std::string logDir;          // absolute: <logDir>/<name>_%A_%a.log, appended to by requeued runs
  std::string gres = "gpu:1";  // "" (from --gres none): no --gres line
  std::vector<std::string> sbatchOptions;  // more #SBATCH lines, each "--option=value" or "--flag"
  uint32_t maxRetries = kDefaultMaxRetries;

  // A render: the range in chunks of `chunk` output frames, one array task each (0-based ids).
  std::string scene;                    // absolute path, or builtin:NAME
  FrameRange range;                     // normalised: range.last is the last frame rendered
  uint64_t chunk = 1;                   // output frames per task
  std::string output, hdr;              // absolute patterns with # runs ("" hdr: none)
  std::vector<std::string> renderArgs;  // passed to every `rayster render` as given

  // A bench plan instead (benchPlan not empty): shard i of `shards` per task (1-based ids).
  std::string benchPlan;  // absolute path
  uint32_t shards = 0;
  std::string benchJson;  // absolute; shard i writes benchShardPath(benchJson, i, shards)

  bool isBench() const { return !benchPlan.empty(); }
  uint64_t tasks() const;  // array tasks: chunks of the range, or shards
};

// The sbatch script: bash, self-contained (absolute paths, every word single-quoted).
Result<std::string> slurmScript(const SlurmJob& job);

// Where shard i of n writes its results: bench.json -> bench.shard-3-of-8.json.
std::string benchShardPath(const std::string& json, uint32_t shard, uint32_t shards);

// A word as bash reads it back unchanged: 'it'\''s'.
std::string shellQuote(const std::string& word);

// The printf format of an output pattern: each # run of the file name becomes %0Nd (one
// argument each), every % is doubled; `runs` says how many arguments it takes.
std::string printfPattern(const std::string& pattern, int& runs);

}  // namespace rayster::app
