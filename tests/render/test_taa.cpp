// Temporal anti-aliasing end to end (docs/techniques.md §18), through the real binary with validation:
// a static view converges to a supersampled render, and a camera cut leaves no trace of the old view.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "render/tonemap_curves.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kW = 160, kH = 120;

// Renders with `args` and returns the linear HDR image (the TAA output when TAA is on).
ImageF renderHdr(const std::filesystem::path& dir, const std::string& name, const std::string& args, int w, int h) {
  const auto exr = dir / (name + ".exr");
  renderOk(dir, name, args + " --hdr " + exr.string(), w, h);
  auto img = readExr(exr);
  EXPECT_TRUE(img.ok());
  return img.ok() ? std::move(img).value() : ImageF::make(w, h);
}

// Box filter: the mean of each factor × factor block (a supersampled pixel).
ImageF downsample(const ImageF& src, int factor) {
  ImageF out = ImageF::make(src.width / factor, src.height / factor);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 4; ++c) {
        float sum = 0;
        for (int j = 0; j < factor; ++j)
          for (int i = 0; i < factor; ++i) sum += src.pixel(x * factor + i, y * factor + j)[c];
        out.pixel(x, y)[c] = sum / float(factor * factor);
      }
  return out;
}

// What a viewer sees, in 1/255 steps: the default tonemap (ACES, EV 0) and sRGB, without dither.
ImageF display(const ImageF& hdr) {
  ImageF out = ImageF::make(hdr.width, hdr.height);
  for (int y = 0; y < hdr.height; ++y)
    for (int x = 0; x < hdr.width; ++x) {
      const float* p = hdr.pixel(x, y);
      const glm::vec3 t = render::applyTonemapper(render::Tonemapper::Aces, {p[0], p[1], p[2]});
      for (int c = 0; c < 3; ++c) out.pixel(x, y)[c] = 255.0f * linearToSrgb(t[c]);
    }
  return out;
}

float maxChannelDiff(const ImageF& a, const ImageF& b, int x, int y) {
  float d = 0;
  for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.pixel(x, y)[c] - b.pixel(x, y)[c]));
  return d;
}

struct Errors {
  double edgeRms = 0, allRms = 0, fractionWithin = 0;
};

// Errors against `ref`; edges are pixels whose 3×3 neighbourhood in `ref` spans more than 24/255.
Errors errorsAgainst(const ImageF& ref, const ImageF& img, float tolerance) {
  double edgeSum = 0, allSum = 0;
  size_t edges = 0, within = 0, all = 0;
  for (int y = 1; y + 1 < ref.height; ++y)
    for (int x = 1; x + 1 < ref.width; ++x) {
      float lo = 1e9f, hi = -1e9f;
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
          const float g = ref.pixel(x + i, y + j)[1];
          lo = std::min(lo, g), hi = std::max(hi, g);
        }
      const double d = maxChannelDiff(ref, img, x, y);
      allSum += d * d;
      ++all;
      within += d <= tolerance;
      if (hi - lo > 24.0f) edgeSum += d * d, ++edges;
    }
  return {std::sqrt(edgeSum / std::max<size_t>(edges, 1)), std::sqrt(allSum / all), double(within) / double(all)};
}

TEST(Taa, StaticViewConvergesToSupersampled) {
  auto dir = testDir();
  // Indirect light off: its 1-spp sparkle is noise, not aliasing, and no filter here removes it.
  const std::string scene = "builtin:cornell --primary raster --seed 2 --indirect off ";
  // The reference: 4×4 pixel centres per pixel × 4 frames. It costs most of the test, and its own
  // noise hardly shows: with 8 frames the errors below were edge RMS 5.88 vs 13.10, all RMS 2.29 vs
  // 4.88, within 6/255 0.979 vs 0.967; with 4 frames 5.92 vs 13.12, 2.35 vs 4.90, 0.977 vs 0.966.
  const ImageF ref = display(downsample(renderHdr(dir, "ref4x", scene + "--frames 4 --taa off", kW * 4, kH * 4), 4));
  const ImageF taa = display(renderHdr(dir, "taa", scene + "--frames 32 --taa on", kW, kH));
  const ImageF plain = display(renderHdr(dir, "plain", scene + "--frames 32 --taa off", kW, kH));
  const Errors withTaa = errorsAgainst(ref, taa, 6.0f), without = errorsAgainst(ref, plain, 6.0f);
  std::printf("edge RMS: TAA %.2f, no TAA %.2f; all RMS: TAA %.2f, no TAA %.2f; within 6/255: %.4f, %.4f\n",
              withTaa.edgeRms, without.edgeRms, withTaa.allRms, without.allRms, withTaa.fractionWithin,
              without.fractionWithin);
  // Measured on lavapipe: edge RMS 5.9 with TAA, 13.1 without. What remains is the 0.1/0.9
  // exponential average weighting the 16 jitter positions unevenly, and the 1/(1 + L) weights
  // biasing pixels that partly cover the light.
  EXPECT_LT(withTaa.edgeRms, 0.6 * without.edgeRms) << "jittered TAA must anti-alias the edges";
  EXPECT_LT(withTaa.edgeRms, 8.0);
  EXPECT_LT(withTaa.allRms, 0.6 * without.allRms);
  EXPECT_GT(withTaa.fractionWithin, without.fractionWithin);
}

