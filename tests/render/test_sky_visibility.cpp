// Sky visibility (render/passes/rt_sky_visibility.cpp, --sky-visibility on): the pass added through
// the pass API in four files (docs/architecture.md §10). It is off by default and then records
// nothing; on, it traces and denoises an output that sees the open sky as 1 and the floor beside a
// wall as less, and it leaves the lit image as it was.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

class SkyVisibility : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testDir(); }

  // A white floor (8 × 8) and, with `wall`, a wall 2 high across its middle (both sides facing out).
  std::string scene(bool wall) {
    const std::string name = wall ? "wall" : "open";
    std::ofstream(dir_ / "white.mtl") << "newmtl white\nKd 0.8 0.8 0.8\nNs 0\nillum 2\n";
    std::ofstream obj(dir_ / (name + ".obj"));
    obj << "mtllib white.mtl\nusemtl white\nv -4 0 4\nv 4 0 4\nv 4 0 -4\nv -4 0 -4\nf 1 2 3 4\n";
    if (wall) obj << "v 0 0 -4\nv 0 2 -4\nv 0 2 4\nv 0 0 4\nf 5 6 7 8\nf 8 7 6 5\n";
    return (dir_ / (name + ".obj")).string();
  }

  static void expectImage(const ImageF& img) {
    ASSERT_EQ(img.width, 96);
    ASSERT_EQ(img.height, 64);
    for (float v : img.rgba) ASSERT_TRUE(std::isfinite(v));
  }

  std::filesystem::path dir_;
};

TEST_F(SkyVisibility, OffRecordsNothingOnTracesAndDenoisesIt) {
  const std::string out = (dir_ / "out.png").string();
  RunResult off = runRayster("render " + scene(true) + " --size 48x32 --frames 2 --timings -o " + out);
  ASSERT_EQ(off.exitCode, 0) << off.output;
  EXPECT_EQ(off.output.find("sky-visibility"), std::string::npos) << off.output;
  RunResult on =
      runRayster("render " + scene(true) + " --size 48x32 --frames 2 --timings --sky-visibility on -o " + out);
  ASSERT_EQ(on.exitCode, 0) << on.output;
  for (const char* pass : {"rt-sky-visibility", "sky-visibility-temporal", "sky-visibility-atrous-4"})
    EXPECT_NE(on.output.find(pass), std::string::npos) << pass << "\n" << on.output;
  // The switch is a setting like any other: on the command line's help, refused when misspelt.
  RunResult help = runRayster("render --help");
  EXPECT_NE(help.output.find("--sky-visibility"), std::string::npos) << help.output;
  RunResult bad = runRayster("render " + scene(true) + " --size 48x32 --frames 1 --sky-visibility maybe -o " + out);
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
}

TEST_F(SkyVisibility, OpenSkyIsOneAndAWallDarkensIt) {
  const std::string args = " --size 96x64 --frames 8 --taa off --sky-visibility on";
  const std::vector<std::string> aovs = {"sky-visibility-raw", "sky-visibility-denoised", "gbuffer-id"};
  // Raw one-ray samples are 0 or 1; a floor under the open sky sees it from everywhere.
  auto open = renderAovs(dir_, scene(false) + args, aovs);
  ASSERT_EQ(open.size(), 3u);
  expectImage(open["sky-visibility-raw"]);
  for (size_t i = 0; i < open["sky-visibility-raw"].rgba.size(); i += 4) {
    ASSERT_EQ(open["sky-visibility-raw"].rgba[i], 1.0f) << "pixel " << i / 4;
    ASSERT_NEAR(open["sky-visibility-denoised"].rgba[i], 1.0f, 1e-3f) << "pixel " << i / 4;
  }

  // Beside a wall the floor sees less sky: a wall h high blocks about (1 − d/√(d² + h²))/2 of the
  // cosine-weighted hemisphere at distance d (half at its foot, 15 % at d = h).
  auto walled = renderAovs(dir_, scene(true) + args, aovs);
  ASSERT_EQ(walled.size(), 3u);
  const ImageF& raw = walled["sky-visibility-raw"];
  const ImageF& denoised = walled["sky-visibility-denoised"];
  const ImageF& id = walled["gbuffer-id"];
  expectImage(raw);
  expectImage(denoised);
  size_t geometry = 0, zeros = 0, shaded = 0;
  double rawSum = 0, denoisedSum = 0;
  for (size_t i = 0; i < raw.rgba.size(); i += 4) {
    const float r = raw.rgba[i], d = denoised.rgba[i];
    ASSERT_TRUE(r == 0.0f || r == 1.0f) << "raw samples are visibilities: " << r;
    ASSERT_GE(d, 0.0f);
    ASSERT_LE(d, 1.0f + 1e-3f);
    if (id.rgba[i] > 6.0e4f) continue;  // the background (kBackgroundId, clamped to a finite half float)
    ++geometry;
    zeros += r == 0.0f ? 1 : 0;
    shaded += d < 0.9f ? 1 : 0;
    rawSum += r;
    denoisedSum += d;
  }
  ASSERT_GT(geometry, size_t(raw.rgba.size() / 4 / 20)) << "the floor fills part of the view";
  EXPECT_GT(zeros, geometry / 50) << "the wall blocks rays";
  EXPECT_GT(shaded, geometry / 20) << "the floor near the wall sees less sky";
  EXPECT_LT(denoisedSum / double(geometry), 0.95) << "the wall darkens the mean";
  EXPECT_NEAR(denoisedSum / double(geometry), rawSum / double(geometry), 0.1) << "denoising keeps the mean";
}

TEST_F(SkyVisibility, LeavesTheLitImageUnchanged) {
  // One G-buffer producer for both (auto picks by timing, which differs from run to run).
  const std::string args = scene(true) + " --size 48x32 --frames 3 --primary raster";
  RunResult off = runRayster("render " + args + " -o " + (dir_ / "off.exr").string());
  RunResult on = runRayster("render " + args + " --sky-visibility on -o " + (dir_ / "on.exr").string());
  ASSERT_EQ(off.exitCode, 0) << off.output;
  ASSERT_EQ(on.exitCode, 0) << on.output;
  auto a = readExr(dir_ / "off.exr");
  auto b = readExr(dir_ / "on.exr");
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a->rgba.size(), size_t(48 * 32 * 4));
  EXPECT_GT(*std::max_element(a->rgba.begin(), a->rgba.end()), 0.0f) << "a lit image, not black";
  EXPECT_EQ(a->rgba, b->rgba);
}

}  // namespace
}  // namespace rayster::test
