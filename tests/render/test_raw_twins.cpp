// The raw-rate twins of the ray-traced passes (render/passes/raw_rays.cpp, --raw-rays) trace the
// rays of their passes: where that is checkable from the passes' raw AOVs it is checked here,
// exactly where the replay is exact. Also the half-rate glossy checkerboard of rt-specular.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

constexpr int kW = 64, kH = 48;

// One frame (frame index 0) of `scene` with raw twins on; the AOVs by name.
std::map<std::string, ImageF> renderTwins(const std::filesystem::path& dir, const std::string& scene,
                                          const std::string& args, const std::vector<std::string>& aovs) {
  return renderAovs(
      dir, scene + " --size " + std::to_string(kW) + "x" + std::to_string(kH) + " --frames 1 --raw-rays " + args, aovs);
}

float at(const ImageF& img, int x, int y, int c = 0) { return img.pixel(x, y)[c]; }

TEST(RawTwins, AoTwinTracesTheSameRaysAsRtAo) {
  // No alpha-tested geometry in whitted: the opaque twin's visibility is rt-ao's, texel for texel.
  auto dir = testDir();
  auto img = renderTwins(dir, "builtin:whitted", "--primary raster --ao-rate full", {"ao-raw", "raw-ao"});
  ASSERT_EQ(img.size(), 2u);
  size_t occluded = 0, open = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      ASSERT_EQ(at(img["raw-ao"], x, y), at(img["ao-raw"], x, y)) << x << "," << y;
      (at(img["ao-raw"], x, y) == 0.0f ? occluded : open)++;
    }
  // Both outcomes occur, so equality says something about the rays.
  EXPECT_GT(occluded, 20u);
  EXPECT_GT(open, 20u);
}

TEST(RawTwins, HalfRateAoTwinTracesTheCheckerboardRtAoDoes) {
  // --ao-rate half: the twin marks the pixels not traced this frame 0.25; they form a checkerboard
  // (every 4-neighbour of one was traced), and on the traced ones its visibility is rt-ao's.
  // rt-ao-fill gives the others a mean of their neighbours, in [0, 1].
  auto dir = testDir();
  auto img = renderTwins(dir, "builtin:whitted", "--primary raster --ao-rate half", {"ao-raw", "raw-ao"});
  ASSERT_EQ(img.size(), 2u);
  const ImageF& raw = img["raw-ao"];
  const ImageF& pass = img["ao-raw"];
  size_t skipped = 0, traced = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float r = at(raw, x, y), a = at(pass, x, y);
      if (r == 0.25f) {
        ++skipped;
        EXPECT_GE(a, 0.0f) << x << "," << y;
        EXPECT_LE(a, 1.0f) << x << "," << y;
        if (x + 1 < kW) EXPECT_NE(at(raw, x + 1, y), 0.25f) << x << "," << y;
        if (y + 1 < kH) EXPECT_NE(at(raw, x, y + 1), 0.25f) << x << "," << y;
      } else {
        ++traced;
        ASSERT_EQ(r, a) << x << "," << y;
      }
    }
  EXPECT_EQ(skipped, size_t(kW) * kH / 2);
  EXPECT_EQ(traced, size_t(kW) * kH / 2);
}

