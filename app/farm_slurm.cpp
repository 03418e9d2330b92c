#include "app/farm_slurm.h"

#include <fmt/format.h>

namespace rayster::app {

uint64_t SlurmJob::tasks() const {
  if (isBench()) return shards;
  return chunk == 0 ? 0 : (range.count() + chunk - 1) / chunk;
}

std::string shellQuote(const std::string& word) {
  std::string q = "'";
  for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string printfPattern(const std::string& pattern, int& runs) {
  const size_t slash = pattern.rfind('/');
  const size_t nameStart = slash == std::string::npos ? 0 : slash + 1;
  std::string out;
  runs = 0;
  for (size_t i = 0; i < pattern.size();) {
    if (pattern[i] == '%') {
      out += "%%";
      ++i;
    } else if (pattern[i] == '#' && i >= nameStart) {
      size_t run = 0;
      while (i + run < pattern.size() && pattern[i + run] == '#') ++run;
      out += fmt::format("%0{}d", run);
      ++runs;
      i += run;
    } else {
      out += pattern[i++];
    }
  }
  return out;
}

std::string benchShardPath(const std::string& json, uint32_t shard, uint32_t shards) {
  const std::string stem = json.size() > 5 && json.ends_with(".json") ? json.substr(0, json.size() - 5) : json;
  return fmt::format("{}.shard-{}-of-{}.json", stem, shard, shards);
}

namespace {

// The sbatch header: the array, requeue, one GPU, the log, the user's options.
std::string header(const SlurmJob& job, const std::string& what) {
  const uint64_t first = job.isBench() ? 1 : 0;
  std::string s = "#!/usr/bin/env bash\n";
  s += fmt::format("# Written by `rayster farm slurm` (docs/farm.md): {}.\n", what);
  s += "# Submit with `sbatch THIS_FILE`; each array task is resumable and requeues itself on a\n";
  s += "# retryable rayster exit code (4, 6, 7, 8 or a signal), at most max_retries times.\n";
  s += fmt::format("#SBATCH --job-name={}\n", job.name);
  s += fmt::format("#SBATCH --array={}-{}\n", first, first + job.tasks() - 1);
  s += "#SBATCH --ntasks=1\n";
  s += "#SBATCH --requeue\n";           // node failure and preemption: Slurm requeues the task itself
  s += "#SBATCH --open-mode=append\n";  // a requeued run appends to its task's log
  s += fmt::format("#SBATCH --output={}/{}_%A_%a.log\n", job.logDir, job.name);
  if (!job.gres.empty()) s += fmt::format("#SBATCH --gres={}\n", job.gres);
  for (const std::string& o : job.sbatchOptions) s += fmt::format("#SBATCH {}\n", o);
  return s;
}

// The device of the task: the user's --device if any; else the GPU Slurm allocated, by the UUID
// nvidia-smi gives it (Vulkan ignores CUDA_VISIBLE_DEVICES; an NVIDIA device's Vulkan deviceUUID is
// its CUDA UUID); else rayster's own choice.
std::string deviceSelection(const std::vector<std::string>& args) {
  for (const std::string& a : args)
    if (a == "--device" || a.starts_with("--device=")) return "device=()  # --device given: every task uses it\n";
  return R"SH(device=()
gpu=${SLURM_JOB_GPUS:-${CUDA_VISIBLE_DEVICES:-}}
gpu=${gpu%%,*}
if [ -n "$gpu" ] && command -v nvidia-smi >/dev/null 2>&1; then
  # Under device cgroups nvidia-smi lists only the allocated GPU; otherwise pick it by index.
  uuids=$(nvidia-smi --query-gpu=uuid --format=csv,noheader 2>/dev/null)
  if [ "$(printf '%s\n' "$uuids" | grep -c .)" = 1 ]; then uuid=$uuids
  else uuid=$(nvidia-smi --query-gpu=uuid --format=csv,noheader -i "$gpu" 2>/dev/null); fi
  uuid=${uuid#GPU-}
  if [ -n "$uuid" ]; then device=(--device "$uuid"); fi
fi
)SH";
}

// The end of every task: exit codes to Slurm (docs/farm.md, "Exit codes").
std::string retry(const SlurmJob& job) {
  std::string codes;
  for (int c : kRetryableExitCodes) codes += (codes.empty() ? "" : "|") + std::to_string(c);
  return fmt::format(R"SH(code=$?
case $code in
  0) echo "rayster-farm: task $task done"; exit 0 ;;
  {0}) kind=retryable ;;
  *) if [ "$code" -gt 128 ]; then kind=retryable; else kind=permanent; fi ;;
esac
restarts=${{SLURM_RESTART_COUNT:-0}}
if [ "$kind" = retryable ] && [ "$restarts" -lt {1} ] && [ -n "${{SLURM_JOB_ID:-}}" ]; then
  echo "rayster-farm: task $task: rayster exited with code $code (retryable): requeueing, restart $((restarts + 1)) of {1}"
  scontrol requeue "$SLURM_JOB_ID" && exit "$code"
  echo "rayster-farm: task $task: scontrol requeue failed"
fi
echo "rayster-farm: task $task: rayster exited with code $code ($kind, after $restarts restart(s))"
exit "$code"
)SH",
                     codes, job.maxRetries);
}

