// Image sequences (`render --frames-out A:B[:STEP]`, docs/sequences.md): a chunk of a range renders
// the same pixels as the whole range, --skip-existing resumes one, bad input is refused before any
// GPU work, and a failed write stops with exit 8 leaving no partial file.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "tests/render/fixtures.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

namespace fs = std::filesystem;

// The animated glTF's slider crosses the floor in 1 s: at 12 frames/s every frame moves it. Raster
// primaries (--primary auto times both producers, and a close race may pick differently in two
// processes); no indirect light here (its probe warm-up after every restart costs about 2.4 s per
// output frame on lavapipe; ProbesRestartWithEveryFrame covers it); TAA, the shadow, AO and
// reflection denoisers and auto exposure all keep histories across the 2 accumulated frames.
std::string sequenceArgs(const fs::path& scene) {
  return "render " + scene.string() + " --size 48x36 --frames 2 --primary raster --indirect off --path-fps 12";
}

std::string frameName(const fs::path& dir, int frame, const char* ext) {
  char name[32];
  std::snprintf(name, sizeof name, "f_%04d.%s", frame, ext);
  return (dir / name).string();
}

// Bit for bit: the 8-bit image and the half-float EXR of one frame.
void expectSameFrame(const fs::path& a, const fs::path& b, int frame) {
  auto pa = readPng(frameName(a, frame, "png")), pb = readPng(frameName(b, frame, "png"));
  auto ea = readExr(frameName(a, frame, "exr")), eb = readExr(frameName(b, frame, "exr"));
  ASSERT_TRUE(pa.ok() && pb.ok() && ea.ok() && eb.ok()) << "frame " << frame;
  EXPECT_TRUE(pa->rgba == pb->rgba) << "frame " << frame << ": the PNGs differ";
  size_t differ = 0;
  for (size_t i = 0; i < ea->rgba.size() && i < eb->rgba.size(); ++i) differ += ea->rgba[i] != eb->rgba[i];
  EXPECT_EQ(ea->rgba.size(), eb->rgba.size());
  EXPECT_EQ(differ, 0u) << "frame " << frame << ": " << differ << " EXR values differ";
}

bool anyTemporaryFile(const fs::path& dir) {
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp-") != std::string::npos) return true;
  return false;
}

TEST(Sequence, AChunkEqualsTheSameFramesOfTheWholeRange) {
  const fs::path dir = testDir();
  const fs::path scene = writeAnimatedGltf(dir), whole = dir / "whole", chunk = dir / "chunk";
  RunResult all = runRayster(sequenceArgs(scene) + " --frames-out 0:12 --progress lines -o " +
                             (whole / "f_####.png").string() + " --hdr " + (whole / "f_####.exr").string());
  ASSERT_EQ(all.exitCode, 0) << all.output;
  // One line per written frame (each takes longer than kSequenceLineInterval? not on every
  // machine: the first and the last are always there).
  EXPECT_NE(all.output.find("frame 0 -> "), std::string::npos) << all.output;
  EXPECT_NE(all.output.find("frame 12 -> "), std::string::npos) << all.output;
  EXPECT_NE(all.output.find("13/13, 100%"), std::string::npos) << all.output;
  RunResult part = runRayster(sequenceArgs(scene) + " --frames-out 10:12 -o " + (chunk / "f_####.png").string() +
                              " --hdr " + (chunk / "f_####.exr").string());
  ASSERT_EQ(part.exitCode, 0) << part.output;
  EXPECT_FALSE(fs::exists(frameName(chunk, 9, "png")));
  for (int f = 10; f <= 12; ++f) expectSameFrame(whole, chunk, f);
  // And the frames are not all one image: the slider moves.
  auto f0 = readPng(frameName(whole, 0, "png")), f10 = readPng(frameName(whole, 10, "png")),
       f12 = readPng(frameName(whole, 12, "png"));
  ASSERT_TRUE(f0.ok() && f10.ok() && f12.ok());
  EXPECT_FALSE(f0->rgba == f10->rgba);
  EXPECT_FALSE(f10->rgba == f12->rgba);
  EXPECT_FALSE(anyTemporaryFile(dir));
}

