// Automatic exposure as a user meets it (render/exposure.h, docs/techniques.md §20): a scene lit by
// a 1 lux sun and the same scene under 100 000 lux render alike by default, in the hybrid, raster
// and path-traced modes, with finite EXRs in the scene's units; fixed exposures (--exposure EV,
// --ev100 N) are what they say; a viewer-style run adapts over time to a light that changes.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "core/metrics.h"
#include "render/exposure.h"
#include "render/renderer.h"
#include "rhi/context.h"
#include "scene/loader.h"
#include "tests/render/run_rayster.h"
#include "tests/render/user_scenes.h"

namespace rayster::test {
namespace {

constexpr int kW = 96, kH = 72;

double meanLdr(const Image8& img) {
  double sum = 0;
  for (size_t i = 0; i < img.rgba.size(); ++i)
    if (i % 4 != 3) sum += img.rgba[i];
  return sum / (double(img.rgba.size()) * 0.75);
}

// The fraction of pixels with a channel at 250 or more.
double saturated(const Image8& img) {
  size_t n = 0;
  for (size_t i = 0; i + 3 < img.rgba.size(); i += 4)
    n += std::max({img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]}) >= 250;
  return double(n) / double(img.rgba.size() / 4);
}

bool allFinite(const ImageF& img) {
  for (float v : img.rgba)
    if (!std::isfinite(v)) return false;
  return true;
}

// The mirror / glass / gold spheres of tests/render/user_scenes.h under a sun of `lux` lux (and a
// point light of 16 × that in candela), written once per test into its own folder.
std::filesystem::path sunScene(const std::filesystem::path& dir, double lux) {
  const auto sub = dir / ("sun-" + std::to_string(int64_t(lux * 1000)));
  std::filesystem::create_directories(sub);
  return writeSpecularSpheresGltf(sub, lux / 3.0);
}

TEST(Exposure, OneLuxAndAHundredThousandLuxLookAlikeByDefault) {
  auto dir = testDir();
  for (const char* mode : {"hybrid", "raster", "pathtrace"}) {
    const std::string args = std::string(" --mode ") + mode + " --primary rt --frames " +
                             (std::string(mode) == "pathtrace" ? "16" : "4") + " --seed 3";
    Image8 dim = renderOk(dir, std::string("dim-") + mode, sunScene(dir, 1.0).string() + args, kW, kH);
    Image8 bright = renderOk(dir, std::string("bright-") + mode, sunScene(dir, 1e5).string() + args, kW, kH);
    // Neither black nor white: the sunlit ground and spheres sit in the middle of the range (the
    // background is black: the scene has no environment).
    EXPECT_GT(meanLdr(bright), 25.0) << mode;
    EXPECT_LT(meanLdr(bright), 200.0) << mode;
    EXPECT_LT(saturated(bright), 0.05) << mode;
    // The same picture at both scales (the meter's bins are 0.23 EV wide: a few levels apart at most).
    EXPECT_NEAR(meanLdr(dim), meanLdr(bright), 6.0) << mode;
  }
}

TEST(Exposure, AHundredThousandLuxExrIsFiniteAndInTheScenesUnits) {
  auto dir = testDir();
  const std::string args = " --primary rt --frames 4 --seed 3 --size 96x72";
  for (const char* mode : {"hybrid", "pathtrace"}) {
    const auto dim = dir / (std::string("dim-") + mode + ".exr"),
               bright = dir / (std::string("bright-") + mode + ".exr");
    const auto brightHalf = dir / (std::string("bright-half-") + mode + ".exr");
    // fp32 EXRs for the comparison: the sun's highlights on the smooth spheres are brighter than the
    // largest half (65504) in the 100 000 lux scene, and a half EXR clamps them there.
    RunResult a = runRayster("render " + sunScene(dir, 1.0).string() + args + " --exr-float --mode " + mode + " -o " +
                             dim.string());
    RunResult b = runRayster("render " + sunScene(dir, 1e5).string() + args + " --exr-float --mode " + mode + " -o " +
                             bright.string());
    RunResult c =
        runRayster("render " + sunScene(dir, 1e5).string() + args + " --mode " + mode + " -o " + brightHalf.string());
    ASSERT_EQ(a.exitCode, 0) << a.output;
    ASSERT_EQ(b.exitCode, 0) << b.output;
    ASSERT_EQ(c.exitCode, 0) << c.output;
    auto x = readExr(dim), y = readExr(bright), h = readExr(brightHalf);
    ASSERT_TRUE(x.ok() && y.ok() && h.ok());
    EXPECT_FALSE(rejectEmpty(*y, kW, kH).has_value());
    EXPECT_TRUE(allFinite(*y)) << mode;
    EXPECT_TRUE(allFinite(*h)) << mode << ": the default half EXR clamps, it never holds inf";
    // The EXR holds the scene's radiance, 1e5 × the 1 lux scene's, whatever exposure each metered.
    EXPECT_NEAR(meanLuminance(*y) / meanLuminance(*x), 1e5, 1e5 * 0.05) << mode;
  }
}

TEST(Exposure, FixedExposureOfABrightSceneIsWhiteWhereAutoIsNot) {
  auto dir = testDir();
  const std::string scene = sunScene(dir, 1e5).string() + " --primary rt --frames 2 --seed 3";
  // At the unit exposure the sunlit ground (most of the picture) is white.
  EXPECT_GT(saturated(renderOk(dir, "ev0", scene + " --exposure 0", kW, kH)), 0.4);
  EXPECT_LT(saturated(renderOk(dir, "auto", scene, kW, kH)), 0.05);
}

TEST(Exposure, Ev100IsTheEquivalentFixedExposure) {
  auto dir = testDir();
  const std::string scene = sunScene(dir, 1e5).string() + " --primary rt --frames 2 --seed 3";
  // EV100 15 is the multiplier 1 / (1.2 · 2^15): --exposure log2 of it renders the same pixels.
  const std::string ev = std::to_string(std::log2(render::exposureFromEv100(15.0f)));
  Image8 a = renderOk(dir, "ev100", scene + " --ev100 15", kW, kH);
  Image8 b = renderOk(dir, "ev", scene + " --exposure " + ev, kW, kH);
  EXPECT_GE(compare(a, b, 1).fractionWithinTolerance, 0.999);
  RunResult both = runRayster("render " + scene + " --ev100 15 --exposure 2 -o " + (dir / "x.png").string());
  EXPECT_EQ(both.exitCode, 2) << both.output;
  EXPECT_NE(both.output.find("--ev100 and --exposure cannot be given together"), std::string::npos) << both.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST(Exposure, CompensationBrightensAndTheJsonReportsTheMeteredExposure) {
  auto dir = testDir();
  const std::string scene = sunScene(dir, 1e5).string() + " --primary rt --frames 2 --seed 3";
  const auto json = dir / "auto.json";
  Image8 plain = renderOk(dir, "auto", scene + " --json " + json.string(), kW, kH);
  Image8 lifted = renderOk(dir, "plus1", scene + " --exposure-compensation 1", kW, kH);
  EXPECT_GT(meanLdr(lifted), meanLdr(plain) + 10.0);
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["exposure"]["mode"], "auto");
  // 100 000 lux: a sunny-day exposure (EV100 ≈ 15, give or take the scene's albedos).
  EXPECT_NEAR(j["exposure"]["ev100"].get<double>(), 15.0, 2.5);
  EXPECT_NEAR(j["exposure"]["multiplier"].get<double>(), render::exposureFromEv100(j["exposure"]["ev100"].get<float>()),
              1e-9);
}

}  // namespace
}  // namespace rayster::test

