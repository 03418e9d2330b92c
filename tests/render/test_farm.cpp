// `rayster farm slurm` (docs/farm.md): the sbatch script it writes, read as text, and its array
// tasks run by bash with a stand-in rayster and scontrol (no Slurm needed): the tasks cover the
// range once, requeue on retryable exit codes only, and clean only their own stale temporary files.
// The real Slurm run is tests/scripts/test_farm_slurm.sh (ctest farm_slurm).
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "app/farm_slurm.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

namespace fs = std::filesystem;

void writeExecutable(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
  fs::permissions(p, fs::perms::owner_all);
}

bool hasLine(const std::string& text, const std::string& line) {
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (l == line) return true;
  return false;
}

TEST(FarmSlurm, ScriptIsAnArrayOfResumableOneGpuTasks) {
  const fs::path dir = testDir();
  RunResult r = runRayster("farm slurm builtin:cornell --frames-out 0:9 --chunk 4 -o " + (dir / "f_####.png").string() +
                           " --script - --partition gpu --time 1:00:00 --sbatch=--exclusive -- --size 32x24 --mode "
                           "raster");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::string& s = r.output;
  EXPECT_EQ(s.rfind("#!/usr/bin/env bash\n", 0), 0u) << s;
  for (const std::string& line : std::vector<std::string>{
           "#SBATCH --array=0-2", "#SBATCH --requeue", "#SBATCH --gres=gpu:1", "#SBATCH --open-mode=append",
           "#SBATCH --job-name=rayster-f", "#SBATCH --output=" + (dir / "slurm").string() + "/rayster-f_%A_%a.log",
           "#SBATCH --partition=gpu", "#SBATCH --time=1:00:00", "#SBATCH --exclusive", "first=0 last=9 step=1 chunk=4",
           "rayster='" + fs::canonical(RAYSTER_BINARY).string() + "'",
           "cd '" + fs::current_path().string() + "' || exit 3"})
    EXPECT_TRUE(hasLine(s, line)) << line << "\n" << s;
  EXPECT_NE(s.find("\"$rayster\" render 'builtin:cornell' '--size' '32x24' '--mode' 'raster' \"${device[@]}\" "
                   "--frames-out \"$a:$b:$step\" -o '" +
                   (dir / "f_####.png").string() + "' --skip-existing --progress lines"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("4|6|7|8) kind=retryable"), std::string::npos) << s;
  // --gres none (CPU-only nodes) leaves the line out; a range with a step ends on its last frame.
  RunResult cpu = runRayster("farm slurm builtin:cornell --frames-out 3:20:2 --chunk 3 -o " +
                             (dir / "g_###.png").string() + " --script - --gres none");
  ASSERT_EQ(cpu.exitCode, 0) << cpu.output;
  EXPECT_EQ(cpu.output.find("--gres"), std::string::npos) << cpu.output;
  EXPECT_TRUE(hasLine(cpu.output, "#SBATCH --array=0-2")) << cpu.output;  // 9 frames: 3 tasks
  EXPECT_TRUE(hasLine(cpu.output, "first=3 last=19 step=2 chunk=3")) << cpu.output;
}

TEST(FarmSlurm, WritesTheScriptAndTheLogFolderAndSaysHowToSubmit) {
  const fs::path dir = testDir();
  RunResult r = runRayster("farm slurm builtin:cornell --frames-out 0:5 --chunk 2 -o " +
                           (dir / "shot" / "s_####.png").string() + " --job-name shot1");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const fs::path script = dir / "shot" / "slurm" / "shot1.sbatch";
  ASSERT_TRUE(fs::exists(script)) << r.output;
  EXPECT_TRUE((fs::status(script).permissions() & fs::perms::owner_exec) != fs::perms::none);
  EXPECT_TRUE(fs::is_directory(dir / "shot" / "slurm"));  // Slurm does not create a log folder
  EXPECT_NE(r.output.find("sbatch " + script.string()), std::string::npos) << r.output;
  EXPECT_NE(readText(script).find("#SBATCH --array=0-2"), std::string::npos);
}

TEST(FarmSlurm, RefusesBadInputWithOneLineAndItsExitCode) {
  const fs::path dir = testDir();
  const std::string out = " -o " + (dir / "f_####.png").string() + " --script - ";
  const std::pair<std::string, int> cases[] = {
      {"farm slurm builtin:cornell --frames-out 0:9 --chunk 3 -o " + (dir / "f.png").string(), 2},  // no #
      {"farm slurm builtin:cornell --frames-out 0:9 --chunk 0" + out, 2},
      {"farm slurm builtin:cornell --frames-out 9:0 --chunk 3" + out, 2},
      {"farm slurm builtin:cornell --chunk 3" + out, 2},
      {"farm slurm builtin:cornell --frames-out 0:9 --chunk 3" + out + "-- --frames-out 1:2", 2},
      {"farm slurm builtin:cornell --frames-out 0:9 --chunk 3" + out + "-- --json x.json", 2},
      {"farm slurm builtin:cornell --frames-out 0:9 --chunk 3" + out + "-- --size 3", 2},
      {"farm slurm builtin:cornell --frames-out 0:9 --chunk 3" + out + "-- --no-such-option", 2},
      {"farm slurm builtin:cornell --frames-out 0:9 --chunk 3" + out + "-- builtin:whitted", 2},
      {"farm slurm builtin:cornell --frames-out 0:9 --chunk 3" + out + "--job-name 'a b'", 2},
      {"farm slurm builtin:cornell --frames-out 0:9 --chunk 3" + out + "--sbatch=exclusive", 2},
      {"farm slurm " + (dir / "missing.gltf").string() + " --frames-out 0:9 --chunk 3" + out, 3},
      {"farm slurm --bench-plan " + (dir / "missing.json").string() + " --shards 2 --script -", 3},
      {"farm slurm --bench-plan x.json --script -", 2},
  };
  for (const auto& [args, code] : cases) {
    RunResult r = runRayster(args);
    EXPECT_EQ(r.exitCode, code) << args << "\n" << r.output;
    EXPECT_EQ(r.output.find("#SBATCH"), std::string::npos) << args;
    EXPECT_NE(r.output.find("rayster: error: "), std::string::npos) << args << "\n" << r.output;
  }
  // --submit without sbatch: the script is written, the cause is one line, exit 1.
  RunResult r = runRayster(
      "farm slurm builtin:cornell --frames-out 0:9 --chunk 3 -o " + (dir / "f_####.png").string() + " --submit",
      "PATH=/nonexistent");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("rayster: error: farm slurm --submit: sbatch is not on PATH"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "slurm" / "rayster-f.sbatch"));
}