// Every output frame is metered afresh; the "exposure: auto" line comes again only when the
// exposure changed, not once per frame (a 10000-frame job's log).
TEST(Sequence, AnUnchangedExposureIsLoggedOnce) {
  const fs::path dir = testDir();
  RunResult r = runRayster("render builtin:cornell --size 32x24 --frames 1 --indirect off --frames-out 0:3 -o " +
                           (dir / "f_#.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  size_t lines = 0;
  for (size_t at = r.output.find("exposure: auto"); at != std::string::npos;
       at = r.output.find("exposure: auto", at + 1))
    ++lines;
  EXPECT_EQ(lines, 1u) << r.output;
}

TEST(Sequence, SkipExistingRendersOnlyTheMissingFramesAndTheSamePixels) {
  const fs::path dir = testDir();
  const fs::path scene = writeAnimatedGltf(dir), out = dir / "out";
  const std::string args = sequenceArgs(scene) + " --frames-out 0:4:2 -o " + (out / "f_####.png").string() + " --hdr " +
                           (out / "f_####.exr").string() + " --json " + (dir / "run.json").string();
  RunResult first = runRayster(args + " --progress bar");
  ASSERT_EQ(first.exitCode, 0) << first.output;
  EXPECT_NE(first.output.find("\r"), std::string::npos) << "--progress bar redraws in place";
  EXPECT_NE(first.output.find("frames/s, ETA"), std::string::npos) << first.output;
  for (int f : {0, 2, 4}) ASSERT_TRUE(fs::exists(frameName(out, f, "png"))) << f;
  EXPECT_FALSE(fs::exists(frameName(out, 1, "png")));
  const fs::path keep = dir / "frame2";
  fs::create_directories(keep);
  for (const char* ext : {"png", "exr"}) fs::rename(frameName(out, 2, ext), frameName(keep, 2, ext));
  const auto frame0Time = fs::last_write_time(frameName(out, 0, "png"));

  RunResult resumed = runRayster(args + " --skip-existing --progress off");
  ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
  EXPECT_EQ(resumed.output.find(" -> "), std::string::npos) << "--progress off prints no progress\n" << resumed.output;
  expectSameFrame(out, keep, 2);
  EXPECT_EQ(fs::last_write_time(frameName(out, 0, "png")), frame0Time) << "frame 0 was rendered again";
  std::ifstream f(dir / "run.json");
  const nlohmann::json j = nlohmann::json::parse(f, nullptr, false);
  ASSERT_FALSE(j.is_discarded());
  const nlohmann::json& seq = j["sequence"];
  EXPECT_EQ(seq["frames_written"], 1) << seq.dump();
  EXPECT_EQ(seq["frames_skipped"], 2) << seq.dump();
  EXPECT_EQ(seq["frames_in_range"], 3) << seq.dump();
  EXPECT_GT(seq["wall_s"].get<double>(), 0.0);
  EXPECT_GT(seq["frames_per_s"].get<double>(), 0.0);
  EXPECT_TRUE(seq.contains("encode_s") && seq.contains("render_thread_wait_s")) << seq.dump();
  EXPECT_TRUE(j.contains("passes")) << "the render's own JSON is still there";
}

TEST(Sequence, ProbesRestartWithEveryFrameSoAChunkStillMatches) {
  // The irradiance probes (--gi probes, the default) are the history with the longest memory.
  const fs::path dir = testDir();
  const fs::path scene = writeAnimatedGltf(dir), whole = dir / "whole", chunk = dir / "chunk";
  const std::string args = "render " + scene.string() + " --size 32x24 --frames 1 --primary raster --path-fps 12";
  RunResult all = runRayster(args + " --frames-out 0:2 -o " + (whole / "f_####.png").string() + " --hdr " +
                             (whole / "f_####.exr").string());
  ASSERT_EQ(all.exitCode, 0) << all.output;
  RunResult part = runRayster(args + " --frames-out 2:2 -o " + (chunk / "f_####.png").string() + " --hdr " +
                              (chunk / "f_####.exr").string());
  ASSERT_EQ(part.exitCode, 0) << part.output;
  expectSameFrame(whole, chunk, 2);
}

TEST(Sequence, ARunDoesNotInheritTheExposureOrCullingOfTheRunsBeforeIt) {
  // Without Renderer::restartHistories the whitted scene's frame 3 after frames 0-2 differs from
  // frame 3 alone (the auto exposure starts from the last run's reading instead of its estimate).
  const fs::path dir = testDir(), whole = dir / "whole", chunk = dir / "chunk";
  const std::string args = "render builtin:whitted --size 32x24 --frames 2 --primary raster --indirect off";
  RunResult all = runRayster(args + " --frames-out 0:3 -o " + (whole / "f_####.png").string() + " --hdr " +
                             (whole / "f_####.exr").string());
  ASSERT_EQ(all.exitCode, 0) << all.output;
  RunResult part = runRayster(args + " --frames-out 3:3 -o " + (chunk / "f_####.png").string() + " --hdr " +
                              (chunk / "f_####.exr").string());
  ASSERT_EQ(part.exitCode, 0) << part.output;
  expectSameFrame(whole, chunk, 3);
}

TEST(Sequence, BadRangesAndNamesAreRefusedWithOneLine) {
  const fs::path dir = testDir();
  struct Case {
    std::string args, cause;
  } cases[] = {
      {"--frames-out 5:2 -o " + (dir / "f_#.png").string(), "the last frame (2) is before the first (5)"},
      {"--frames-out 0:3 -o " + (dir / "f.png").string(), "needs # for the frame number"},
      {"--frames-out 0:3 -o " + (dir / "f_#.png").string() + " --hdr " + (dir / "h.exr").string(), "--hdr"},
      {"--frames-out 1-3 -o " + (dir / "f_#.png").string(), "must be FIRST:LAST or FIRST:LAST:STEP"},
      {"--frames-out 0:3:0 -o " + (dir / "f_#.png").string(), "step must be at least 1"},
      {"--skip-existing -o " + (dir / "f.png").string(), "--skip-existing needs --frames-out"},
      {"--progress sometimes -o " + (dir / "f.png").string(), "--progress must be auto, bar, lines or off"},
      {"--frames-out 0:1 --move-instance a:0,0,0@1 -o " + (dir / "f_#.png").string(), "--move-instance"},
  };
  for (const Case& c : cases) {
    RunResult r = runRayster("render builtin:cornell " + c.args);
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.cause), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << c.args << "\n" << r.output;
  }
  EXPECT_TRUE(fs::is_empty(dir)) << "nothing was written";
}

TEST(Sequence, AFailedWriteStopsWithCode8AndLeavesNoPartialFile) {
  const fs::path dir = testDir();
  // Frame 1's name is taken by a folder: its rename fails, as a full disk or a read-only share would.
  fs::create_directories(dir / "f_0001.png");
  RunResult r = runRayster("render builtin:cornell --size 32x24 --frames 1 --mode raster --frames-out 0:3 -o " +
                           (dir / "f_####.png").string());
  EXPECT_EQ(r.exitCode, 8) << r.output;
  EXPECT_NE(r.output.find("rayster: error: cannot write " + (dir / "f_0001.png").string()), std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(dir / "f_0000.png")) << "frames before the failure stay";
  EXPECT_TRUE(fs::is_directory(dir / "f_0001.png"));
  EXPECT_FALSE(anyTemporaryFile(dir)) << r.output;
}

}  // namespace
}  // namespace rayster::test
