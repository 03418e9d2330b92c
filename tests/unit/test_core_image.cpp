// Half floats, sRGB, image files and logging: the pieces every pixel test stands on.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/half.h"
#include "core/image.h"
#include "core/image_io.h"
#include "core/log.h"
#include "tests/support/test_dirs.h"

namespace fs = std::filesystem;
using namespace rayster;

namespace {

// A fresh folder of the running test (tests/support/test_dirs.h: removed when the test passes).
class TempDir {
 public:
  TempDir() : path_(rayster::test::uniqueTestDir("image")) {}
  const fs::path& path() const { return path_; }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

Image8 gradient8(int w, int h) {
  Image8 image = Image8::make(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = image.pixel(x, y);
      p[0] = static_cast<uint8_t>(x * 255 / std::max(1, w - 1));
      p[1] = static_cast<uint8_t>(y * 255 / std::max(1, h - 1));
      p[2] = static_cast<uint8_t>((x * 7 + y * 13) % 256);
      p[3] = static_cast<uint8_t>(200 + (x % 50));
    }
  return image;
}

ImageF gradientF(int w, int h) {
  ImageF image = ImageF::make(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = image.pixel(x, y);
      p[0] = 0.01f * static_cast<float>(x);
      p[1] = 3.0f + 0.5f * static_cast<float>(y);  // above 1: EXR must keep HDR values
      p[2] = 1e-3f * static_cast<float>(x + y);
      p[3] = 0.25f;
    }
  return image;
}

void writeFile(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

}  // namespace

TEST(Half, KnownValues) {
  EXPECT_EQ(floatToHalf(0.0f), 0x0000);
  EXPECT_EQ(floatToHalf(-0.0f), 0x8000);
  EXPECT_EQ(floatToHalf(1.0f), 0x3c00);
  EXPECT_EQ(floatToHalf(-2.0f), 0xc000);
  EXPECT_EQ(floatToHalf(65504.0f), 0x7bff);
  EXPECT_EQ(floatToHalf(65520.0f), 0x7c00);  // halfway to 65536 rounds to even: infinity
  EXPECT_EQ(floatToHalf(1e6f), 0x7c00);
  EXPECT_EQ(floatToHalf(std::numeric_limits<float>::infinity()), 0x7c00);
  EXPECT_EQ(floatToHalf(-std::numeric_limits<float>::infinity()), 0xfc00);
  EXPECT_TRUE(std::isnan(halfToFloat(floatToHalf(std::numeric_limits<float>::quiet_NaN()))));
  EXPECT_EQ(halfToFloat(0x3c00), 1.0f);
  EXPECT_EQ(halfToFloat(0x7bff), 65504.0f);
  EXPECT_TRUE(std::isinf(halfToFloat(0x7c00)));
}

TEST(Half, RoundsToNearestEven) {
  EXPECT_EQ(floatToHalf(1.0f + std::ldexp(1.0f, -11)), 0x3c00);      // tie, even below
  EXPECT_EQ(floatToHalf(1.0f + 3 * std::ldexp(1.0f, -11)), 0x3c02);  // tie, even above
  EXPECT_EQ(floatToHalf(1.0f + std::ldexp(1.2f, -11)), 0x3c01);      // above the tie
}

TEST(Half, Denormals) {
  EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -24)), 0x0001);  // smallest denormal
  EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -25)), 0x0000);  // tie rounds to even zero
  EXPECT_EQ(floatToHalf(std::ldexp(1.5f, -25)), 0x0001);
  EXPECT_EQ(floatToHalf(std::ldexp(1023.0f, -24)), 0x03ff);  // largest denormal
  EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -14)), 0x0400);     // smallest normal
  EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -40)), 0x0000);
  EXPECT_EQ(halfToFloat(0x0001), std::ldexp(1.0f, -24));
  EXPECT_EQ(halfToFloat(0x8200), -std::ldexp(512.0f, -24));
}

