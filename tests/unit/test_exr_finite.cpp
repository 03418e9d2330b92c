// EXR files Rayster writes hold only finite values: half channels clamp to the largest half
// (65504), NaN becomes 0, and ExrPixels::Float keeps values past the half range.

#include <cfloat>
#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <tinyexr.h>

#include "core/image.h"
#include "core/image_io.h"
#include "tests/support/test_dirs.h"

using namespace rayster;
namespace fs = std::filesystem;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kHalfMax = 65504.0f;

// One row of the values that break half EXRs, with what each must read back as in half.
const std::vector<float> kWritten = {1e6f, -1e6f, kInf, -kInf, std::nanf(""), 70000.0f, 65519.0f, 1.5f};
const std::vector<float> kAsHalf = {kHalfMax, -kHalfMax, kHalfMax, -kHalfMax, 0.0f, kHalfMax, kHalfMax, 1.5f};

ImageF rowImage() {
  ImageF image = ImageF::make(int(kWritten.size()), 1);
  for (size_t i = 0; i < kWritten.size(); ++i)
    for (int c = 0; c < 4; ++c) image.rgba[i * 4 + size_t(c)] = kWritten[i];
  return image;
}

fs::path tempPath(const char* name) { return rayster::test::uniqueTestDir("exr") / name; }

// The pixel type tinyexr reads from the file's header for every channel, or -1 if they differ.
int channelPixelType(const fs::path& path) {
  EXRVersion version;
  EXRHeader header;
  InitEXRHeader(&header);
  const char* err = nullptr;
  if (ParseEXRVersionFromFile(&version, path.c_str()) != TINYEXR_SUCCESS) return -2;
  if (ParseEXRHeaderFromFile(&header, &version, path.c_str(), &err) != TINYEXR_SUCCESS) {
    if (err) FreeEXRErrorMessage(err);
    return -2;
  }
  int type = header.pixel_types[0];
  for (int i = 1; i < header.num_channels; ++i)
    if (header.pixel_types[i] != type) type = -1;
  FreeEXRHeader(&header);
  return type;
}

TEST(ExrFinite, HalfClampsToTheLargestHalfAndNanToZero) {
  const fs::path path = tempPath("half.exr");
  ASSERT_TRUE(writeExr(path, rowImage()).ok());
  EXPECT_EQ(channelPixelType(path), TINYEXR_PIXELTYPE_HALF);
  auto read = readExr(path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  for (size_t i = 0; i < kWritten.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      const float v = read->rgba[i * 4 + size_t(c)];
      EXPECT_TRUE(std::isfinite(v)) << "value " << kWritten[i] << " channel " << c << " read " << v;
      EXPECT_EQ(v, kAsHalf[i]) << "value " << kWritten[i] << " channel " << c;
    }
  fs::remove(path);
}

TEST(ExrFinite, FloatKeepsTheRangeAndIsFinite) {
  const fs::path path = tempPath("float.exr");
  ASSERT_TRUE(writeExr(path, rowImage(), ExrPixels::Float).ok());
  EXPECT_EQ(channelPixelType(path), TINYEXR_PIXELTYPE_FLOAT);
  auto read = readExr(path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  const std::vector<float> expected = {1e6f, -1e6f, FLT_MAX, -FLT_MAX, 0.0f, 70000.0f, 65519.0f, 1.5f};
  for (size_t i = 0; i < kWritten.size(); ++i)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(read->rgba[i * 4 + size_t(c)], expected[i]) << "value " << kWritten[i];
  fs::remove(path);
}

TEST(ExrFinite, WriteImageTakesThePixelType) {
  const fs::path path = tempPath("image.exr");
  ASSERT_TRUE(writeImage(path, rowImage(), ExrPixels::Float).ok());
  EXPECT_EQ(channelPixelType(path), TINYEXR_PIXELTYPE_FLOAT);
  ASSERT_TRUE(writeImage(path, rowImage()).ok());
  EXPECT_EQ(channelPixelType(path), TINYEXR_PIXELTYPE_HALF);
  fs::remove(path);
}

}  // namespace
