// Motion vectors (docs/techniques.md §2): exactly zero for a static camera, the analytic value for a
// known camera pan, from both G-buffer producers.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kW = 64, kH = 48;
constexpr float kDistance = 5.0f, kPan = 0.3f, kYFovDeg = 40.0f;

// A 40 m wall at z = 0 facing +Z; the camera looks at it from z = kDistance and, along its path,
// slides kPan metres along +X in one second (position and target together: a pure pan).
std::filesystem::path writePanScene(const std::filesystem::path& dir) {
  std::ofstream(dir / "wall.obj") << "v -20 -20 0\nv 20 -20 0\nv 20 20 0\nv -20 20 0\nvn 0 0 1\n"
                                     "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n";
  std::ofstream(dir / "pan.json") << R"({"models": [{"path": "wall.obj"}],
    "lights": [{"type": "point", "position": [0, 0, 4], "intensity": 20}],
    "cameras": [{"position": [0, 0, 5], "target": [0, 0, 0], "yfov": 40, "znear": 0.1, "zfar": 100}],
    "cameraPath": [{"time": 0, "position": [0, 0, 5], "target": [0, 0, 0]},
                   {"time": 1, "position": [0.3, 0, 5], "target": [0.3, 0, 0]}]})";
  return dir / "pan.json";
}

ImageF renderMotion(const std::filesystem::path& dir, const std::string& name, const std::string& args) {
  RunResult r = runRayster("render " + args + " --aov motion --size " + std::to_string(kW) + "x" + std::to_string(kH) +
                           " -o " + (dir / (name + ".png")).string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  auto img = readExr(dir / (name + ".motion.exr"));
  EXPECT_TRUE(img.ok()) << r.output;
  if (!img.ok()) return {};
  EXPECT_EQ(img->width, kW);
  EXPECT_EQ(img->height, kH);
  return std::move(img).value();
}

class Motion : public ::testing::TestWithParam<const char*> {};

TEST_P(Motion, StaticCameraHasExactlyZeroMotion) {
  auto dir = testDir();
  ImageF mv = renderMotion(dir, "static", "builtin:whitted --frames 3 --primary " + std::string(GetParam()));
  for (size_t i = 0; i < size_t(kW) * kH; ++i) {
    ASSERT_EQ(mv.rgba[i * 4 + 0], 0.0f) << "pixel " << i;
    ASSERT_EQ(mv.rgba[i * 4 + 1], 0.0f) << "pixel " << i;
  }
}

TEST_P(Motion, CameraPanMatchesTheAnalyticMotion) {
  auto dir = testDir();
  auto scene = writePanScene(dir);
  // Frame 1 at 1 fps is one second along the path: the camera has moved kPan.
  ImageF mv = renderMotion(
      dir, "pan", scene.string() + " --camera-path --path-fps 1 --frames 2 --primary " + std::string(GetParam()));
  // A point of the wall moves left on screen: uvNow − uvBefore = −pan / (visible width at distance).
  const float visibleWidth = 2.0f * kDistance * std::tan(kYFovDeg * 0.5f * 3.14159265f / 180.0f) * kW / kH;
  const float expected = -kPan / visibleWidth;
  int checked = 0;
  for (size_t i = 0; i < size_t(kW) * kH; ++i) {
    // Half floats: about 3 significant digits.
    ASSERT_NEAR(mv.rgba[i * 4 + 0], expected, 2e-4) << "pixel " << i;
    ASSERT_NEAR(mv.rgba[i * 4 + 1], 0.0f, 2e-4) << "pixel " << i;
    ++checked;
  }
  EXPECT_EQ(checked, kW * kH);
  EXPECT_NE(expected, 0.0f);
}

INSTANTIATE_TEST_SUITE_P(Producers, Motion, ::testing::Values("raster", "rt"));

}  // namespace
}  // namespace rayster::test