TEST(FarmSlurm, ShellQuotingSurvivesBash) {
  const fs::path dir = testDir();
  const std::string words[] = {"plain", "it's", "a b", "$HOME", "`x`", "\"q\"", "back\\slash", "*", "semi;colon", ""};
  std::string cmd = "printf '[%s]\\n'";
  std::string expected;
  for (const std::string& w : words) {
    cmd += " " + app::shellQuote(w);
    expected += "[" + w + "]\n";
  }
  writeExecutable(dir / "q.sh", cmd + "\n");
  FILE* p = popen(("bash " + (dir / "q.sh").string()).c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string got;
  char buf[256];
  while (size_t n = fread(buf, 1, sizeof buf, p)) got.append(buf, n);
  pclose(p);
  EXPECT_EQ(got, expected);
  int runs = 0;
  EXPECT_EQ(app::printfPattern("/a#b/100%_##.#.png", runs), "/a#b/100%%_%02d.%01d.png");
  EXPECT_EQ(runs, 2);
}

// A stand-in rayster for the script: logs its arguments, exits with $FAKE_EXIT (KILL: kills itself).
constexpr const char* kFakeRayster = R"SH(#!/usr/bin/env bash
printf '%s\n' "$*" >> "$FAKE_LOG"
if [ "$FAKE_EXIT" = KILL ]; then kill -KILL $$; fi
exit "$FAKE_EXIT"
)SH";

struct TaskRun {
  int exitCode = -1;
  std::string output;
};

TaskRun runTask(const fs::path& script, const std::string& env) {
  TaskRun t;
  FILE* p = popen((env + " bash " + script.string() + " 2>&1").c_str(), "r");
  if (!p) return t;
  char buf[512];
  while (size_t n = fread(buf, 1, sizeof buf, p)) t.output.append(buf, n);
  const int status = pclose(p);
  t.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return t;
}

app::SlurmJob fakeJob(const fs::path& dir) {
  app::SlurmJob job;
  job.rayster = (dir / "rayster").string();
  job.workDir = dir.string();
  job.name = "t";
  job.logDir = dir.string();
  job.scene = "builtin:cornell";
  job.range = {3, 19, 2};  // 3, 5, ..., 19: 9 frames
  job.chunk = 4;           // tasks of 4, 4 and 1 frame(s)
  job.output = (dir / "out" / "f_####.png").string();
  job.renderArgs = {"--size", "32x24"};
  return job;
}

