// What a user sees on scenes shaped like the Khronos sample models and Blender exports
// (tests/render/user_scenes.h): traced primaries through a 1 mm near plane, and reflections under
// physically scaled lights.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include "tests/render/run_rayster.h"
#include "tests/render/user_scenes.h"

namespace rayster::test {
namespace {

TEST(UserScenes, TracedPrimariesMatchRasterThroughAMillimetreNearPlane) {
  // The camera is 28 m from the origin with znear = 1 mm (EnvironmentTest's camera). Primary rays
  // aimed through the near plane were tilted by several pixels by float rounding, so traced hits left
  // the rays that depth reconstruction assumes: streaks and self-shadowing on the spheres.
  auto dir = testDir();
  const auto scene = writeSphereRowGltf(dir, 0.001).string();
  constexpr int kW = 200, kH = 112;
  const std::string args = scene + " --frames 2 --seed 4 --aov shadow-raw";
  Image8 raster = renderOk(dir, "raster", args + " --primary raster", kW, kH);
  Image8 traced = renderOk(dir, "traced", args + " --primary rt", kW, kH);
  ImageDiff diff = compare(raster, traced, 2);
  if (diff.fractionWithinTolerance < 0.995) (void)writePng(dir / "diff.png", diff.heatmap);
  EXPECT_GE(diff.fractionWithinTolerance, 0.995) << "max diff " << diff.maxChannelDiff;
  EXPECT_GE(diff.psnr, 45.0);
  // The shadow rays start from the reconstructed surface: with bent primaries they hit it again.
  auto rasterShadow = readPng(dir / "raster.shadow-raw.png");
  auto tracedShadow = readPng(dir / "traced.shadow-raw.png");
  ASSERT_TRUE(rasterShadow.ok() && tracedShadow.ok());
  ImageDiff shadowDiff = compare(*rasterShadow, *tracedShadow, 2);
  EXPECT_GE(shadowDiff.fractionWithinTolerance, 0.995) << "max diff " << shadowDiff.maxChannelDiff;
}

TEST(UserScenes, ReflectionsDoNotDependOnTheScaleOfLightUnits) {
  // The same mirror / glass / gold scene with its lights ×1000 (what a Blender export in lux and
  // candela looks like) at −log2(1000) EV must render like the built-in scale at 0 EV: every clamp
  // and fp16 target works relative to the exposure. Before, the reflections clamped at an absolute
  // radiance and the spheres came out as dull grey balls.
  auto dir = testDir();
  const auto unit = writeSpecularSpheresGltf(dir, 1.0);
  std::filesystem::create_directories(dir / "bright");
  const auto bright = writeSpecularSpheresGltf(dir / "bright", 1000.0);
  constexpr int kW = 160, kH = 120;
  const std::string ev = " --exposure " + std::to_string(-std::log2(1000.0));
  for (const char* primary : {"raster", "rt"}) {
    const std::string args = std::string(" --frames 4 --seed 2 --primary ") + primary;
    Image8 a = renderOk(dir, std::string("unit-") + primary, unit.string() + args + " --exposure 0", kW, kH);
    Image8 b = renderOk(dir, std::string("bright-") + primary, bright.string() + args + ev, kW, kH);
    ImageDiff diff = compare(a, b, 2);
    if (diff.fractionWithinTolerance < 0.999)
      (void)writePng(dir / (std::string("diff-") + primary + ".png"), diff.heatmap);
    EXPECT_GE(diff.fractionWithinTolerance, 0.999) << primary << ": max diff " << diff.maxChannelDiff;
  }
}

TEST(UserScenes, HdrOutputsAreInTheScenesUnitsWhateverTheExposure) {
  // Light is stored pre-exposed on the GPU; what Rayster writes as HDR (the EXR image, radiance AOVs,
  // the path tracer's mean) is divided back, so --exposure changes only the tonemapped image.
  auto dir = testDir();
  auto meanOf = [](const ImageF& img) {
    double sum = 0;
    for (size_t i = 0; i < img.rgba.size(); ++i)
      if (i % 4 != 3) sum += img.rgba[i];
    return sum / double(img.rgba.size() / 4 * 3);
  };
  for (const char* mode : {"hybrid", "pathtrace"}) {
    const std::string args =
        std::string("builtin:whitted --size 64x48 --frames 2 --seed 3 --primary raster --mode ") + mode;
    auto hdrAt = [&](const char* ev) {
      const auto out = dir / (std::string(mode) + ev + ".exr");
      RunResult r = runRayster("render " + args + " --exposure " + ev + " -o " + out.string());
      EXPECT_EQ(r.exitCode, 0) << r.output;
      return readExr(out);
    };
    auto lowHdr = hdrAt("-3"), highHdr = hdrAt("4");
    ASSERT_TRUE(lowHdr.ok() && highHdr.ok()) << mode;
    EXPECT_FALSE(rejectEmpty(*lowHdr, 64, 48).has_value()) << mode;
    const double a = meanOf(*lowHdr), b = meanOf(*highHdr);
    // The path tracer is linear in its sources (fp32 mean): only rounding differs. The hybrid's
    // denoisers weigh by exposed luminance, so a 7-stop change may move its mean a little.
    EXPECT_NEAR(b / a, 1.0, std::string(mode) == "pathtrace" ? 1e-3 : 0.02) << mode << ": " << a << " vs " << b;
  }
}

// Where the sidedness scene's camera (tests/render/user_scenes.h) sees a world point, in pixels.
glm::ivec2 sidednessPixel(glm::vec3 world, int w, int h) {
  const glm::mat4 clip = glm::perspective(0.8f, float(w) / float(h), 0.05f, 100.0f) *
                         glm::lookAt(glm::vec3(0.0f, 3.5f, 9.0f), glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(0, 1, 0));
  const glm::vec4 c = clip * glm::vec4(world, 1.0f);
  const glm::ivec2 px(int((c.x / c.w * 0.5f + 0.5f) * float(w)), int((0.5f - c.y / c.w * 0.5f) * float(h)));
  EXPECT_TRUE(px.x >= 0 && px.y >= 0 && px.x < w && px.y < h)
      << world.x << "," << world.y << "," << world.z << " → " << px.x << "," << px.y;
  return glm::clamp(px, glm::ivec2(0), glm::ivec2(w - 1, h - 1));
}

enum class Hue { Green, Blue, Yellow, Orange, NotOrange };
bool hasHue(const float* p, Hue hue) {
  const float r = p[0], g = p[1], b = p[2];
  switch (hue) {
    case Hue::Green:
      return g > 2.0f * r && g > 2.0f * b;
    case Hue::Blue:
      return b > 2.0f * r && b > 1.5f * g;
    case Hue::Yellow:
      return r > 2.0f * b && g > 2.0f * b;
    case Hue::Orange:
      return r > 1.2f * g && g > 1.5f * b;
    case Hue::NotOrange:
      return !hasHue(p, Hue::Orange);
  }
  return false;
}

// What every mode must show of the sidedness scene: front faces, no back faces of single-sided
// quads (a mirrored node's fronts are its fronts), and shadows as rays see them.
struct SidednessProbe {
  glm::vec3 at;
  Hue hue;
  const char* what;
};
const SidednessProbe kSidednessProbes[] = {
    {{-3.0f, 1.5f, 0.0f}, Hue::Green, "the single-sided quad facing the camera"},
    {{-1.0f, 1.5f, 0.0f}, Hue::Blue, "the backdrop through the back of a single-sided quad"},
    {{3.0f, 1.5f, 0.0f}, Hue::Yellow, "the mirrored node's quad facing the camera"},
    {{1.0f, 1.5f, 0.0f}, Hue::Blue, "the backdrop through the back of the mirrored node's quad"},
    {{-2.0f, 0.0f, 1.5f}, Hue::Orange, "the horizontal quad facing up"},
    {{2.0f, 0.0f, 1.5f}, Hue::NotOrange, "the floor through the back of the horizontal quad facing down"},
};

TEST(UserScenes, SingleSidedMaterialsShowNoBackFacesInAnyProducer) {
  auto dir = testDir();
  const auto scene = writeSidednessGltf(dir).string();
  constexpr int kW = 192, kH = 128;
  for (const char* mode : {"--primary raster", "--primary rt", "--mode raster"}) {
    auto aovs = renderAovs(dir, scene + " --size 192x128 --frames 1 " + mode, {"albedo", "shadow-raw"});
    ASSERT_TRUE(aovs.count("albedo") && aovs.count("shadow-raw")) << mode;
    EXPECT_FALSE(rejectEmpty(aovs["albedo"], kW, kH).has_value()) << mode;
    for (const SidednessProbe& probe : kSidednessProbes) {
      const glm::ivec2 px = sidednessPixel(probe.at, kW, kH);
      const float* p = aovs["albedo"].pixel(px.x, px.y);
      EXPECT_TRUE(hasHue(p, probe.hue)) << mode << ": " << probe.what << " at " << px.x << "," << px.y << " is " << p[0]
                                        << " " << p[1] << " " << p[2];
    }
    // The sun's rays from the floor meet the up-facing quad's back (no shadow) and the down-facing
    // quad's front (shadow); shadow maps render what those rays see.
    const glm::ivec2 lit = sidednessPixel({-2.0f, -1.0f, 0.5f}, kW, kH),
                     dark = sidednessPixel({2.0f, -1.0f, 0.5f}, kW, kH);
    EXPECT_GT(aovs["shadow-raw"].pixel(lit.x, lit.y)[0], 0.9f) << mode << ": the up-facing quad casts a shadow";
    EXPECT_LT(aovs["shadow-raw"].pixel(dark.x, dark.y)[0], 0.1f) << mode << ": the down-facing quad casts none";
  }
}

TEST(UserScenes, SingleSidedMaterialsShowNoBackFacesInThePathTracer) {
  auto dir = testDir();
  const auto scene = writeSidednessGltf(dir).string();
  constexpr int kW = 192, kH = 128;
  auto out = dir / "pt.exr";
  RunResult r = runRayster("render " + scene + " --mode pathtrace --size 192x128 --spp 16 -o " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto img = readExr(out);
  ASSERT_TRUE(img.ok());
  EXPECT_FALSE(rejectEmpty(*img, kW, kH).has_value());
  for (const SidednessProbe& probe : kSidednessProbes) {
    const glm::ivec2 px = sidednessPixel(probe.at, kW, kH);
    const float* p = img->pixel(px.x, px.y);
    EXPECT_TRUE(hasHue(p, probe.hue)) << probe.what << " at " << px.x << "," << px.y << " is " << p[0] << " " << p[1]
                                      << " " << p[2];
  }
  auto luminance = [&](glm::vec3 at) {
    const glm::ivec2 px = sidednessPixel(at, kW, kH);
    const float* p = img->pixel(px.x, px.y);
    return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
  };
  EXPECT_GT(luminance({-2.0f, -1.0f, 0.5f}), 1.5f * luminance({2.0f, -1.0f, 0.5f}))
      << "the sun lights the floor past the up-facing quad and not past the down-facing one";
}

}  // namespace
}  // namespace rayster::test
