// What a scheduler sees when a sequence fails or is stopped (docs/sequences.md, "Faults, signals
// and exit codes"): a device loss or memory exhaustion at frame N exits 6 or 7 with one line and
// keeps every finished frame, and a rerun with --skip-existing completes the range with the pixels
// of a clean run; SIGTERM and SIGINT exit 143 and 130 leaving only whole files; a full file system
// exits 8 and leaves no partial file.
#include <signal.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/render/fixtures.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The animated glTF's slider moves every frame at 12 frames/s, so each frame is its own image;
// one accumulated frame, raster primaries and no indirect light keep a frame at tens of ms.
std::string tinyArgs(const fs::path& scene, const std::string& size = "32x24") {
  return "render " + scene.string() + " --size " + size + " --frames 1 --primary raster --indirect off --path-fps 12";
}

std::string frameName(const fs::path& dir, int64_t frame, const char* ext) {
  char name[32];
  std::snprintf(name, sizeof name, "f_%04lld.%s", static_cast<long long>(frame), ext);
  return (dir / name).string();
}

std::string outputs(const fs::path& dir) {
  return " -o " + (dir / "f_####.png").string() + " --hdr " + (dir / "f_####.exr").string();
}

void expectSameFrame(const fs::path& a, const fs::path& b, int64_t frame) {
  auto pa = readPng(frameName(a, frame, "png")), pb = readPng(frameName(b, frame, "png"));
  auto ea = readExr(frameName(a, frame, "exr")), eb = readExr(frameName(b, frame, "exr"));
  ASSERT_TRUE(pa.ok() && pb.ok() && ea.ok() && eb.ok()) << "frame " << frame;
  EXPECT_TRUE(pa->rgba == pb->rgba) << "frame " << frame << ": the PNGs differ";
  EXPECT_TRUE(ea->rgba == eb->rgba) << "frame " << frame << ": the EXRs differ";
}

int countTemporaryFiles(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    n += e.path().filename().string().find(".tmp-") != std::string::npos;
  return n;
}

size_t countLines(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A device loss (or exhaustion) at frame 3 of 0:5, then a rerun with --skip-existing.
void faultAtFrame3ThenResume(const char* fault, int code, const char* cause) {
  const fs::path dir = testDir();
  const fs::path scene = writeAnimatedGltf(dir), clean = dir / "clean", out = dir / "out";
  const std::string args = tinyArgs(scene) + " --frames-out 0:5 --progress off";
  RunResult whole = runRayster(args + outputs(clean));
  ASSERT_EQ(whole.exitCode, 0) << whole.output;

  RunResult failed = runRayster(args + outputs(out), std::string("RAYSTER_RENDER_FAIL_AT=") + fault + ":3");
  EXPECT_EQ(failed.exitCode, code) << failed.output;
  EXPECT_EQ(countLines(failed.output, "rayster: error:"), 1u) << failed.output;
  EXPECT_NE(failed.output.find(cause), std::string::npos) << failed.output;
  EXPECT_EQ(failed.output.find("validation"), std::string::npos) << failed.output;
  for (int64_t f = 0; f <= 2; ++f) expectSameFrame(clean, out, f);
  for (int64_t f = 3; f <= 5; ++f) EXPECT_FALSE(fs::exists(frameName(out, f, "png"))) << f;
  EXPECT_EQ(countTemporaryFiles(dir), 0);
  const auto frame0Time = fs::last_write_time(frameName(out, 0, "png"));

  RunResult resumed = runRayster(args + outputs(out) + " --skip-existing");
  ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("wrote 3 of 6 frames"), std::string::npos) << resumed.output;
  EXPECT_EQ(fs::last_write_time(frameName(out, 0, "png")), frame0Time) << "frame 0 was rendered again";
  for (int64_t f = 0; f <= 5; ++f) expectSameFrame(clean, out, f);
  EXPECT_EQ(countTemporaryFiles(dir), 0);
}

TEST(SequenceFault, DeviceLostAtFrame3Exits6KeepsFrames0To2AndAResumeEqualsACleanRun) {
  faultAtFrame3ThenResume("lost", 6, "the GPU device was lost");
}

TEST(SequenceFault, OutOfMemoryAtFrame3Exits7KeepsFrames0To2AndAResumeEqualsACleanRun) {
  faultAtFrame3ThenResume("oom", 7, "out of device memory");
}