TEST(FarmSlurm, TasksCoverTheRangeOnceAndRequeueOnlyRetryableFailures) {
  const fs::path dir = testDir();
  writeExecutable(dir / "rayster", kFakeRayster);
  fs::create_directories(dir / "bin");
  writeExecutable(dir / "bin" / "scontrol", "#!/bin/sh\necho \"$*\" >> \"$FAKE_SCONTROL\"\n");
  auto text = app::slurmScript(fakeJob(dir));
  ASSERT_TRUE(text.ok()) << text.error().message;
  EXPECT_TRUE(hasLine(*text, "#SBATCH --array=0-2")) << *text;
  writeExecutable(dir / "job.sh", *text);
  const std::string env = "PATH=" + (dir / "bin").string() + ":$PATH FAKE_LOG=" + (dir / "log").string() +
                          " FAKE_SCONTROL=" + (dir / "scontrol").string() + " SLURM_JOB_ID=77";

  std::multiset<int64_t> frames;
  for (int task = 0; task < 3; ++task) {
    fs::remove(dir / "log");
    TaskRun t = runTask(dir / "job.sh", env + " FAKE_EXIT=0 SLURM_ARRAY_TASK_ID=" + std::to_string(task));
    ASSERT_EQ(t.exitCode, 0) << t.output;
    const std::string args = readText(dir / "log");
    EXPECT_NE(args.find("--skip-existing --progress lines"), std::string::npos) << args;
    const size_t at = args.find("--frames-out ");
    ASSERT_NE(at, std::string::npos) << args;
    long long a = 0, b = 0, step = 0;
    ASSERT_EQ(std::sscanf(args.c_str() + at, "--frames-out %lld:%lld:%lld", &a, &b, &step), 3) << args;
    EXPECT_EQ(step, 2);
    for (long long f = a; f <= b; f += step) frames.insert(f);
  }
  EXPECT_EQ(frames, (std::multiset<int64_t>{3, 5, 7, 9, 11, 13, 15, 17, 19}));
  EXPECT_FALSE(fs::exists(dir / "scontrol"));  // nothing failed, nothing requeued

  // Retryable codes and signals requeue this task (its SLURM_JOB_ID) until max_retries; the others do not.
  const std::pair<std::string, bool> cases[] = {{"4", true},  {"6", true},  {"7", true},  {"8", true}, {"KILL", true},
                                                {"1", false}, {"2", false}, {"3", false}, {"5", false}};
  for (const auto& [code, requeued] : cases) {
    fs::remove(dir / "scontrol");
    TaskRun t = runTask(dir / "job.sh", env + " FAKE_EXIT=" + code + " SLURM_ARRAY_TASK_ID=1");
    EXPECT_NE(t.exitCode, 0) << code;
    EXPECT_EQ(fs::exists(dir / "scontrol"), requeued) << code << "\n" << t.output;
    if (requeued) {
      EXPECT_EQ(readText(dir / "scontrol"), "requeue 77\n") << code;
    }
  }
  fs::remove(dir / "scontrol");
  TaskRun spent = runTask(dir / "job.sh", env + " FAKE_EXIT=6 SLURM_RESTART_COUNT=3 SLURM_ARRAY_TASK_ID=1");
  EXPECT_EQ(spent.exitCode, 6) << spent.output;
  EXPECT_FALSE(fs::exists(dir / "scontrol")) << spent.output;
  EXPECT_NE(spent.output.find("code 6 (retryable, after 3 restart(s))"), std::string::npos) << spent.output;
}

TEST(FarmSlurm, ATaskRemovesOnlyItsOwnFramesStaleTemporaryFiles) {
  const fs::path dir = testDir();
  writeExecutable(dir / "rayster", kFakeRayster);
  auto text = app::slurmScript(fakeJob(dir));
  ASSERT_TRUE(text.ok());
  writeExecutable(dir / "job.sh", *text);
  fs::create_directories(dir / "out");
  for (const char* name : {"f_0003.png.tmp-123", "f_0009.png.tmp-45", "f_0011.png.tmp-6", "f_0005.png"})
    std::ofstream(dir / "out" / name) << "x";
  // Task 0 renders 3, 5, 7, 9; 11 is task 1's, perhaps being written now.
  TaskRun t = runTask(dir / "job.sh", "FAKE_EXIT=0 FAKE_LOG=" + (dir / "log").string() + " SLURM_ARRAY_TASK_ID=0");
  ASSERT_EQ(t.exitCode, 0) << t.output;
  EXPECT_FALSE(fs::exists(dir / "out" / "f_0003.png.tmp-123"));
  EXPECT_FALSE(fs::exists(dir / "out" / "f_0009.png.tmp-45"));
  EXPECT_TRUE(fs::exists(dir / "out" / "f_0011.png.tmp-6"));
  EXPECT_TRUE(fs::exists(dir / "out" / "f_0005.png"));  // a finished frame stays (--skip-existing skips it)
}

}  // namespace
}  // namespace rayster::test
