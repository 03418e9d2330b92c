// `rayster view` under Xvfb on lavapipe: the window renders the same frame graph as the headless
// path, so a scripted run's screenshot (panel hidden) must match `rayster render` of the same
// scene, camera, size and frame count. TAA stays on: both runs use the same jitter sequence and
// seeds, so the comparison tolerance only covers the blit (exact for same-size copies).
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kWidth = 160, kHeight = 120;

TEST(Viewer, ScreenshotMatchesHeadlessRender) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is missing (scripts/setup.sh installs xvfb and xauth)";
  const auto dir = testDir();
  const std::string common =
      "builtin:cornell --primary raster --frames 4 --size " + std::to_string(kWidth) + "x" + std::to_string(kHeight);
  const auto shot = dir / "view.png";
  RunResult v = runUnderXvfb("view " + common + " --hide-ui --screenshot " + shot.string());
  ASSERT_EQ(v.exitCode, 0) << v.output;
  RunResult h = runRayster("render " + common + " -o " + (dir / "render.png").string());
  ASSERT_EQ(h.exitCode, 0) << h.output;
  auto viewed = readPng(shot);
  auto rendered = readPng(dir / "render.png");
  ASSERT_TRUE(viewed.ok() && rendered.ok());
  ASSERT_EQ(viewed->width, kWidth);
  ASSERT_EQ(viewed->height, kHeight);
  EXPECT_FALSE(rejectEmpty(*viewed, kWidth, kHeight).has_value());
  // Same graph, same settings: the images agree to within the 8-bit rounding of the blit.
  const ImageDiff d = compare(*rendered, *viewed, 1);
  EXPECT_GE(d.fractionWithinTolerance, 0.999) << "max difference " << d.maxChannelDiff;
}

TEST(Viewer, ScriptedCameraPathMatchesHeadlessRender) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is missing (scripts/setup.sh installs xvfb and xauth)";
  const auto dir = testDir();
  auto file = dir / "path.json";
  std::ofstream(file) << R"({
  "models": [{"path": "builtin:cornell"}],
  "cameraPath": [{"time": 0, "position": [0, 1, 3.9], "target": [0, 1, 0]},
                 {"time": 1, "position": [0.6, 1.2, 3.6], "target": [0, 1, 0]}]
})";
  const std::string common = file.string() + " --primary raster --camera-path --path-fps 10 --frames 5 --size 128x96";
  RunResult v = runUnderXvfb("view " + common + " --hide-ui --screenshot " + (dir / "view.png").string());
  ASSERT_EQ(v.exitCode, 0) << v.output;
  RunResult h = runRayster("render " + common + " -o " + (dir / "render.png").string());
  ASSERT_EQ(h.exitCode, 0) << h.output;
  auto viewed = readPng(dir / "view.png");
  auto rendered = readPng(dir / "render.png");
  ASSERT_TRUE(viewed.ok() && rendered.ok());
  EXPECT_FALSE(rejectEmpty(*viewed, 128, 96).has_value());
  const ImageDiff d = compare(*rendered, *viewed, 1);
  EXPECT_GE(d.fractionWithinTolerance, 0.999) << "max difference " << d.maxChannelDiff;
}

TEST(Viewer, ResizeMidRunIsCleanUnderValidation) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is missing (scripts/setup.sh installs xvfb and xauth)";
  const auto dir = testDir();
  const auto shot = dir / "resized.png";
  // Grow, then shrink; the panel stays on so ImGui's pipeline sees the new framebuffers too.
  RunResult v = runUnderXvfb(
      "view builtin:spheres --frames 6 --size 160x120 --resize-at 2:200x150 "
      "--resize-at 4:128x96 --screenshot " +
      shot.string());
  ASSERT_EQ(v.exitCode, 0) << v.output;
  EXPECT_EQ(v.output.find("validation error"), std::string::npos) << v.output;
  auto img = readPng(shot);
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img->width, 128);
  EXPECT_EQ(img->height, 96);
}

