// Highlights on traced surfaces of lights no ray can hit. The hybrid traces the specular light of
// mirrors, glossy metals and glass; a light with no visible shape (a glTF punctual light, a scene
// file's light) is never hit by those rays, so lighting adds its highlight for the traced share
// (lib/shading.glsl, kLightVisibleShape). Without it a gold sphere under a point light lost its
// highlight (the Blender product shot's key light: −10 % of the frame).
#include <gtest/gtest.h>

#include <fstream>

#include "core/image_io.h"
#include "tests/render/golden.h"
#include "tests/render/run_rayster.h"
#include "tests/render/user_scenes.h"

namespace rayster::test {
namespace {

constexpr int kW = 64, kH = 48;

// A glossy gold floor (roughness 0.3: traced, one GGX sample per pixel) and a rough grey one beside
// it, a point light without a shape above, no environment: what the metal shows is the light's highlight.
std::filesystem::path writeGlossyFloorGltf(const std::filesystem::path& dir) {
  Doc d;
  addPrimitive(d, 0, {-3, 0, 2, 0, 0, 2, 0, 0, -2, -3, 0, -2}, {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 3},
               0);
  addPrimitive(d, 0, {0, 0, 2, 3, 0, 2, 3, 0, -2, 0, 0, -2}, {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 3},
               1);
  d.j["materials"] = {pbr({1.0f, 0.78f, 0.34f}, 1.0f, 0.3f), pbr({0.5f, 0.5f, 0.5f}, 0.0f, 0.9f)};
  d.j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.05}, {"zfar", 100.0}}}}};
  addLights(d, {{{"type", "point"}, {"intensity", 20.0}}});
  d.j["nodes"] = {{{"mesh", 0}, {"name", "floors"}},
                  cameraNode({0.0f, 1.5f, 3.0f}, {0.0f, 0.0f, -0.5f}, 0),
                  {{"translation", {0.0, 1.2, -1.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}};
  d.j["scenes"] = {{{"nodes", {0, 1, 2}}}};
  d.j["scene"] = 0;
  auto path = dir / "glossy-floor.gltf";
  std::ofstream(path) << d.gltf();
  return path;
}

// The linear HDR image of one render (no TAA: its jitter is not what this compares).
ImageF renderHdr(const std::filesystem::path& dir, const std::string& name, const std::filesystem::path& scene,
                 int frames, const std::string& extra) {
  const auto exr = dir / (name + ".exr");
  RunResult r = runRayster("render " + scene.string() + " --size " + std::to_string(kW) + "x" + std::to_string(kH) +
                           " --frames " + std::to_string(frames) + " --seed 3 --taa off --hdr " + exr.string() +
                           " -o " + (dir / (name + ".png")).string() + " " + extra);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  auto hdr = readExr(exr);
  if (!hdr.ok()) {
    ADD_FAILURE() << hdr.error().message;
    return {};
  }
  EXPECT_FALSE(rejectEmpty(*hdr, kW, kH).has_value()) << name << ": " << rejectEmpty(*hdr, kW, kH).value_or("");
  return std::move(hdr).value();
}

double meanLuminance(const ImageF& img, int x0, int x1) {
  double sum = 0;
  int n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = x0; x < x1; ++x) {
      const float* p = img.pixel(x, y);
      sum += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
      ++n;
    }
  return sum / n;
}

TEST(Highlights, AShapelessPointLightsHighlightOnGlossyMetalMatchesThePathTracer) {
  const auto dir = testDir();
  const auto scene = writeGlossyFloorGltf(dir);
  const std::string common = "--exposure 0 --primary raster";
  const ImageF hybrid = renderHdr(dir, "hybrid", scene, 16, common);
  const ImageF reference = renderHdr(dir, "reference", scene, 256, common + " --mode pathtrace --max-depth 8");
  ASSERT_FALSE(hybrid.rgba.empty() || reference.rgba.empty());
  // The gold half (left) and the rough grey half (right, untraced: its highlight was always there).
  const double gold = meanLuminance(hybrid, 0, kW / 2), goldRef = meanLuminance(reference, 0, kW / 2);
  const double grey = meanLuminance(hybrid, kW / 2, kW), greyRef = meanLuminance(reference, kW / 2, kW);
  std::printf("[highlights] gold hybrid %.4f reference %.4f; grey hybrid %.4f reference %.4f\n", gold, goldRef, grey,
              greyRef);
  ASSERT_GT(goldRef, 0.01) << "the reference shows the gold's highlight";
  EXPECT_NEAR(gold / goldRef, 1.0, 0.1) << "the gold floor's highlight of a light no traced ray can hit";
  EXPECT_NEAR(grey / greyRef, 1.0, 0.1) << "the rough floor beside it";
}

}  // namespace
}  // namespace rayster::test