TEST(Half, EveryHalfRoundTrips) {
  for (uint32_t h = 0; h <= 0xffff; ++h) {
    const float f = halfToFloat(static_cast<uint16_t>(h));
    if (std::isnan(f)) {
      EXPECT_TRUE(std::isnan(halfToFloat(floatToHalf(f)))) << h;
      continue;
    }
    ASSERT_EQ(floatToHalf(f), h) << "half 0x" << std::hex << h;
  }
}

TEST(Srgb, KnownPoints) {
  EXPECT_FLOAT_EQ(srgbToLinear(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(srgbToLinear(1.0f), 1.0f);
  EXPECT_NEAR(srgbToLinear(0.5f), 0.214041f, 1e-5);
  EXPECT_NEAR(srgbToLinear(0.04045f), 0.04045f / 12.92f, 1e-7);  // linear segment
  EXPECT_NEAR(linearToSrgb(0.18f), 0.461356f, 1e-5);
  EXPECT_NEAR(linearToSrgb(0.0031308f), 0.04045f, 1e-5);  // the two pieces meet
  EXPECT_FLOAT_EQ(linearToSrgb(1.0f), 1.0f);
}

TEST(Srgb, RoundTrips) {
  for (int i = 0; i <= 1000; ++i) {
    const float v = static_cast<float>(i) / 1000.0f;
    EXPECT_NEAR(linearToSrgb(srgbToLinear(v)), v, 1e-5) << v;
  }
  Image8 all = Image8::make(256, 1);
  for (int i = 0; i < 256; ++i) std::fill_n(all.pixel(i, 0), 4, static_cast<uint8_t>(i));
  EXPECT_EQ(encodeSrgb8(decodeSrgb8(all)).rgba, all.rgba);
}

TEST(Srgb, EncodeClampsAndZeroesNan) {
  ImageF image = ImageF::make(3, 1);
  image.pixel(0, 0)[0] = -1.0f;
  image.pixel(1, 0)[0] = 7.0f;
  image.pixel(2, 0)[0] = std::numeric_limits<float>::quiet_NaN();
  const Image8 out = encodeSrgb8(image);
  EXPECT_EQ(out.pixel(0, 0)[0], 0);
  EXPECT_EQ(out.pixel(1, 0)[0], 255);
  EXPECT_EQ(out.pixel(2, 0)[0], 0);
}

TEST(ImageIo, PngRoundTrip) {
  TempDir dir;
  const Image8 image = gradient8(37, 19);
  const fs::path path = dir.path() / "nested" / "out.png";  // parent folder is created
  ASSERT_TRUE(writePng(path, image).ok());
  auto read = readPng(path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->width, 37);
  EXPECT_EQ(read->height, 19);
  EXPECT_EQ(read->rgba, image.rgba);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"nested"});
  EXPECT_EQ(fs::directory_iterator(dir.path() / "nested")->path().filename(), "out.png");
}

TEST(ImageIo, ExrRoundTripIsHalfExact) {
  TempDir dir;
  const ImageF image = gradientF(23, 11);
  const fs::path path = dir.path() / "out.exr";
  ASSERT_TRUE(writeExr(path, image).ok());
  auto read = readExr(path);
  ASSERT_TRUE(read.ok()) << read.error().message;
  ASSERT_EQ(read->width, 23);
  ASSERT_EQ(read->height, 11);
  for (size_t i = 0; i < image.rgba.size(); ++i)
    ASSERT_EQ(read->rgba[i], halfToFloat(floatToHalf(image.rgba[i]))) << "value " << i;
}