TEST(SequenceFault, AMalformedInjectionIsRefusedWithOneLine) {
  const fs::path dir = testDir();
  RunResult r = runRayster("render builtin:cornell -o " + (dir / "x.png").string(), "RAYSTER_RENDER_FAIL_AT=lost");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("RAYSTER_RENDER_FAIL_AT must be lost:FRAME or oom:FRAME"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_empty(dir));
}

// `rayster ARGS > log 2>&1` in the background (exec'd, so the pid is rayster's).
pid_t startRayster(const std::string& args, const fs::path& log) {
  const std::string cmd = "exec env XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} RAYSTER_VALIDATION=1 " +
                          std::string(RAYSTER_BINARY) + " " + args + " > " + log.string() + " 2>&1";
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

template <class Predicate>
bool waitUntil(Predicate done, double seconds) {
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return done();
}

// The exit code, or -1 (killed) when it did not end within `seconds`.
int waitForExit(pid_t pid, double seconds) {
  int status = 0;
  const bool ended = waitUntil([&] { return waitpid(pid, &status, WNOHANG) == pid; }, seconds);
  if (!ended) {
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

TEST(SequenceFault, SigtermWritesTheFramesRenderedDropsTheOneInFlightAndExits143) {
  const fs::path dir = testDir();
  const fs::path scene = writeAnimatedGltf(dir), out = dir / "out", log = dir / "log.txt";
  const pid_t pid = startRayster(tinyArgs(scene) + " --frames-out 0:2000 --progress off" + outputs(out), log);
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(waitUntil([&] { return fs::exists(frameName(out, 1, "png")); }, 60)) << readText(log);
  kill(pid, SIGTERM);
  const auto signalled = Clock::now();
  const int code = waitForExit(pid, 20);
  const std::string text = readText(log);
  EXPECT_EQ(code, 143) << text;
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - signalled).count(), 10.0) << text;
  EXPECT_EQ(countLines(text, "rayster: error:"), 1u) << text;
  EXPECT_NE(text.find("interrupted by SIGTERM"), std::string::npos) << text;
  EXPECT_NE(text.find("rerun with --skip-existing"), std::string::npos) << text;
  // Written in order and whole: frames 0..K exist with both images, none after.
  int64_t written = 0;
  while (fs::exists(frameName(out, written, "png"))) {
    auto png = readPng(frameName(out, written, "png"));
    auto exr = readExr(frameName(out, written, "exr"));
    ASSERT_TRUE(png.ok() && exr.ok()) << "frame " << written;
    EXPECT_EQ(png->width, 32);
    ++written;
  }
  EXPECT_GE(written, 2);
  EXPECT_LT(written, 2001);
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(out)) files += e.is_regular_file();
  EXPECT_EQ(files, size_t(2 * written)) << "an image of an unfinished frame was left";
  EXPECT_EQ(countTemporaryFiles(dir), 0);
}