std::string renderBody(const SlurmJob& job) {
  std::string s;
  s += fmt::format("first={} last={} step={} chunk={}\n", job.range.first, job.range.last, job.range.step, job.chunk);
  s += R"SH(task=${SLURM_ARRAY_TASK_ID:?not an array task: submit this file with sbatch}
a=$((first + task * chunk * step))
b=$((a + (chunk - 1) * step))
if [ "$b" -gt "$last" ]; then b=$last; fi
if [ "$a" -gt "$last" ]; then echo "rayster-farm: task $task is past the range"; exit 0; fi
)SH";
  s += deviceSelection(job.renderArgs);
  // A run killed while writing leaves its temporary file (name.tmp-PID) beside the frame; only this
  // task's own frames are cleaned, since other tasks write into the same folder.
  s += "for ((f = a; f <= b; f += step)); do\n";
  for (const std::string& pattern : {job.output, job.hdr}) {
    if (pattern.empty()) continue;
    int runs = 0;
    const std::string format = printfPattern(pattern, runs);
    std::string args;
    for (int i = 0; i < runs; ++i) args += " \"$f\"";
    s += fmt::format("  rm -f -- \"$(printf {}{})\".tmp-*\n", shellQuote(format), args);
  }
  s += "done\n";
  s += "echo \"rayster-farm: task $task: frames $a:$b:$step on $(hostname) (restart ${SLURM_RESTART_COUNT:-0}, "
       "job ${SLURM_JOB_ID:-none}) ${device[*]}\"\n";
  std::string cmd = "\"$rayster\" render " + shellQuote(job.scene);
  for (const std::string& a : job.renderArgs) cmd += " " + shellQuote(a);
  cmd += " \"${device[@]}\" --frames-out \"$a:$b:$step\" -o " + shellQuote(job.output);
  if (!job.hdr.empty()) cmd += " --hdr " + shellQuote(job.hdr);
  cmd += " --skip-existing --progress lines\n";
  return s + cmd;
}

std::string benchBody(const SlurmJob& job) {
  std::string s = fmt::format("shards={}\n", job.shards);
  s += "task=${SLURM_ARRAY_TASK_ID:?not an array task: submit this file with sbatch}\n";
  s += deviceSelection({});
  // benchShardPath(json, $task, $shards), spelled in bash.
  const std::string stem = benchShardPath(job.benchJson, 0, 0);
  s += fmt::format("out={}.shard-$task-of-$shards.json\n", shellQuote(stem.substr(0, stem.rfind(".shard-0-of-0"))));
  s += "echo \"rayster-farm: task $task: shard $task/$shards on $(hostname) (restart ${SLURM_RESTART_COUNT:-0}, "
       "job ${SLURM_JOB_ID:-none}) ${device[*]}\"\n";
  s += fmt::format("\"$rayster\" bench --plan {} --shard \"$task/$shards\" \"${{device[@]}}\" --json \"$out\"\n",
                   shellQuote(job.benchPlan));
  return s;
}

}  // namespace

Result<std::string> slurmScript(const SlurmJob& job) {
  if (job.tasks() == 0) return makeError(ExitCode::BadArguments, "farm slurm: the job has no tasks");
  const std::string what = job.isBench()
                               ? fmt::format("bench plan {} in {} shards", job.benchPlan, job.shards)
                               : fmt::format("{} frames {}:{}:{} in {} chunks of {}", job.scene, job.range.first,
                                             job.range.last, job.range.step, job.tasks(), job.chunk);
  std::string s = header(job, what);
  s += "set -u\n";
  s += fmt::format("rayster={}\n", shellQuote(job.rayster));
  s += fmt::format("cd {} || exit 3\n", shellQuote(job.workDir));
  s += job.isBench() ? benchBody(job) : renderBody(job);
  s += retry(job);
  return s;
}

}  // namespace rayster::app
