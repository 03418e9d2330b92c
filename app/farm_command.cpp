#include "app/farm_command.h"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "core/log.h"

namespace rayster::app {
namespace {

namespace fs = std::filesystem;

int fail(const Error& e) {
  std::fprintf(stderr, "rayster: error: %s\n", e.message.c_str());
  return int(e.code);
}

std::string absolute(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

// The options a task sets itself: given after `--` they would fight the script's own.
Status checkPassThrough(const std::vector<std::string>& args) {
  static const char* kOwned[] = {"--frames-out", "-o", "--output", "--hdr", "--skip-existing", "--progress", "--json"};
  for (const std::string& a : args)
    for (const char* owned : kOwned)
      if (a == owned || a.starts_with(std::string(owned) + "="))
        return makeError(ExitCode::BadArguments,
                         "farm slurm: {} after -- is set by each task (give --frames-out, -o and --hdr to farm slurm; "
                         "--json would be one file for every task)",
                         owned);
  return okStatus();
}

// sbatch options become #SBATCH lines: one option each, nothing that could end the line.
Status checkSbatchOption(const std::string& o) {
  if (o.size() < 2 || o[0] != '-')
    return makeError(ExitCode::BadArguments, "farm slurm: --sbatch '{}' is not an sbatch option (e.g. --exclusive)", o);
  for (char c : o)
    if (c == '\n' || c == '\r' || c == '\0')
      return makeError(ExitCode::BadArguments, "farm slurm: --sbatch '{}' holds a line break", o);
  return okStatus();
}

// rayster-<file name without extension, # runs and trailing separators>: shot_####.png -> rayster-shot.
std::string defaultName(const std::string& path) {
  std::string stem = fs::path(path).stem().string(), name;
  for (char c : stem)
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.') name += c;
  while (!name.empty() && (name.back() == '_' || name.back() == '-' || name.back() == '.')) name.pop_back();
  return name.empty() ? "rayster" : "rayster-" + name;
}

Status renderJob(const FarmOptions& o, SlurmJob& job) {
  if (o.scene.empty()) return makeError(ExitCode::BadArguments, "farm slurm: give a SCENE (or --bench-plan)");
  if (o.scene[0] == '-')
    return makeError(ExitCode::BadArguments, "farm slurm: '{}' is not a scene: give SCENE before --", o.scene);
  if (o.framesOut.empty()) return makeError(ExitCode::BadArguments, "farm slurm: SCENE needs --frames-out A:B[:STEP]");
  if (o.chunk == 0)
    return makeError(ExitCode::BadArguments, "farm slurm: --chunk N (output frames per task) is missing");
  if (o.output.empty() || !hasFrameNumber(o.output))
    return makeError(ExitCode::BadArguments, "farm slurm: -o needs # for the frame number, e.g. out/shot_####.png");
  if (!o.hdr.empty() && !hasFrameNumber(o.hdr))
    return makeError(ExitCode::BadArguments, "farm slurm: --hdr '{}' needs # for the frame number", o.hdr);
  auto range = parseFrameRange(o.framesOut);
  if (!range) return range.error();
  if (Status s = checkPassThrough(o.renderArgs); !s) return s;
  if (o.checkRenderArgs)
    if (Status s = o.checkRenderArgs(o.renderArgs); !s)
      return makeError(ExitCode::BadArguments, "farm slurm: render options after --: {}", s.error().message);
  const bool builtin = o.scene.rfind("builtin:", 0) == 0;
  if (!builtin && !fs::is_regular_file(o.scene))
    return makeError(ExitCode::BadInput, "farm slurm: scene '{}' is not a file", o.scene);
  job.scene = builtin ? o.scene : absolute(o.scene);
  job.range = *range;
  job.range.last = range->at(range->count() - 1);  // A:B:STEP ends on the last frame it renders
  job.chunk = o.chunk;
  job.output = absolute(o.output);
  job.hdr = o.hdr.empty() ? "" : absolute(o.hdr);
  job.renderArgs = o.renderArgs;
  return okStatus();
}

Status benchJob(const FarmOptions& o, SlurmJob& job) {
  if (!o.scene.empty() || !o.renderArgs.empty() || !o.framesOut.empty() || !o.output.empty())
    return makeError(ExitCode::BadArguments, "farm slurm: --bench-plan takes no SCENE, --frames-out, -o or --");
  if (o.shards == 0) return makeError(ExitCode::BadArguments, "farm slurm: --bench-plan needs --shards N");
  if (!fs::is_regular_file(o.benchPlan))
    return makeError(ExitCode::BadInput, "farm slurm: plan '{}' is not a file", o.benchPlan);
  if (fs::path(o.benchJson).extension() != ".json")
    return makeError(ExitCode::BadArguments, "farm slurm: --json '{}' must end in .json", o.benchJson);
  job.benchPlan = absolute(o.benchPlan);
  job.shards = o.shards;
  job.benchJson = absolute(o.benchJson);
  return okStatus();
}

Status writeScript(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream f(tmp);
    f << text;
    if (!f) return makeError(ExitCode::OutputFailed, "farm slurm: cannot write {}", path);
  }
  ::chmod(tmp.c_str(), 0755);
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) return makeError(ExitCode::OutputFailed, "farm slurm: cannot write {}: {}", path, ec.message());
  return okStatus();
}

// `sbatch --parsable SCRIPT`: the job id, or why not.
Result<std::string> submit(const std::string& script) {
  bool found = false;
  std::stringstream path(std::getenv("PATH") ? std::getenv("PATH") : "");
  for (std::string dir; std::getline(path, dir, ':');)
    found = found || (!dir.empty() && ::access((dir + "/sbatch").c_str(), X_OK) == 0);
  if (!found)
    return makeError(ExitCode::Failure,
                     "farm slurm --submit: sbatch is not on PATH (the script is written: run `sbatch {}` where "
                     "Slurm is installed)",
                     script);
  std::fflush(nullptr);
  FILE* pipe = ::popen(("sbatch --parsable " + shellQuote(script) + " 2>&1").c_str(), "r");
  if (!pipe) return makeError(ExitCode::Failure, "farm slurm --submit: cannot run sbatch");
  std::string out;
  char buf[512];
  while (size_t n = std::fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = ::pclose(pipe);
  while (!out.empty() && std::isspace(static_cast<unsigned char>(out.back()))) out.pop_back();
  if (status != 0 || out.empty() || !std::isdigit(static_cast<unsigned char>(out[0]))) {
    for (char& c : out)
      if (c == '\n') c = ' ';
    return makeError(ExitCode::Failure, "farm slurm --submit: sbatch refused {}: {}", script, out);
  }
  return out.substr(0, out.find(';'));  // --parsable: "ID" or "ID;CLUSTER"
}

// benchShardPath's files of every shard, as a shell glob.
std::string shardGlob(const std::string& json, uint32_t shards) {
  std::string path = benchShardPath(json, 1, shards);
  return path.replace(path.rfind(".shard-1-of-"), 9, ".shard-*-");
}

}  // namespace

Result<SlurmJob> slurmJob(const FarmOptions& o) {
  SlurmJob job;
  if (Status s = o.benchPlan.empty() ? renderJob(o, job) : benchJob(o, job); !s) return s.error();
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  job.rayster = ec ? "rayster" : self.string();
  job.workDir = fs::current_path().string();
  const std::string anchor = job.isBench() ? job.benchJson : job.output;
  job.name = o.name.empty() ? defaultName(anchor) : o.name;
  for (char c : job.name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.')
      return makeError(ExitCode::BadArguments, "farm slurm: --job-name '{}': letters, digits, - _ . only", job.name);
  job.logDir = o.logDir.empty() ? (fs::path(anchor).parent_path() / "slurm").string() : absolute(o.logDir);
  job.gres = o.gres == "none" ? "" : o.gres;
  if (job.gres.find_first_of(" \t\n'\"") != std::string::npos)
    return makeError(ExitCode::BadArguments, "farm slurm: --gres '{}' is not a gres (e.g. gpu:1, or none)", o.gres);
  const std::pair<const char*, const std::string*> named[] = {{"partition", &o.partition},   {"time", &o.time},
                                                              {"account", &o.account},       {"qos", &o.qos},
                                                              {"constraint", &o.constraint}, {"mem", &o.mem}};
  for (const auto& [key, value] : named)
    if (!value->empty()) job.sbatchOptions.push_back(fmt::format("--{}={}", key, *value));
  if (o.cpusPerTask > 0) job.sbatchOptions.push_back(fmt::format("--cpus-per-task={}", o.cpusPerTask));
  for (const std::string& s : o.sbatch) job.sbatchOptions.push_back(s);
  for (const std::string& s : job.sbatchOptions)
    if (Status st = checkSbatchOption(s); !st) return st.error();
  job.maxRetries = o.maxRetries;
  return job;
}

int farmCommand(const FarmOptions& o) {
  auto job = slurmJob(o);
  if (!job) return fail(job.error());
  auto text = slurmScript(*job);
  if (!text) return fail(text.error());
  if (o.script == "-") {
    if (o.submit) return fail(makeError(ExitCode::BadArguments, "farm slurm: --submit needs a --script file"));
    std::fputs(text->c_str(), stdout);
    return 0;
  }
  const std::string script =
      o.script.empty() ? (fs::path(job->logDir) / (job->name + ".sbatch")).string() : absolute(o.script);
  // Slurm does not create the log folder (a task whose log cannot open fails without a word), and
  // the tasks should not race to create the output folder.
  std::error_code ec;
  for (const std::string& dir : {job->logDir, fs::path(script).parent_path().string(),
                                 fs::path(job->isBench() ? job->benchJson : job->output).parent_path().string()}) {
    fs::create_directories(dir, ec);
    if (ec) return fail(makeError(ExitCode::OutputFailed, "farm slurm: cannot create {}: {}", dir, ec.message()));
  }
  if (Status s = writeScript(script, *text); !s) return fail(s.error());
  log::info("wrote {}: {} array task(s) of {}, logs in {}", script, job->tasks(),
            job->isBench() ? fmt::format("one shard of {}", job->benchPlan) : fmt::format("{} frames", job->chunk),
            job->logDir);
  if (job->isBench())
    log::info("when every task is done, merge the shards with: rayster bench --merge {} --json {}",
              shardGlob(job->benchJson, job->shards), job->benchJson);
  if (!o.submit) {
    log::info("submit it with: sbatch {}", script);
    return 0;
  }
  auto id = submit(script);
  if (!id) return fail(id.error());
  log::info("submitted job array {} ({} task(s))", *id, job->tasks());
  std::printf("%s\n", id->c_str());  // stdout: the job id alone, for scripts
  return 0;
}

CLI::App* addFarmCommand(CLI::App& cli, FarmOptions& o) {
  CLI::App* farm = cli.add_subcommand("farm", "Spread a frame range or a bench plan over a cluster (docs/farm.md)");
  farm->require_subcommand(1);
  CLI::App* s = o.slurm = farm->add_subcommand(
      "slurm",
      "Write (with --submit: submit) an sbatch job array: one task per chunk of --frames-out (or per bench shard), "
      "one GPU each, resumable (--skip-existing), requeued on a retryable exit code. Render options go after --");
  s->add_option("scene", o.scene, "Scene, as for render");
  s->add_option("render-args", o.renderArgs, "After --: render options every task gets (--size, --mode, ...)");
  s->add_option("--frames-out", o.framesOut, "FIRST:LAST[:STEP], as for render");
  s->add_option("--chunk", o.chunk, "Output frames per array task")->check(CLI::Range(uint64_t(1), uint64_t(1) << 40));
  s->add_option("-o,--output", o.output, "Output pattern with # for the frame number, as for render");
  s->add_option("--hdr", o.hdr, "Also the linear HDR .exr pattern, as for render");
  s->add_option("--bench-plan", o.benchPlan,
                "A bench plan (bench/plans/*.json) instead of a scene: one shard per task");
  s->add_option("--shards", o.shards, "With --bench-plan: the number of shards (tasks)")
      ->check(CLI::Range(1u, 100000u));
  s->add_option("--json", o.benchJson,
                "With --bench-plan: merged results (default bench-out/bench.json); shard i writes "
                "<stem>.shard-i-of-N.json beside it");
  s->add_option("--script", o.script,
                "Where to write the script (default <output folder>/slurm/NAME.sbatch; - stdout)");
  s->add_option("--log-dir", o.logDir, "Task logs, NAME_JOB_TASK.log (default <output folder>/slurm)");
  s->add_option("--job-name", o.name, "sbatch --job-name (default rayster-<output stem>)");
  s->add_option("--gres", o.gres, "Generic resources per task (default gpu:1; none for CPU-only nodes)");
  s->add_option("--partition", o.partition, "sbatch --partition");
  s->add_option("--time", o.time, "sbatch --time, per task");
  s->add_option("--account", o.account, "sbatch --account");
  s->add_option("--qos", o.qos, "sbatch --qos");
  s->add_option("--constraint", o.constraint, "sbatch --constraint");
  s->add_option("--mem", o.mem, "sbatch --mem, per task");
  s->add_option("--cpus-per-task", o.cpusPerTask, "sbatch --cpus-per-task");
  s->add_option("--sbatch", o.sbatch, "Any other sbatch option, one per --sbatch (e.g. --sbatch=--exclusive)")
      ->allow_extra_args(false);
  s->add_option("--max-retries", o.maxRetries,
                fmt::format("Requeues of a task after a retryable failure (default {})", kDefaultMaxRetries))
      ->check(CLI::Range(0u, 1000u));
  s->add_flag("--submit", o.submit, "Submit the script with sbatch and print the job id");
  return farm;
}

}  // namespace rayster::app