// A scene file over the Cornell box whose camera path holds `first`, then jumps to `second`.
std::filesystem::path writeCutScene(const std::filesystem::path& dir, const std::string& name, const std::string& first,
                                    const std::string& second) {
  const auto path = dir / (name + ".json");
  const std::string target = "[2.78, 2.73, 2.8]";
  std::ofstream(path) << R"({"models": [{"path": "builtin:cornell"}],
  "cameras": [{"name": "cam", "position": [2.78, 2.73, -8], "target": [2.78, 2.73, 0], "yfov": 39.3, "znear": 0.1, "zfar": 30}],
  "cameraPath": [
    {"time": 0, "position": )" +
                             first + R"(, "target": )" + target + R"(},
    {"time": 0.5, "position": )" +
                             first + R"(, "target": )" + target + R"(},
    {"time": 0.501, "position": )" +
                             second + R"(, "target": )" + target + R"(},
    {"time": 100, "position": )" +
                             second + R"(, "target": )" + target + R"(}
  ]})";
  return path;
}

TEST(Taa, CameraCutLeavesNoTraceOfTheOldView) {
  auto dir = testDir();
  const std::string oldView = "[0.6, 4.6, -3]", newView = "[4.6, 1.2, -4]";
  // At 10 fps frame 5 is the last of the old view and frame 6 (the 7th) the first after the cut.
  // Indirect light off (as it was by default for scene files when this was written): one frame of it
  // after the cut is noisier than seven, which is not what this test is about.
  const std::string args = " --camera-path --path-fps 10 --frames 7 --primary raster --taa on --seed 4 --indirect off";
  const ImageF cut =
      display(renderHdr(dir, "cut", writeCutScene(dir, "cut", oldView, newView).string() + args, kW, kH));
  const ImageF alone =
      display(renderHdr(dir, "alone", writeCutScene(dir, "alone", newView, newView).string() + args, kW, kH));
  const ImageF old =
      display(renderHdr(dir, "old", writeCutScene(dir, "old", oldView, oldView).string() + args, kW, kH));
  const Errors vsAlone = errorsAgainst(alone, cut, 12.0f), oldVsAlone = errorsAgainst(alone, old, 12.0f);
  std::printf("cut vs new view alone: RMS %.2f, within 12/255 %.4f; old vs new view: RMS %.2f\n", vsAlone.allRms,
              vsAlone.fractionWithin, oldVsAlone.allRms);
  ASSERT_GT(oldVsAlone.allRms, 20.0) << "the two views must differ for the test to mean anything";
  // The frame after the cut differs from the new view alone only by sub-pixel jitter and noise.
  EXPECT_LT(vsAlone.allRms, 0.15 * oldVsAlone.allRms);
  EXPECT_GE(vsAlone.fractionWithin, 0.97);
}

TEST(Taa, NeutralTonemapIsSelectable) {
  auto dir = testDir();
  const std::string scene = "builtin:cornell --primary raster --frames 2 --seed 5 ";
  Image8 aces = renderOk(dir, "aces", scene + "--tonemap aces", kW, kH);
  Image8 neutral = renderOk(dir, "neutral", scene + "--tonemap neutral", kW, kH);
  Image8 fallback = renderOk(dir, "default", scene, kW, kH);
  EXPECT_EQ(aces.rgba, fallback.rgba) << "aces is the default";
  EXPECT_NE(aces.rgba, neutral.rgba);
  // Neutral keeps mid-tones brighter than ACES (base colours minus 0.04 below 0.76).
  long sumAces = 0, sumNeutral = 0;
  for (size_t i = 0; i < aces.rgba.size(); i += 4) sumAces += aces.rgba[i + 1], sumNeutral += neutral.rgba[i + 1];
  EXPECT_GT(sumNeutral, sumAces);
}

TEST(Taa, RejectsBadValues) {
  auto dir = testDir();
  for (const char* bad : {"--taa maybe", "--tonemap reinhard", "--tonemap none"}) {
    RunResult r = runRayster(std::string("render --size 32x24 --frames 1 ") + bad + " -o " + (dir / "x.png").string());
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
  }
}

}  // namespace
}  // namespace rayster::test