namespace rayster::test {
namespace {

// A viewer-style run (Renderer::beginRun, one renderFrame per displayed frame): the first frame
// meters, then the exposure follows a light made 16× brighter at the rate the eye adapts, and
// settles where a fresh run of the brighter scene starts.
TEST(Exposure, AViewerRunAdaptsToALightThatChanges) {
  // 330 frames, so a smaller view than the other tests': the adaptation is per frame, not per pixel.
  constexpr int kViewerW = 48, kViewerH = 36;
  auto created = rhi::Context::create({/*validation*/ true, /*requireRayTracing*/ false, ""});
  if (!created) GTEST_SKIP() << "no Vulkan device";
  std::unique_ptr<rhi::Context> ctx = std::move(created.value());
  auto dir = testDir();
  auto loaded = scene::loadScene(sunScene(dir, 1000.0).string());
  ASSERT_TRUE(loaded.ok()) << (loaded.ok() ? "" : loaded.error().message);
  scene::Scene scene = std::move(loaded.value());
  {
    auto made = render::Renderer::create(*ctx, scene);
    ASSERT_TRUE(made.ok()) << (made.ok() ? "" : made.error().message);
    std::unique_ptr<render::Renderer> renderer = std::move(made.value());
    render::RenderSettings s;
    s.width = kViewerW, s.height = kViewerH;
    s.mode = ctx->caps().rayTracing() ? render::Mode::Hybrid : render::Mode::Raster;
    s.primary = render::Primary::Raster;
    ASSERT_TRUE(renderer->beginRun(s).ok());
    constexpr float kDt = 1.0f / 30.0f;
    auto frame = [&] {
      return render::ev100FromExposure(renderer->renderFrame({.moving = true, .dtSeconds = kDt}).exposure);
    };
    // Frame 0 renders at the guess from the lights, frame 1 at frame 0's reading; the exposure then
    // follows the image as its histories converge.
    std::vector<float> ev;
    for (int f = 0; f < 90; ++f) ev.push_back(frame());
    EXPECT_NEAR(ev[89], ev[88], 0.02f) << "settled";
    const size_t changed = ev.size();
    const float before = ev.back();
    // Every light of the scene 16× brighter (4 EV), without a cut (the viewer cuts on a light edit,
    // and a cut snaps the exposure): as when an animated light or the camera moves into the sun.
    // The frames are "moving" throughout, so the denoisers' histories let go of the old light.
    for (scene::Light& l : scene.lights) l.intensity *= 16.0f;
    renderer->refreshLights();
    for (int f = 0; f < 150; ++f) ev.push_back(frame());
    // Monotonic, no jump: each frame moves a step of at most the adaptation rate's share of 4 EV.
    for (size_t f = changed + 1; f < ev.size(); ++f) {
      EXPECT_GE(ev[f], ev[f - 1] - 0.01f) << f;  // the meter's reading is noisy by a little
      EXPECT_LE(ev[f] - ev[f - 1], 4.0f * (1.0f - std::exp(-render::kAdaptTowardsBright * kDt)) + 0.1f) << f;
    }
    // 1.5 s at 1.5/s would be 1 − e^(−2.25) ≈ 90 % of the way; the meter reads the image after TAA
    // and the denoisers, whose histories take a few frames to show the new light.
    const float after45 = ev[changed + 45] - before;
    EXPECT_GT(after45, 2.5f);
    EXPECT_LT(after45, 4.0f * (1.0f - std::exp(-render::kAdaptTowardsBright * 45 * kDt)) + 0.1f);
    // Settled where a fresh view of the brighter scene settles.
    auto fresh = render::Renderer::create(*ctx, scene);
    ASSERT_TRUE(fresh.ok());
    ASSERT_TRUE((*fresh)->beginRun(s).ok());
    float settled = 0.0f;
    for (int f = 0; f < 90; ++f)
      settled = render::ev100FromExposure((*fresh)->renderFrame({.moving = true, .dtSeconds = kDt}).exposure);
    (void)(*fresh)->endRun();
    std::printf("[exposure] after 45 frames +%.3f EV, fresh view settled +%.3f EV, adapted - fresh %+.4f EV\n", after45,
                settled - before, ev.back() - settled);
    EXPECT_GT(settled - before, 3.5f);
    EXPECT_NEAR(ev.back(), settled, 0.05f);
    renderer->renderFrame({.readback = true, .dtSeconds = kDt});
    render::RenderOutput out = renderer->endRun();
    EXPECT_FALSE(rejectEmpty(out.ldr, kViewerW, kViewerH).has_value());
  }
  ctx->waitIdle();
  ctx->collectGarbage();
  EXPECT_EQ(ctx->validationErrors(), 0u);
}

}  // namespace
}  // namespace rayster::test