TEST(ImageIo, WriteImageChoosesFormatByExtension) {
  TempDir dir;
  const ImageF image = gradientF(8, 8);
  ASSERT_TRUE(writeImage(dir.path() / "a.PNG", image).ok());
  ASSERT_TRUE(writeImage(dir.path() / "a.exr", image).ok());
  auto png = readImageLinear(dir.path() / "a.PNG");
  auto exr = readImageLinear(dir.path() / "a.exr");
  ASSERT_TRUE(png.ok() && exr.ok());
  for (int x = 0; x < 8; ++x) {
    // PNG clamps to 1 and quantises in sRGB space; compare there.
    const float r = image.pixel(x, 2)[0];
    EXPECT_NEAR(linearToSrgb(png->pixel(x, 2)[0]), linearToSrgb(r), 0.5f / 255.0f + 1e-6f);
    EXPECT_FLOAT_EQ(png->pixel(x, 2)[1], 1.0f);
    EXPECT_NEAR(exr->pixel(x, 2)[1], image.pixel(x, 2)[1], 1e-3f);
  }
  const Status bad = writeImage(dir.path() / "a.bmp", image);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().code, ExitCode::BadArguments);
  auto badRead = readImageLinear(dir.path() / "a.tga");
  ASSERT_FALSE(badRead.ok());
  EXPECT_EQ(badRead.error().code, ExitCode::BadArguments);
}

TEST(ImageIo, UnwritableParentFailsCleanly) {
  TempDir dir;
  writeFile(dir.path() / "file", "x");
  const Status status = writePng(dir.path() / "file" / "out.png", gradient8(4, 4));
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error().code, ExitCode::OutputFailed);
  EXPECT_NE(status.error().message.find("cannot write"), std::string::npos);
  EXPECT_NE(status.error().message.find("out.png"), std::string::npos);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"file"});
}

TEST(ImageIo, FailedRenameRemovesTempFile) {
  TempDir dir;
  // The target is a non-empty folder: the temp file is written, the rename must fail.
  fs::create_directories(dir.path() / "taken.exr" / "inside");
  const Status status = writeExr(dir.path() / "taken.exr", gradientF(4, 4));
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error().code, ExitCode::OutputFailed);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"taken.exr"});
  const Status png = writePng(dir.path() / "taken.exr", gradient8(4, 4));
  EXPECT_FALSE(png.ok());
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"taken.exr"});
}

TEST(ImageIo, ReadOnlyFolderFailsCleanly) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores folder permissions";
  TempDir dir;
  fs::create_directories(dir.path() / "ro");
  fs::permissions(dir.path() / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  const Status status = writePng(dir.path() / "ro" / "out.png", gradient8(4, 4));
  fs::permissions(dir.path() / "ro", fs::perms::owner_all);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error().code, ExitCode::OutputFailed);
  EXPECT_TRUE(fs::is_empty(dir.path() / "ro"));
}

TEST(ImageIo, EmptyImageIsNotWritten) {
  TempDir dir;
  EXPECT_FALSE(writePng(dir.path() / "e.png", Image8{}).ok());
  EXPECT_FALSE(writeExr(dir.path() / "e.exr", ImageF{}).ok());
  EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageIo, MissingFileIsBadInput) {
  TempDir dir;
  auto png = readPng(dir.path() / "missing.png");
  ASSERT_FALSE(png.ok());
  EXPECT_EQ(png.error().code, ExitCode::BadInput);
  EXPECT_NE(png.error().message.find("missing.png"), std::string::npos);
  EXPECT_NE(png.error().message.find("no such file"), std::string::npos);
  auto exr = readExr(dir.path() / "missing.exr");
  ASSERT_FALSE(exr.ok());
  EXPECT_EQ(exr.error().code, ExitCode::BadInput);
  auto linear = readImageLinear(dir.path() / "missing.png");
  ASSERT_FALSE(linear.ok());
  EXPECT_EQ(linear.error().code, ExitCode::BadInput);
}

