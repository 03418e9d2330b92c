// Every EXR `rayster render` writes is finite, also where the scene is brighter than half floats
// reach (65504): an emissive quad of 1e6 (KHR_materials_emissive_strength) seen by the camera.
// Half channels clamp there; --exr-float keeps the path tracer's fp32 values.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/render/run_rayster.h"
#include "tests/unit/gltf_test_util.h"

namespace rayster::test {
namespace {

constexpr float kHalfMax = 65504.0f;
constexpr float kEmission = 1e6f;

std::filesystem::path writeBrightQuad(const std::filesystem::path& dir) {
  Doc d = quadDoc();
  d.j["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  d.j["materials"] =
      Json::array({{{"name", "glare"},
                    {"emissiveFactor", {1, 1, 1}},
                    {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", kEmission}}}}}}});
  primitive(d)["material"] = 0;
  std::ofstream(dir / "bright.gltf") << d.gltf();
  return dir / "bright.gltf";
}

ImageF renderExr(const std::filesystem::path& dir, const std::string& name, const std::string& args) {
  const auto out = dir / (name + ".exr");
  RunResult r =
      runRayster("render " + (dir / "bright.gltf").string() + " --size 64x48 --seed 3 " + args + " -o " + out.string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  auto img = readExr(out);
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.error().message);
  return img.ok() ? std::move(*img) : ImageF{};
}

struct Range {
  size_t nonFinite = 0, atHalfMax = 0;
  float max = 0.0f;
};

Range scan(const ImageF& img) {
  Range r;
  for (float v : img.rgba) {
    if (!std::isfinite(v))
      ++r.nonFinite;
    else
      r.max = std::max(r.max, v);
    if (v == kHalfMax) ++r.atHalfMax;
  }
  return r;
}

TEST(ExrOutput, PathTracedOverflowClampsToLargestHalfOrStaysFloat) {
  auto dir = testDir();
  writeBrightQuad(dir);
  const ImageF half = renderExr(dir, "half", "--mode pathtrace --spp 4");
  const ImageF full = renderExr(dir, "float", "--mode pathtrace --spp 4 --exr-float");
  ASSERT_FALSE(half.empty());
  ASSERT_EQ(half.rgba.size(), full.rgba.size());
  const Range h = scan(half), f = scan(full);
  EXPECT_EQ(h.nonFinite, 0u);
  EXPECT_EQ(f.nonFinite, 0u);
  EXPECT_GT(f.max, kHalfMax) << "the quad is brighter than half floats reach";
  EXPECT_EQ(h.max, kHalfMax);
  // The same deterministic render: where the float is past the half range, the half is clamped.
  size_t clamped = 0;
  for (size_t i = 0; i < full.rgba.size(); ++i) {
    if (full.rgba[i] > kHalfMax) {
      ++clamped;
      ASSERT_EQ(half.rgba[i], kHalfMax) << "value " << i << " float " << full.rgba[i];
    } else {
      ASSERT_NEAR(half.rgba[i], full.rgba[i], std::abs(full.rgba[i]) * 1e-3f + 1e-4f) << "value " << i;
    }
  }
  EXPECT_GT(clamped, 0u);
}

TEST(ExrOutput, HybridOutputHdrAndAovsAreFinite) {
  auto dir = testDir();
  writeBrightQuad(dir);
  const ImageF out = renderExr(dir, "hybrid", "--frames 2 --hdr " + (dir / "hdr.exr").string() + " --aov emissive");
  ASSERT_FALSE(out.empty());
  const Range o = scan(out);
  EXPECT_EQ(o.nonFinite, 0u);
  EXPECT_EQ(o.max, kHalfMax);
  EXPECT_GT(o.atHalfMax, 0u);
  for (const char* file : {"hdr.exr", "hybrid.emissive.exr"}) {
    auto img = readExr(dir / file);
    ASSERT_TRUE(img.ok()) << file;
    const Range r = scan(*img);
    EXPECT_EQ(r.nonFinite, 0u) << file;
    EXPECT_EQ(r.max, kHalfMax) << file;
  }
}

TEST(ExrOutput, ViewerScreenshotExrIsFinite) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is missing (scripts/setup.sh installs xvfb and xauth)";
  auto dir = testDir();
  const std::string scene = writeBrightQuad(dir).string();
  for (const char* flag : {"", " --exr-float"}) {
    const auto shot = dir / "shot.exr";
    RunResult v =
        runUnderXvfb("view " + scene + " --size 64x48 --frames 2 --hide-ui --screenshot " + shot.string() + flag);
    ASSERT_EQ(v.exitCode, 0) << v.output;
    auto img = readExr(shot);
    ASSERT_TRUE(img.ok()) << flag;
    const Range r = scan(*img);
    EXPECT_EQ(r.nonFinite, 0u) << flag;
    if (*flag == '\0') {
      EXPECT_EQ(r.max, kHalfMax);  // a half EXR clamps
    } else {
      // The viewer's HDR frame is held in half floats on the GPU, pre-exposed: auto exposure brought
      // the glare into their range, so the fp32 EXR holds its true radiance.
      EXPECT_NEAR(r.max, kEmission, kEmission * 0.01f);
    }
  }
}

}  // namespace
}  // namespace rayster::test
