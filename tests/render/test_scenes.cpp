// Goldens and behaviour checks for the built-in scenes, real glTF files and scene files, rendered
// through the real binary with validation on.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/render/fixtures.h"
#include "tests/render/golden.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kW = 160, kH = 120;
const std::filesystem::path kAssimpGltf2 = "/usr/share/assimp/models/glTF2";

Image8 renderScene(const std::filesystem::path& dir, const std::string& name, const std::string& scene,
                   const std::string& extra = "") {
  // The goldens were made at the unit exposure (auto exposure has tests of its own: test_exposure.cpp).
  return renderOk(dir, name, scene + " --primary raster --frames 8 --seed 1 --exposure 0 " + extra, kW, kH);
}

// builtin:whitted's golden: WhittedRun.FrameMatchesGolden (tests/render/test_effect_goldens.cpp),
// which shares its render with the per-stage goldens.

TEST(Scenes, SpheresMatchesGolden) {
  auto dir = testDir();
  expectMatchesGolden(renderScene(dir, "spheres", "builtin:spheres"), "spheres-160x120", dir);
}

TEST(Scenes, SpheresImpostorAgreesWithIntersectionShader) {
  // Raster impostors and the intersection shader solve the same quadric for the same rays.
  auto dir = testDir();
  Image8 raster = renderOk(dir, "raster", "builtin:spheres --primary raster --frames 4 --seed 2", kW, kH);
  Image8 traced = renderOk(dir, "traced", "builtin:spheres --primary rt --frames 4 --seed 2", kW, kH);
  ImageDiff diff = compare(raster, traced, 2);
  if (diff.fractionWithinTolerance < 0.99) (void)writePng(dir / "diff.png", diff.heatmap);
  EXPECT_GE(diff.fractionWithinTolerance, 0.99) << "max diff " << diff.maxChannelDiff;
}

TEST(Scenes, InstancesRenders) {
  // A validation-clean run and a sane image (renderOk: not blank, not uniform, finite). Two frames:
  // the second reads every history, and later frames of a static view do what it does.
  auto dir = testDir();
  renderOk(dir, "instances", "builtin:instances:16 --primary raster --frames 2 --seed 1", kW, kH);
}

TEST(Scenes, BoxTexturedMatchesGolden) {
  auto file = kAssimpGltf2 / "BoxTextured-glTF" / "BoxTextured.gltf";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "assimp-testmodels is not installed";
  auto dir = testDir();
  expectMatchesGolden(renderScene(dir, "box", file.string()), "box-textured-160x120", dir);
}

TEST(Scenes, TextureTransformMatchesGolden) {
  auto file = kAssimpGltf2 / "textureTransform" / "TextureTransformTest.gltf";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "assimp-testmodels is not installed";
  auto dir = testDir();
  expectMatchesGolden(renderScene(dir, "transform", file.string()), "texture-transform-160x120", dir);
}

TEST(Scenes, AlphaMaskCutsHolesAndShadows) {
  auto dir = testDir();
  auto file = writeAlphaMaskGltf(dir);
  Image8 img = renderScene(dir, "alpha", file.string());
  expectMatchesGolden(img, "alpha-mask-160x120", dir);
}

TEST(Scenes, AlphaMaskRasterAgreesWithAnyHit) {
  // discard in the raster G-buffer and ignoreIntersection in the any-hit shader cut the same holes.
  auto dir = testDir();
  auto file = writeAlphaMaskGltf(dir).string();
  Image8 raster = renderOk(dir, "raster", file + " --primary raster --frames 4 --seed 2", kW, kH);
  Image8 traced = renderOk(dir, "traced", file + " --primary rt --frames 4 --seed 2", kW, kH);
  ImageDiff diff = compare(raster, traced, 2);
  if (diff.fractionWithinTolerance < 0.99) (void)writePng(dir / "diff.png", diff.heatmap);
  EXPECT_GE(diff.fractionWithinTolerance, 0.99) << "max diff " << diff.maxChannelDiff;
}

TEST(Scenes, SceneFileWithHdrEnvironmentMatchesGolden) {
  auto dir = testDir();
  auto file = writeEnvironmentSceneFile(dir);
  Image8 img = renderScene(dir, "env", file.string(), "--camera wide");
  expectMatchesGolden(img, "scene-file-env-160x120", dir);
  // The sky above the horizon is brighter and bluer than black: the map is really sampled.
  const uint8_t* sky = img.pixel(kW / 2, 2);
  EXPECT_GT(sky[2], 60) << "sky pixel should show the environment map";
}

TEST(Scenes, CameraPathEndsAtItsLastKey) {
  // A 1-second path from the front to the side, played at 20 fps for 21 frames, ends exactly where
  // a static camera at the last key looks: the two images agree up to shadow noise.
  auto dir = testDir();
  writeAlphaMaskGltf(dir);
  auto file = dir / "path.json";
  std::ofstream(file) << R"({
  "models": [{"path": "alpha-mask.gltf"}],
  "cameras": [{"name": "end", "position": [4, 2, 3], "target": [0, 1, 0], "yfov": 50}],
  "cameraPath": [{"time": 0, "position": [0, 2, 6], "target": [0, 1, 0]},
                 {"time": 1, "position": [4, 2, 3], "target": [0, 1, 0]}]
})";
  Image8 flown =
      renderOk(dir, "flown", file.string() + " --camera end --camera-path --path-fps 20 --frames 21", kW, kH);
  Image8 still = renderOk(dir, "still", file.string() + " --camera end --frames 1", kW, kH);
  Image8 start = renderOk(dir, "start", file.string() + " --camera end --camera-path --frames 1", kW, kH);
  EXPECT_GT(compare(still, flown, 0).psnr, 25.0) << "the path's last frame should show the last key's view";
  EXPECT_LT(compare(still, start, 0).psnr, 20.0) << "the path's first frame should show another view";
}

TEST(Scenes, CameraPathNeedsAPath) {
  auto dir = testDir();
  RunResult r = runRayster("render builtin:cornell --camera-path --size 32x24 -o " + (dir / "a.png").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("no camera path"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace rayster::test