TEST(RawTwins, SpecularTwinTracesWhereTheSpecularPassDoes) {
  // raw-specular: 0 where rt-specular writes alpha 0 (not traced), 0.125 where a glossy sample
  // leaves below the surface (nothing traced, alpha 1), 0.25 a half-rate skip (filled from its
  // neighbours, alpha 1), 0.5/1 first ray missed/hit. Half-rate skips form a checkerboard: no two
  // are 4-neighbours.
  auto dir = testDir();
  auto img = renderTwins(dir, "builtin:whitted", "--primary raster", {"reflection-raw", "raw-specular"});
  ASSERT_EQ(img.size(), 2u);
  const ImageF& raw = img["raw-specular"];
  const ImageF& pass = img["reflection-raw"];
  std::map<float, size_t> counts;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float r = at(raw, x, y), alpha = at(pass, x, y, 3);
      ++counts[r];
      ASSERT_TRUE(r == 0.0f || r == 0.125f || r == 0.25f || r == 0.5f || r == 1.0f) << r;
      ASSERT_EQ(r > 0.0f, alpha == 1.0f) << x << "," << y << " raw " << r << " alpha " << alpha;
      ASSERT_EQ(r == 0.0f, alpha == 0.0f) << x << "," << y;
      for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(at(pass, x, y, k)));
      if (r == 0.25f && x + 1 < kW) {
        EXPECT_NE(at(raw, x + 1, y), 0.25f) << x << "," << y;
      }
      if (r == 0.25f && y + 1 < kH) {
        EXPECT_NE(at(raw, x, y + 1), 0.25f) << x << "," << y;
      }
    }
  // First rays of rt-specular per pixel, before the checkerboard (every traced or skipped pixel)
  // and now (traced only): the figure the half rate changes.
  const double n = kW * kH;
  std::printf(
      "[raw-specular] first rays per pixel: %.3f with every glossy pixel traced, %.3f now "
      "(%.3f skipped: half-rate glossy)\n",
      (counts[0.25f] + counts[0.5f] + counts[1.0f]) / n, (counts[0.5f] + counts[1.0f]) / n, counts[0.25f] / n);
  // The marble floor (roughness 0.3) skips half its glossy rays; its traced half and the chrome and
  // ice objects both hit and miss.
  EXPECT_GT(counts[0.25f], size_t(kW * kH / 10)) << "no half-rate checkerboard on the floor";
  EXPECT_GT(counts[0.5f], 20u);
  EXPECT_GT(counts[1.0f], 20u);
  EXPECT_GT(counts[0.0f], 20u);  // sky and the lit-only surfaces
}

TEST(RawTwins, IndirectTwinBounceRaysHitInsideTheBoxAndMissUnderTheSky) {
  // raw-indirect: 0 no bounce ray, 0.5 missed, 1 hit. Its bounce rays are rt-indirect's exactly; on
  // whitted's open floor most of them see the sky, in the Cornell box most hit a wall. At full rate:
  // every pixel traces (the quarter rate's block pattern: test_indirect_rate.cpp).
  auto dir = testDir();
  auto fraction = [&](const std::string& scene) {
    auto img = renderTwins(dir, scene, "--primary raster --indirect on --gi path --indirect-rate full",
                           {"indirect-raw", "raw-indirect"});
    size_t hits = 0, traced = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const float r = at(img["raw-indirect"], x, y);
        // A bounce ray is traced only where rt-indirect writes alpha 1.
        if (r > 0.0f) {
          EXPECT_EQ(at(img["indirect-raw"], x, y, 3), 1.0f) << scene << " " << x << "," << y;
        }
        traced += r > 0.0f;
        hits += r == 1.0f;
      }
    EXPECT_GT(traced, size_t(kW * kH / 4)) << scene;
    return double(hits) / double(std::max<size_t>(traced, 1));
  };
  EXPECT_GT(fraction("builtin:cornell"), 0.6);  // open at the front: ~3/4 hit
  EXPECT_LT(fraction("builtin:whitted"), 0.5);
}

TEST(RawTwins, DirectTwinSeesTheLightAsOftenAsTheShadowPass) {
  // --shadow-lights 0 puts whitted's one light into many-light mode (rt-direct): its twin's shadow
  // ray goes to the same light with another sample of it than rt-shadows' (another random stream),
  // so per pixel they may differ in the penumbra, but the lit share of the image matches.
  auto dir = testDir();
  auto many = renderTwins(dir, "builtin:whitted", "--primary raster --shadow-lights 0", {"raw-direct"});
  auto shadowed = renderTwins(dir, "builtin:whitted", "--primary raster", {"shadow-raw"});
  ASSERT_TRUE(many.count("raw-direct") && shadowed.count("shadow-raw"));
  double lit = 0, shadowLit = 0, differ = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float a = at(many["raw-direct"], x, y), b = at(shadowed["shadow-raw"], x, y);
      ASSERT_TRUE(a == 0.0f || a == 1.0f) << a;
      lit += a;
      shadowLit += b;
      differ += a != b;
    }
  const double n = kW * kH;
  EXPECT_GT(lit / n, 0.2);
  EXPECT_NEAR(lit / n, shadowLit / n, 0.03);
  EXPECT_LT(differ / n, 0.1);  // penumbra pixels only
}

}  // namespace
}  // namespace rayster::test
