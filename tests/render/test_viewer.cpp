// `rayster view` under Xvfb on lavapipe: the window renders the same frame graph as the headless
// path, so a scripted run's screenshot (panel hidden) must match `rayster render` of the same
// scene, camera, size and frame count. TAA stays on: both runs use the same jitter sequence and
// seeds, so the comparison tolerance only covers the blit (exact for same-size copies).
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kWidth = 160, kHeight = 120;
// The screen must be 24-bit: Xvfb's default 8-bit visual has no Vulkan surface format.
const std::string kXvfb = "xvfb-run -a -s '-screen 0 1024x768x24' ";

bool haveXvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

RunResult runUnderXvfb(const std::string& args) {
  std::string cmd = kXvfb + "env XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} RAYSTER_VALIDATION=1 " +
                    std::string(RAYSTER_BINARY) + " " + args + " 2>&1";
  RunResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) r.output.append(buf, n);
  int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

TEST(Viewer, ScreenshotMatchesHeadlessRender) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is missing (scripts/setup.sh installs xvfb and xauth)";
  const auto dir = testDir();
  const std::string common = "builtin:cornell --primary raster --frames 4 --size " + std::to_string(kWidth) + "x" +
                             std::to_string(kHeight);
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
  RunResult v = runUnderXvfb("view builtin:spheres --frames 6 --size 160x120 --resize-at 2:200x150 "
                             "--resize-at 4:128x96 --screenshot " + shot.string());
  ASSERT_EQ(v.exitCode, 0) << v.output;
  EXPECT_EQ(v.output.find("validation error"), std::string::npos) << v.output;
  auto img = readPng(shot);
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img->width, 128);
  EXPECT_EQ(img->height, 96);
}

TEST(Viewer, NoDisplayFailsCleanly) {
  RunResult r = runRayster("view builtin:cornell --frames 1", "DISPLAY= WAYLAND_DISPLAY=");
  EXPECT_EQ(r.exitCode, 4) << r.output;
  EXPECT_NE(r.output.find("xvfb-run"), std::string::npos) << r.output;
}

} // namespace
} // namespace rayster::test
