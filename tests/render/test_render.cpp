// End-to-end renders on lavapipe through the real binary, validation on: goldens, determinism,
// the two G-buffer producers, and the error paths a user meets.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <map>

#include <gtest/gtest.h>

#include "tests/render/fixtures.h"
#include "tests/render/golden.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kW = 160, kH = 120;

TEST(Render, CornellMatchesGolden) {
  auto dir = testDir();
  Image8 img = renderOk(dir, "cornell", "builtin:cornell --primary raster --frames 16 --seed 1 --exposure 0", kW, kH);
  expectMatchesGolden(img, "cornell-160x120", dir);
}

TEST(Render, CornellLooksLikeACornellBox) {
  // Independent of the golden: the red wall is on the left, the green on the right, the light is
  // the brightest thing near the top, and the floor under the light is lit.
  auto dir = testDir();
  Image8 img = renderOk(dir, "cornell", "builtin:cornell --primary raster --frames 8", kW, kH);
  const uint8_t* left = img.pixel(kW * 2 / 10, kH / 2);
  const uint8_t* right = img.pixel(kW * 8 / 10, kH / 2);
  EXPECT_GT(left[0], 2 * left[1] + 20) << "left wall should be red";
  // Green dominates but is not pure: white light bounced off the floor, ceiling and back wall
  // desaturates it (the path-traced reference's right wall has G/R = 1.56 there at its auto exposure).
  EXPECT_GT(10 * right[1], 13 * right[0]) << "right wall should be green";
  EXPECT_GT(right[1], right[2]) << "right wall should be green";
  const uint8_t* light = img.pixel(kW / 2, kH * 2 / 10);
  EXPECT_GT(light[0] + light[1] + light[2], 3 * 230) << "the sphere light should be near white";
}

TEST(Render, SameSeedSameImageOtherSeedOtherImage) {
  auto dir = testDir();
  const std::string args = "builtin:cornell --primary raster --frames 2";
  Image8 a = renderOk(dir, "a", args + " --seed 7", kW, kH);
  Image8 b = renderOk(dir, "b", args + " --seed 7", kW, kH);
  Image8 c = renderOk(dir, "c", args + " --seed 8", kW, kH);
  EXPECT_EQ(a.rgba, b.rgba) << "the same seed must give the identical image";
  EXPECT_NE(a.rgba, c.rgba) << "another seed must change the soft-shadow noise";
}

TEST(Render, RasterAndTracedGBufferAgree) {
  auto dir = testDir();
  Image8 raster = renderOk(dir, "raster", "builtin:cornell --primary raster --frames 4 --seed 3", kW, kH);
  Image8 traced = renderOk(dir, "traced", "builtin:cornell --primary rt --frames 4 --seed 3", kW, kH);
  ImageDiff diff = compare(raster, traced, 2);
  if (diff.fractionWithinTolerance < 0.995) (void)writePng(dir / "diff.png", diff.heatmap);
  // Both sample pixel centres with one projection; only silhouette pixels may differ.
  EXPECT_GE(diff.fractionWithinTolerance, 0.995) << "max diff " << diff.maxChannelDiff;
}

