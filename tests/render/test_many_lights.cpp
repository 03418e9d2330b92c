// Many lights (docs/techniques.md §10): one light per pixel picked by importance, divided by the pick's
// probability, converges to the image that shades every light with its own shadow layer — for
// exact selection (≤ 16 lights) and for resampled uniform candidates (more lights).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "core/metrics.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kW = 64, kH = 48;

struct TestLight {
  const char* type;
  float x, y, z, intensity, radius;
};

// A floor with a box on it, lit by `lights` (each repeated `copies` times at 1/copies intensity,
// so the image must not depend on `copies`).
std::filesystem::path writeScene(const std::filesystem::path& dir, const std::vector<TestLight>& lights, int copies) {
  std::ofstream(dir / "room.obj") << "v -4 0 -4\nv 4 0 -4\nv 4 0 4\nv -4 0 4\n"
                                     "v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0.5 0 0.5\nv -0.5 0 0.5\n"
                                     "v -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\n"
                                     "f 1 3 2\nf 1 4 3\n"
                                     "f 9 11 10\nf 9 12 11\nf 5 6 10\nf 5 10 9\nf 6 7 11\nf 6 11 10\n"
                                     "f 7 8 12\nf 7 12 11\nf 8 5 9\nf 8 9 12\n";
  std::ostringstream l;
  bool first = true;
  for (const TestLight& t : lights)
    for (int c = 0; c < copies; ++c) {
      l << (first ? "" : ",") << R"({"type": ")" << t.type << R"(", "position": [)" << t.x << "," << t.y << "," << t.z
        << R"(], "direction": [0, -1, 0.2], "intensity": )" << t.intensity / copies
        << (std::string(t.type) == "point" ? std::string(R"(, "radius": )") + std::to_string(t.radius) : "")
        << (std::string(t.type) == "spot" ? R"(, "innerConeAngle": 20, "outerConeAngle": 40)" : "") << "}";
      first = false;
    }
  std::ofstream(dir / "scene.json") << R"({"models": [{"path": "room.obj"}], "lights": [)" << l.str()
                                    << R"(], "cameras": [{"position": [0, 4, 5], "target": [0, 0, 0], "yfov": 50}]})";
  return dir / "scene.json";
}

ImageF renderHdr(const std::filesystem::path& dir, const std::string& name, const std::string& args) {
  auto png = dir / (name + ".png"), exr = dir / (name + ".exr");
  RunResult r = runRayster("render " + args + " --primary raster --size " + std::to_string(kW) + "x" +
                           std::to_string(kH) + " -o " + png.string() + " --hdr " + exr.string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  auto img = readExr(exr);
  EXPECT_TRUE(img.ok()) << r.output;
  if (!img.ok()) return {};
  auto ldr = readPng(png);
  EXPECT_TRUE(ldr.ok());
  if (ldr.ok()) {
    EXPECT_FALSE(rejectEmpty(*ldr, kW, kH).has_value()) << name;
  }
  return std::move(img).value();
}

const std::vector<TestLight> kEight = {{"point", -2, 3, 1, 12, 0.3f},     {"point", 2, 2.5f, -1, 6, 0.1f},
                                       {"point", 0, 4, -2, 20, 0.0f},     {"spot", 1, 3, 2, 30, 0},
                                       {"point", -1, 1.5f, -2, 2, 0.2f},  {"point", 3, 1, 2, 4, 0.4f},
                                       {"directional", 0, 0, 0, 0.6f, 0}, {"point", -3, 2, -3, 8, 0.5f}};

// Frames: 32 for the image with every light shadowed, 64 for one picked light per pixel. Measured
// (lavapipe): mean ratios within 0.001 of 1 and relative MSE 0.0004-0.0016, as with 64 and 256
// frames (0.0003-0.0014): the denoised images hold far less noise than the budgets below, which
// catch a wrong pick probability (off by ~count×) or resampling weights (a bias of a few percent).
TEST(ManyLights, ImportanceSelectionConvergesToEveryLightShaded) {
  auto dir = testDir();
  for (size_t count : {size_t(2), size_t(8)}) {
    std::vector<TestLight> lights(kEight.begin(), kEight.begin() + count);
    auto scene = writeScene(dir, lights, 1);
    ImageF every = renderHdr(dir, "every", scene.string() + " --frames 32 --shadow-lights 8");
    ImageF picked = renderHdr(dir, "picked", scene.string() + " --frames 64 --shadow-lights 0");
    const double mEvery = meanLuminance(every), mPicked = meanLuminance(picked);
    std::printf("[many lights] %zu lights: mean ratio %.4f, relMSE %.4f\n", count, mPicked / mEvery,
                relMse(every, picked));
    // Unbiased: the means agree; forgetting to divide by the pick probability is off by ~count×.
    EXPECT_NEAR(mPicked / mEvery, 1.0, 0.03) << count << " lights";
    EXPECT_LT(relMse(every, picked), 0.02) << count << " lights";
  }
}

TEST(ManyLights, ResampledCandidatesStayUnbiasedBeyondSixteenLights) {
  // 8 lights, each split into 3 copies of a third of its intensity: 24 lights, more than the 16
  // candidates, so the uniform-candidate resampling path runs; the image must not change.
  auto dir = testDir();
  ImageF every = renderHdr(dir, "every", writeScene(dir, kEight, 1).string() + " --frames 32 --shadow-lights 8");
  ImageF picked = renderHdr(dir, "picked", writeScene(dir, kEight, 3).string() + " --frames 64");
  std::printf("[many lights] 24 lights: mean ratio %.4f, relMSE %.4f\n", meanLuminance(picked) / meanLuminance(every),
              relMse(every, picked));
  EXPECT_NEAR(meanLuminance(picked) / meanLuminance(every), 1.0, 0.03);
  EXPECT_LT(relMse(every, picked), 0.03);
}

}  // namespace
}  // namespace rayster::test