TEST(SequenceFault, SigintWhileAStillAccumulatesWritesNothingAndExits130) {
  const fs::path dir = testDir(), log = dir / "log.txt", image = dir / "still.png";
  const pid_t pid = startRayster(
      "render builtin:cornell --size 32x24 --frames 100000 --primary raster --indirect off --progress lines -o " +
          image.string(),
      log);
  ASSERT_GT(pid, 0);
  // The auto exposure is metered before the accumulation starts.
  ASSERT_TRUE(waitUntil([&] { return readText(log).find("exposure: auto") != std::string::npos; }, 60))
      << readText(log);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(pid, SIGINT);
  const int code = waitForExit(pid, 20);
  const std::string text = readText(log);
  EXPECT_EQ(code, 130) << text;
  EXPECT_EQ(countLines(text, "rayster: error:"), 1u) << text;
  EXPECT_NE(text.find("interrupted by SIGINT: " + image.string() + " not written"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(image));
  EXPECT_EQ(countTemporaryFiles(dir), 0);
}

// The first signal waits for the frame being accumulated (here, every effect at 256x192: a good
// part of a second on lavapipe); a second one ends the process at once, with the bare line.
TEST(SequenceFault, ASecondSignalExitsAtOnce) {
  const fs::path dir = testDir(), log = dir / "log.txt", image = dir / "still.png";
  const pid_t pid = startRayster("render builtin:cornell --size 256x192 --frames 100000 -o " + image.string(), log);
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(waitUntil([&] { return readText(log).find("exposure: auto") != std::string::npos; }, 60))
      << readText(log);
  kill(pid, SIGTERM);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  kill(pid, SIGTERM);
  const int code = waitForExit(pid, 20);
  const std::string text = readText(log);
  EXPECT_EQ(code, 143) << text;
  EXPECT_NE(text.find("rayster: error: interrupted by SIGTERM\n"), std::string::npos) << text;
  EXPECT_EQ(countLines(text, "rayster: error:"), 1u) << text;
  EXPECT_FALSE(fs::exists(image));
  EXPECT_EQ(countTemporaryFiles(dir), 0);
}

// A tmpfs of 64 KiB (16 pages) mounted for the test and unmounted on every way out.
class TinyFileSystem {
 public:
  explicit TinyFileSystem(const fs::path& dir) : dir_(dir) {
    fs::create_directories(dir_);
    if (::mount("tmpfs", dir_.c_str(), "tmpfs", 0, "size=64k") == 0)
      mounted_ = true;
    else
      reason_ = std::string("cannot mount a tmpfs (") + std::strerror(errno) + "; the test needs root)";
  }
  ~TinyFileSystem() {
    if (mounted_ && ::umount2(dir_.c_str(), 0) != 0) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  TinyFileSystem(const TinyFileSystem&) = delete;
  TinyFileSystem& operator=(const TinyFileSystem&) = delete;
  bool mounted() const { return mounted_; }
  const std::string& reason() const { return reason_; }
  // Fills it, leaving `freeBytes` (rounded down to pages) free.
  void fill(size_t freeBytes) {
    const fs::path filler = dir_ / "filler";
    std::FILE* f = std::fopen(filler.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::vector<char> page(4096, 1);
    while (std::fwrite(page.data(), 1, page.size(), f) == page.size() && std::fflush(f) == 0) {
    }
    std::fclose(f);
    const uintmax_t full = fs::file_size(filler);
    fs::resize_file(filler, full > freeBytes ? full - freeBytes : 0);
  }

 private:
  fs::path dir_;
  bool mounted_ = false;
  std::string reason_;
};

TEST(SequenceFault, AFullFileSystemExits8NamingTheFileAndLeavesNoPartialFile) {
  const fs::path dir = testDir(), full = dir / "full";
  TinyFileSystem tmpfs(full);
  if (!tmpfs.mounted()) GTEST_SKIP() << tmpfs.reason();
  // A still on a full disk, PNG and EXR: the small EXR's bytes wait in stdio's buffer until fclose,
  // which is where the full disk shows.
  tmpfs.fill(0);
  for (const char* name : {"still.png", "still.exr"}) {
    RunResult r =
        runRayster("render builtin:cornell --size 32x24 --frames 1 --mode raster -o " + (full / name).string());
    EXPECT_EQ(r.exitCode, 8) << r.output;
    EXPECT_EQ(countLines(r.output, "rayster: error:"), 1u) << r.output;
    EXPECT_NE(r.output.find("rayster: error: cannot write " + (full / name).string() + ": no space left on device"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(full / name)) << name;
  }
  EXPECT_EQ(countTemporaryFiles(full), 0);

  // A sequence that fills the disk part way: the frames before stay whole, the one that did not
  // fit is named and absent.
  tmpfs.fill(3 * 4096);
  const fs::path scene = writeAnimatedGltf(dir);
  RunResult r =
      runRayster(tinyArgs(scene, "64x48") + " --frames-out 0:20 --progress off -o " + (full / "f_####.png").string());
  EXPECT_EQ(r.exitCode, 8) << r.output;
  EXPECT_EQ(countLines(r.output, "rayster: error:"), 1u) << r.output;
  const size_t at = r.output.find("rayster: error: cannot write " + full.string() + "/f_");
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_NE(r.output.find(": no space left on device", at), std::string::npos) << r.output;
  const std::string named = r.output.substr(at + 29, r.output.find(':', at + 29) - at - 29);
  EXPECT_FALSE(fs::exists(named)) << named;
  int whole = 0;
  for (const auto& e : fs::directory_iterator(full)) {
    if (e.path().filename() == "filler") continue;
    auto png = readPng(e.path());
    EXPECT_TRUE(png.ok()) << e.path() << ": " << (png.ok() ? "" : png.error().message);
    whole += png.ok();
  }
  EXPECT_GE(whole, 1) << "three pages hold at least one 64x48 frame";
  EXPECT_EQ(countTemporaryFiles(full), 0);
}

}  // namespace
}  // namespace rayster::test