TEST(Render, TracedGBufferSamplesTheMipsTheRasteriserPicks) {
  // Ray cones (shaders/lib/ray_cone.glsl): the traced primaries sample the marble floor's texture at
  // the LOD the rasteriser's derivatives choose, so the two G-buffers of the default scene agree far
  // past 8-bit noise. Sampling mip 0 at every ray hit, as before, gave 31 dB on the albedo.
  auto dir = testDir();
  const std::string args = "builtin:whitted --size 160x120 --frames 1 --taa off --exposure 0 --aov albedo";
  std::map<std::string, ImageF> albedo, lit;
  for (const char* p : {"raster", "rt"}) {
    const auto out = dir / (std::string(p) + ".exr");
    RunResult r = runRayster("render " + args + " --primary " + p + " -o " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    auto a = readExr(dir / (std::string(p) + ".albedo.exr"));
    auto l = readExr(out);
    ASSERT_TRUE(a.ok() && l.ok()) << p;
    EXPECT_FALSE(rejectEmpty(*a, 160, 120).has_value()) << p;
    EXPECT_FALSE(rejectEmpty(*l, 160, 120).has_value()) << p;
    albedo[p] = std::move(*a);
    lit[p] = std::move(*l);
  }
  const double albedoPsnr = psnr(albedo["raster"], albedo["rt"]), litPsnr = psnr(lit["raster"], lit["rt"]);
  std::printf("[ray cones] raster vs traced G-buffer albedo %.1f dB, lit frame %.1f dB\n", albedoPsnr, litPsnr);
  EXPECT_GE(albedoPsnr, 45.0);
  EXPECT_GE(litPsnr, 45.0);
}

TEST(Render, AutoPrimaryReportsItsChoice) {
  auto dir = testDir();
  RunResult r = runRayster("render --size 64x48 --frames 1 --primary auto -o " + (dir / "a.png").string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("primary: auto chose"), std::string::npos) << r.output;
}

TEST(Render, ShadowsConvergeWithFrames) {
  // More frames average more shadow samples: the image gets closer to a high-sample render. (Indirect
  // light off: its 1-spp fireflies converge far more slowly and are the indirect denoiser's job.)
  // What fails it is frames that do not accumulate (err16 ≈ err1) or a history that keeps fewer than
  // about 4 frames (err16 ≥ err1 / 2). Neither depends on the image size, and a 64-frame reference
  // adds only its own error, σ/8 against the σ/4 of 16 frames: measured at 80×60, 0.030 (1 frame)
  // and 0.0038 (16 frames); against a 256-frame reference 0.030 and 0.0045.
  auto dir = testDir();
  constexpr int w = 80, h = 60;
  auto render = [&](int frames, int seed) {
    return renderOk(dir, "f" + std::to_string(frames) + "s" + std::to_string(seed),
                    "builtin:cornell --primary raster --indirect off --frames " + std::to_string(frames) + " --seed " +
                        std::to_string(seed),
                    w, h);
  };
  Image8 ref = render(64, 100);
  double err1 = compare(ref, render(1, 1), 0).rmse;
  double err16 = compare(ref, render(16, 1), 0).rmse;
  std::printf("[shadows] rmse against 64 frames: 1 frame %.4f, 16 frames %.4f\n", err1, err16);
  EXPECT_LT(err16, err1 * 0.5) << "1 frame rmse " << err1 << ", 16 frames " << err16;
}

TEST(Render, TimingsAndJson) {
  auto dir = testDir();
  auto json = dir / "t.json";
  RunResult r = runRayster("render --size 64x48 --frames 2 --primary raster --timings --json " + json.string() +
                           " -o " + (dir / "a.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* pass : {"gbuffer-raster", "rt-shadows", "rt-ao", "gi-probe-trace", "gi-probe-sample", "lighting",
                           "tonemap", "frame (GPU)"})
    EXPECT_NE(r.output.find(pass), std::string::npos) << pass << " missing in:\n" << r.output;
  ASSERT_TRUE(std::filesystem::exists(json));
}

TEST(Render, ExrOutputIsLinearHdr) {
  auto dir = testDir();
  auto exr = dir / "a.exr";
  RunResult r = runRayster("render --size 64x48 --frames 2 -o " + exr.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto img = readExr(exr);
  ASSERT_TRUE(img.ok());
  EXPECT_FALSE(rejectEmpty(*img, 64, 48).has_value());
  float maxValue = 0;
  for (float v : img->rgba) maxValue = std::max(maxValue, v);
  EXPECT_GT(maxValue, 1.0f) << "the light's radiance is far above display white";
}

TEST(Render, AovsAreWrittenBesideTheOutput) {
  auto dir = testDir();
  RunResult r = runRayster("render builtin:whitted --size 64x48 --frames 2 --aov all -o " + (dir / "w.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* name : {"depth", "normal", "albedo", "material", "emissive", "shadow-raw", "shadow-denoised",
                           "reflection-raw", "reflection-denoised", "ao-raw", "ao-denoised", "indirect-raw",
                           "indirect-denoised", "shadow0-raw", "shadow0-denoised"}) {
    auto png = readPng(dir / (std::string("w.") + name + ".png"));
    ASSERT_TRUE(png.ok()) << name;
    auto exr = readExr(dir / (std::string("w.") + name + ".exr"));
    ASSERT_TRUE(exr.ok()) << name;
    // Every stage shows the scene: not blank, not uniform, no NaN (the whitted light's visible
    // sphere is out of view, so its emissive image is rightly black).
    if (std::string(name) == "emissive") continue;
    EXPECT_FALSE(rejectEmpty(*exr, 64, 48).has_value()) << name << ": " << rejectEmpty(*exr, 64, 48).value_or("");
  }
  // Shadows are a fraction: the accumulated visibility stays within [0, 1].
  auto shadow = readExr(dir / "w.shadow-denoised.exr");
  for (size_t i = 0; i < shadow->rgba.size(); i += 4) ASSERT_TRUE(shadow->rgba[i] >= 0.0f && shadow->rgba[i] <= 1.0f);
  // The whitted scene has one shadowed light: layer 0 is "shadow-raw", there is no light 1.
  EXPECT_EQ(readExr(dir / "w.shadow0-raw.exr")->rgba, readExr(dir / "w.shadow-raw.exr")->rgba);
  EXPECT_FALSE(std::filesystem::exists(dir / "w.shadow1-raw.exr"));
  auto bad = runRayster("render --size 32x24 --aov normal,bogus -o " + (dir / "x.png").string());
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
  EXPECT_NE(bad.output.find("bogus"), std::string::npos) << bad.output;
}

TEST(Render, PerLightShadowAovs) {
  // The alpha-mask model's point light plus a second one from the scene file: one visibility layer
  // each, raw and denoised.
  auto dir = testDir();
  writeAlphaMaskGltf(dir);
  std::ofstream(dir / "two.json") << R"({"models": [{"path": "alpha-mask.gltf"}],
    "lights": [{"type": "point", "position": [-2, 3, 4], "color": [1, 1, 1], "intensity": 40, "radius": 0.1}]})";
  RunResult r =
      runRayster("render " + (dir / "two.json").string() +
                 " --size 64x48 --frames 3 --aov shadow-raw,shadow0-raw,shadow1-raw,shadow1-denoised,shadow2-raw -o " +
                 (dir / "t.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto raw0 = readExr(dir / "t.shadow0-raw.exr"), raw1 = readExr(dir / "t.shadow1-raw.exr");
  auto denoised1 = readExr(dir / "t.shadow1-denoised.exr");
  ASSERT_TRUE(raw0.ok() && raw1.ok() && denoised1.ok());
  EXPECT_EQ(raw0->rgba, readExr(dir / "t.shadow-raw.exr")->rgba) << "shadow-raw is layer 0";
  EXPECT_NE(raw0->rgba, raw1->rgba) << "two lights cast different shadows";
  EXPECT_FALSE(rejectEmpty(*denoised1, 64, 48).has_value());
  for (size_t i = 0; i < denoised1->rgba.size(); i += 4)
    ASSERT_TRUE(denoised1->rgba[i] >= 0.0f && denoised1->rgba[i] <= 1.0f) << denoised1->rgba[i];
  EXPECT_FALSE(std::filesystem::exists(dir / "t.shadow2-raw.exr")) << "the scene has no third light";
  EXPECT_NE(r.output.find("shadow2-raw"), std::string::npos) << "a skipped AOV is reported:\n" << r.output;
}

// ---- error paths: one-line cause, documented exit code, no output file ----

void expectFailure(const RunResult& r, int code, const std::string& needle, const std::filesystem::path& out) {
  EXPECT_EQ(r.exitCode, code) << r.output;
  EXPECT_NE(r.output.find(needle), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out)) << "a failed run must not leave " << out;
}

TEST(RenderErrors, NoVulkanDriver) {
  auto dir = testDir();
  auto out = dir / "a.png";
  RunResult r = runRayster("render -o " + out.string(),
                           "VK_DRIVER_FILES=/nonexistent/icd.json VK_ICD_FILENAMES=/nonexistent/icd.json");
  expectFailure(r, 4, "rayster: error:", out);
}

TEST(RenderErrors, BadArguments) {
  auto dir = testDir();
  auto out = dir / "a.png";
  expectFailure(runRayster("render --size 0x10 -o " + out.string()), 2, "--size", out);
  expectFailure(runRayster("render --size banana -o " + out.string()), 2, "--size", out);
  expectFailure(runRayster("render --frames 0 -o " + out.string()), 2, "frames", out);
  expectFailure(runRayster("render --primary maybe -o " + out.string()), 2, "primary", out);
  expectFailure(runRayster("render -o " + (dir / "a.jpg").string()), 2, ".png", dir / "a.jpg");
  expectFailure(runRayster("render --camera nope -o " + out.string()), 2, "nope", out);
}

TEST(RenderErrors, UnknownSceneOrMissingFile) {
  auto dir = testDir();
  auto out = dir / "a.png";
  expectFailure(runRayster("render builtin:nope -o " + out.string()), 3, "nope", out);
  expectFailure(runRayster("render /nonexistent/scene.gltf -o " + out.string()), 3, "scene.gltf", out);
}

TEST(RenderErrors, UnwritableOutput) {
  auto dir = testDir();
  auto blocker = dir / "file";
  {
    FILE* f = std::fopen(blocker.c_str(), "w");
    std::fclose(f);
  }
  // A path under a regular file can never be created, even by root.
  RunResult r = runRayster("render --size 32x24 --frames 1 -o " + (blocker / "a.png").string());
  EXPECT_EQ(r.exitCode, 8) << r.output;
  EXPECT_NE(r.output.find("cannot write"), std::string::npos) << r.output;
}

TEST(Info, ListsLavapipeWithRayTracing) {
  RunResult r = runRayster("info");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("ray-tracing pipeline: yes"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace rayster::test