// Scripted edits (--move-instance, the same path as the panel's drags): the block's pixels move,
// its motion vectors are nonzero where a still scene's are zero, and validation stays clean.
TEST(Viewer, MovedInstanceMovesPixelsWithMotionVectors) {
  const auto dir = testDir();
  const std::string common = "render builtin:cornell --primary raster --frames 3 --size 160x120 --aov motion";
  RunResult still = runRayster(common + " -o " + (dir / "still.png").string());
  ASSERT_EQ(still.exitCode, 0) << still.output;
  RunResult moved = runRayster(common + " --move-instance short-block:0.8,0,0.3@2 -o " + (dir / "moved.png").string());
  ASSERT_EQ(moved.exitCode, 0) << moved.output;
  EXPECT_EQ(moved.output.find("validation error"), std::string::npos) << moved.output;
  auto a = readPng(dir / "still.png");
  auto b = readPng(dir / "moved.png");
  ASSERT_TRUE(a.ok() && b.ok());
  const ImageDiff d = compare(*a, *b, 8);
  EXPECT_LT(d.fractionWithinTolerance, 0.98) << "the block did not move";
  auto countMoving = [](const ImageF& mv) {
    size_t n = 0;
    for (size_t i = 0; i < mv.rgba.size(); i += 4) n += std::abs(mv.rgba[i]) + std::abs(mv.rgba[i + 1]) > 1e-6f;
    return n;
  };
  auto stillMotion = readExr(dir / "still.motion.exr");
  auto movedMotion = readExr(dir / "moved.motion.exr");
  ASSERT_TRUE(stillMotion.ok() && movedMotion.ok());
  EXPECT_EQ(countMoving(*stillMotion), 0u);
  EXPECT_GT(countMoving(*movedMotion), size_t(160 * 120 / 100)) << "no motion vectors on the moved block";

  // A bad name is a bad argument, before any output.
  RunResult bad = runRayster(common + " --move-instance nothing:0,0,0@1 -o " + (dir / "bad.png").string());
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
}

TEST(Viewer, MovedInstanceMatchesHeadlessRender) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is missing (scripts/setup.sh installs xvfb and xauth)";
  const auto dir = testDir();
  const std::string common =
      "builtin:cornell --primary raster --frames 4 --size 160x120 "
      "--move-instance short-block:0.8,0,0.3@2";
  RunResult v = runUnderXvfb("view " + common + " --hide-ui --screenshot " + (dir / "view.png").string());
  ASSERT_EQ(v.exitCode, 0) << v.output;
  RunResult h = runRayster("render " + common + " -o " + (dir / "render.png").string());
  ASSERT_EQ(h.exitCode, 0) << h.output;
  auto viewed = readPng(dir / "view.png");
  auto rendered = readPng(dir / "render.png");
  ASSERT_TRUE(viewed.ok() && rendered.ok());
  const ImageDiff d = compare(*rendered, *viewed, 1);
  EXPECT_GE(d.fractionWithinTolerance, 0.999) << "max difference " << d.maxChannelDiff;
}

// --debug-view shows what `--aov` writes, mapped for display the same way.
TEST(Viewer, DebugViewMatchesRenderAov) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is missing (scripts/setup.sh installs xvfb and xauth)";
  const auto dir = testDir();
  const std::string common = "builtin:cornell --primary raster --frames 2 --size 160x120";
  RunResult v =
      runUnderXvfb("view " + common + " --debug-view normal --hide-ui --screenshot " + (dir / "view.png").string());
  ASSERT_EQ(v.exitCode, 0) << v.output;
  RunResult h = runRayster("render " + common + " --aov normal -o " + (dir / "render.png").string());
  ASSERT_EQ(h.exitCode, 0) << h.output;
  auto viewed = readPng(dir / "view.png");
  auto rendered = readPng(dir / "render.normal.png");
  ASSERT_TRUE(viewed.ok() && rendered.ok());
  EXPECT_FALSE(rejectEmpty(*viewed, 160, 120).has_value());
  const ImageDiff d = compare(*rendered, *viewed, 2);
  EXPECT_GE(d.fractionWithinTolerance, 0.999) << "max difference " << d.maxChannelDiff;
  RunResult bad = runRayster("view " + common + " --debug-view nonsense");
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
}

// Memory exhaustion (injected) is drawn inside the window for three seconds, then the process exits
// with the documented code.
TEST(Viewer, FatalErrorIsShownInTheWindowBeforeExiting) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is missing (scripts/setup.sh installs xvfb and xauth)";
  const auto start = std::chrono::steady_clock::now();
  RunResult v =
      runUnderXvfb("view builtin:cornell --primary raster --frames 5 --size 160x120", "RAYSTER_VIEWER_FAIL_AT=oom:1");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(v.exitCode, 7) << v.output;
  EXPECT_NE(v.output.find("shown in the window: out of device memory"), std::string::npos) << v.output;
  EXPECT_EQ(v.output.find("validation error"), std::string::npos) << v.output;
  EXPECT_GE(seconds, 3.0);
}

TEST(Viewer, NoDisplayFailsCleanly) {
  RunResult r = runRayster("view builtin:cornell --frames 1", "DISPLAY= WAYLAND_DISPLAY=");
  EXPECT_EQ(r.exitCode, 4) << r.output;
  EXPECT_NE(r.output.find("xvfb-run"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace rayster::test
