#pragma once
// Golden-image comparison shared by the render tests. Every golden is rendered at the unit exposure
// (--exposure 0), what the built-in scenes were tuned at: the goldens hold the pipeline still, and
// automatic exposure has tests of its own (tests/render/test_exposure.cpp).
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "core/image.h"
#include "core/image_io.h"
#include "core/metrics.h"

namespace rayster::test {

// docs/architecture.md §9: at most 2/255 per channel on at least 99.9 % of the pixels.
inline constexpr int kGoldenTolerance = 2;
inline constexpr double kGoldenFraction = 0.999;

inline std::filesystem::path goldenPath(const std::string& name) {
  return std::filesystem::path(RAYSTER_SOURCE_DIR) / "tests" / "golden" / (name + ".png");
}

// Compares with the committed golden; RAYSTER_BLESS=1 rewrites the golden instead (scripts/bless-goldens.sh).
inline void expectMatchesGolden(const Image8& actual, const std::string& name, const std::filesystem::path& dir) {
  auto golden = goldenPath(name);
  if (const char* bless = std::getenv("RAYSTER_BLESS"); bless && std::string(bless) == "1") {
    ASSERT_TRUE(writePng(golden, actual).ok());
    GTEST_SKIP() << "blessed " << golden;
  }
  auto expected = readPng(golden);
  ASSERT_TRUE(expected.ok()) << "missing golden " << golden << " (run scripts/bless-goldens.sh)";
  ASSERT_EQ(expected->width, actual.width);
  ASSERT_EQ(expected->height, actual.height);
  ImageDiff diff = compare(*expected, actual, kGoldenTolerance);
  if (diff.fractionWithinTolerance < kGoldenFraction) {
    (void)writePng(dir / (name + ".actual.png"), actual);
    (void)writePng(dir / (name + ".diff.png"), diff.heatmap);
  }
  EXPECT_GE(diff.fractionWithinTolerance, kGoldenFraction)
      << name << ": max channel diff " << diff.maxChannelDiff << ", PSNR " << diff.psnr << " dB; actual and diff in "
      << dir;
}

}  // namespace rayster::test