TEST(ImageIo, GarbageFileIsBadInput) {
  TempDir dir;
  writeFile(dir.path() / "garbage.png", "this is not an image at all");
  writeFile(dir.path() / "garbage.exr", "v/1\x01 still not an image");
  auto png = readPng(dir.path() / "garbage.png");
  ASSERT_FALSE(png.ok());
  EXPECT_EQ(png.error().code, ExitCode::BadInput);
  EXPECT_NE(png.error().message.find("garbage.png"), std::string::npos);
  EXPECT_EQ(png.error().message.find('\n'), std::string::npos);
  auto exr = readExr(dir.path() / "garbage.exr");
  ASSERT_FALSE(exr.ok());
  EXPECT_EQ(exr.error().code, ExitCode::BadInput);
  EXPECT_NE(exr.error().message.find("garbage.exr"), std::string::npos);
  // A truncated real PNG is corrupt too.
  ASSERT_TRUE(writePng(dir.path() / "good.png", gradient8(16, 16)).ok());
  fs::resize_file(dir.path() / "good.png", 40);
  auto truncated = readPng(dir.path() / "good.png");
  ASSERT_FALSE(truncated.ok());
  EXPECT_EQ(truncated.error().code, ExitCode::BadInput);
}

TEST(Log, PrefixesAndFilters) {
  const log::Level saved = log::level();
  log::setLevel(log::Level::Info);
  ::testing::internal::CaptureStderr();
  log::debug("hidden {}", 1);
  log::info("hello {}", 2);
  log::warn("careful");
  log::error("broken {}", "x");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(),
            "rayster: hello 2\nrayster: warning: careful\nrayster: error: broken x\n");
  log::setLevel(log::Level::Error);
  ::testing::internal::CaptureStderr();
  log::warn("quiet");
  log::error("loud");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "rayster: error: loud\n");
  log::setLevel(log::Level::Debug);
  ::testing::internal::CaptureStderr();
  log::debug("d");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "rayster: d\n");
  log::setLevel(saved);
}

// Debian's stb_image 2.27 writes past its Huffman tables for a JPEG table of more than 256 codes
// (fuzz/fuzz_image.cpp found it); the readers refuse such a file before stb sees it.
TEST(ImageIo, RefusesJpegHuffmanTablesStbWouldOverflow) {
  const fs::path dir = test::testDir();
  std::vector<uint8_t> jpeg = {0xFF, 0xD8, 0xFF, 0xC4, 0x00, 0x13, 0x00};
  for (int i = 0; i < 16; ++i) jpeg.push_back(17);  // 272 codes
  jpeg.insert(jpeg.end(), {0xFF, 0xD9});
  EXPECT_NE(stbDecodeHazard(jpeg.data(), jpeg.size()).find("declares 272 codes"), std::string::npos);
  std::ofstream(dir / "bad.png", std::ios::binary).write(reinterpret_cast<const char*>(jpeg.data()), jpeg.size());
  Result<Image8> image = readPng(dir / "bad.png");
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.error().code, ExitCode::BadInput);
  EXPECT_NE(image.error().message.find("Huffman table declares 272 codes"), std::string::npos) << image.error().message;
  // stb takes fill bytes before the SOI marker too (fuzz_image found that way past the check).
  std::vector<uint8_t> filled = {0xFF, 0xFF, 0xFF};
  filled.insert(filled.end(), jpeg.begin(), jpeg.end());
  EXPECT_NE(stbDecodeHazard(filled.data(), filled.size()).find("declares 272 codes"), std::string::npos);
  std::ofstream(dir / "filled.png", std::ios::binary)
      .write(reinterpret_cast<const char*>(filled.data()), std::streamsize(filled.size()));
  EXPECT_FALSE(readPng(dir / "filled.png").ok());
  // Ordinary files are not affected.
  EXPECT_EQ(stbDecodeHazard(nullptr, 0), "");
  const std::vector<uint8_t> png = {0x89, 'P', 'N', 'G'};
  EXPECT_EQ(stbDecodeHazard(png.data(), png.size()), "");
}

// A header may claim any size; the readers refuse what is over 16384 per side before decoding.
TEST(ImageIo, RefusesAbsurdDimensionsBeforeDecoding) {
  const fs::path dir = test::testDir();
  std::ofstream(dir / "huge.hdr", std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n";
  Result<ImageF> image = readImageLinear(dir / "huge.hdr");
  ASSERT_FALSE(image.ok());
  EXPECT_NE(image.error().message.find("100000x100000 pixels, more than 16384 per side"), std::string::npos)
      << image.error().message;
}
