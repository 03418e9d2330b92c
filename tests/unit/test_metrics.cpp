// Image metrics: hand-computed cases, so a wrong formula cannot hide behind a self-consistent test.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/metrics.h"

using namespace rayster;

namespace {

Image8 gradient8(int w, int h) {
  Image8 image = Image8::make(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = image.pixel(x, y);
      p[0] = static_cast<uint8_t>(10 * x + 20);
      p[1] = static_cast<uint8_t>(10 * y + 20);
      p[2] = 100;
      p[3] = 255;
    }
  return image;
}

ImageF gradientF(int w, int h) {
  ImageF image = ImageF::make(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = image.pixel(x, y);
      p[0] = 0.1f * static_cast<float>(x);
      p[1] = 0.1f * static_cast<float>(y);
      p[2] = 0.5f;
      p[3] = 1.0f;
    }
  return image;
}

}  // namespace

TEST(RejectEmpty, AcceptsAGradient) {
  EXPECT_EQ(rejectEmpty(gradient8(8, 6), 8, 6), std::nullopt);
  EXPECT_EQ(rejectEmpty(gradientF(8, 6), 8, 6), std::nullopt);
}

TEST(RejectEmpty, WrongSizeAndEmpty) {
  EXPECT_NE(rejectEmpty(gradient8(8, 6), 6, 8), std::nullopt);
  EXPECT_NE(rejectEmpty(gradientF(8, 6), 8, 7), std::nullopt);
  EXPECT_NE(rejectEmpty(Image8{}, 0, 0), std::nullopt);
  EXPECT_NE(rejectEmpty(ImageF{}, 0, 0), std::nullopt);
  Image8 lying = gradient8(4, 4);
  lying.rgba.resize(8);  // width/height disagree with the data
  EXPECT_NE(rejectEmpty(lying, 4, 4), std::nullopt);
}

TEST(RejectEmpty, AllBlack) {
  Image8 black = Image8::make(5, 5);
  for (size_t i = 3; i < black.rgba.size(); i += 4) black.rgba[i] = 255;  // opaque black is still black
  const auto reason = rejectEmpty(black, 5, 5);
  ASSERT_NE(reason, std::nullopt);
  EXPECT_NE(reason->find("black"), std::string::npos);
  EXPECT_NE(rejectEmpty(ImageF::make(5, 5), 5, 5), std::nullopt);
}

TEST(RejectEmpty, Uniform) {
  Image8 grey = Image8::make(5, 5);
  for (size_t i = 0; i < grey.rgba.size(); ++i) grey.rgba[i] = static_cast<uint8_t>(i % 4 == 3 ? i % 7 : 128);
  const auto reason = rejectEmpty(grey, 5, 5);  // alpha varies, rgb does not
  ASSERT_NE(reason, std::nullopt);
  EXPECT_NE(reason->find("uniform"), std::string::npos);
  ImageF flat = ImageF::make(3, 3);
  for (float& v : flat.rgba) v = 0.25f;
  EXPECT_NE(rejectEmpty(flat, 3, 3), std::nullopt);
  flat.pixel(2, 2)[1] = 0.3f;  // one different pixel makes it a real image
  EXPECT_EQ(rejectEmpty(flat, 3, 3), std::nullopt);
}

TEST(RejectEmpty, NonFinite) {
  ImageF image = gradientF(4, 4);
  image.pixel(1, 2)[2] = std::numeric_limits<float>::quiet_NaN();
  const auto reason = rejectEmpty(image, 4, 4);
  ASSERT_NE(reason, std::nullopt);
  EXPECT_NE(reason->find("(1, 2)"), std::string::npos);
  image = gradientF(4, 4);
  image.pixel(3, 3)[3] = std::numeric_limits<float>::infinity();  // alpha counts too
  EXPECT_NE(rejectEmpty(image, 4, 4), std::nullopt);
}

TEST(Compare, IdenticalImages) {
  const Image8 a = gradient8(4, 4);
  const ImageDiff diff = compare(a, a, 0);
  EXPECT_EQ(diff.maxChannelDiff, 0);
  EXPECT_EQ(diff.fractionWithinTolerance, 1.0);
  EXPECT_EQ(diff.rmse, 0.0);
  EXPECT_TRUE(std::isinf(diff.psnr) && diff.psnr > 0);
  ASSERT_EQ(diff.heatmap.width, 4);
  for (size_t i = 0; i < diff.heatmap.rgba.size(); ++i) EXPECT_EQ(diff.heatmap.rgba[i], i % 4 == 3 ? 255 : 0);
}

TEST(Compare, OnePixelOffByThree) {
  const Image8 a = gradient8(4, 4);
  Image8 b = a;
  b.pixel(2, 1)[0] += 3;
  b.pixel(0, 0)[3] = 0;  // alpha is ignored
  const ImageDiff diff = compare(a, b, 2);
  EXPECT_EQ(diff.maxChannelDiff, 3);
  EXPECT_DOUBLE_EQ(diff.fractionWithinTolerance, 15.0 / 16.0);
  // One squared error of (3/255)^2 over 16 pixels * 3 channels.
  const double expectedRmse = std::sqrt(9.0 / 48.0) / 255.0;
  EXPECT_NEAR(diff.rmse, expectedRmse, 1e-12);
  EXPECT_NEAR(diff.psnr, 20.0 * std::log10(1.0 / expectedRmse), 1e-9);
  // diff 3 of 16 on a 3-segment ramp: t = 0.5625 of the black->red segment.
  const uint8_t* hot = diff.heatmap.pixel(2, 1);
  EXPECT_EQ(hot[0], 143);
  EXPECT_EQ(hot[1], 0);
  EXPECT_EQ(hot[2], 0);
  EXPECT_EQ(diff.heatmap.pixel(0, 0)[0], 0);
  EXPECT_DOUBLE_EQ(compare(a, b, 3).fractionWithinTolerance, 1.0);
}

TEST(Compare, HeatmapSaturatesToWhite) {
  const Image8 a = gradient8(2, 1);
  Image8 b = a;
  b.pixel(0, 0)[1] += 16;
  b.pixel(1, 0)[2] += 100;
  const ImageDiff diff = compare(a, b, 0);
  EXPECT_EQ(diff.maxChannelDiff, 100);
  EXPECT_EQ(diff.fractionWithinTolerance, 0.0);
  for (int x = 0; x < 2; ++x)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(diff.heatmap.pixel(x, 0)[c], 255);
}

TEST(FloatMetrics, RmseByHand) {
  ImageF a = ImageF::make(2, 1);
  ImageF b = ImageF::make(2, 1);
  b.pixel(0, 0)[0] = 1.0f;
  b.pixel(1, 0)[2] = 2.0f;
  b.pixel(1, 0)[3] = 100.0f;  // alpha is ignored
  EXPECT_NEAR(rmse(a, b), std::sqrt(5.0 / 6.0), 1e-12);
  EXPECT_EQ(rmse(a, a), 0.0);
}

TEST(FloatMetrics, RelMseByHand) {
  ImageF ref = ImageF::make(1, 1);
  ImageF test = ImageF::make(1, 1);
  ref.rgba = {1.0f, 0.0f, 0.5f, 1.0f};
  test.rgba = {2.0f, 0.0f, 0.5f, 0.0f};
  EXPECT_NEAR(relMse(ref, test), 1.0 / (1.01 * 3.0), 1e-12);
  // Against a black reference, eps sets the scale: (0.1)^2 / 0.01 = 1 per channel.
  ImageF black = ImageF::make(1, 1);
  ImageF dim = ImageF::make(1, 1);
  dim.rgba = {0.1f, 0.1f, 0.1f, 1.0f};
  EXPECT_NEAR(relMse(black, dim), 1.0, 1e-6);
  EXPECT_EQ(relMse(ref, ref), 0.0);
}

TEST(MetricsPsnr, IdenticalIsInfinite) {
  const ImageF a = gradientF(4, 3);
  EXPECT_TRUE(std::isinf(psnr(a, a)) && psnr(a, a) > 0);
}

TEST(MetricsPsnr, ByHand) {
  // One channel of one pixel off by 0.3 in a 2x1 image: MSE = 0.09 / 6 = 0.015,
  // PSNR = -10 log10(0.015) = 18.2391 dB.
  ImageF a = ImageF::make(2, 1), b = ImageF::make(2, 1);
  b.pixel(1, 0)[1] = 0.3f;
  EXPECT_NEAR(psnr(a, b), -10.0 * std::log10(0.09 / 6.0), 1e-5);
  EXPECT_NEAR(psnr(a, b), 18.2391, 1e-4);
}

TEST(MetricsMask, FromImage) {
  Image8 image = Image8::make(3, 1);
  image.pixel(1, 0)[2] = 1;    // any nonzero rgb counts
  image.pixel(2, 0)[3] = 255;  // alpha alone does not
  const PixelMask mask = maskFromImage(image);
  ASSERT_EQ(mask.inside.size(), 3u);
  EXPECT_EQ(mask.count(), 1u);
  EXPECT_FALSE(mask.covers(0));
  EXPECT_TRUE(mask.covers(1));
  EXPECT_FALSE(mask.covers(2));
  EXPECT_TRUE(PixelMask{}.covers(2));  // empty: everything
}

TEST(MetricsMask, RestrictsTheMean) {
  // Errors only in pixel 0 (r + 1) and pixel 1 (b + 2): masking pixel 0 out leaves (2^2) / 3 channels.
  ImageF a = ImageF::make(2, 1), b = ImageF::make(2, 1);
  b.pixel(0, 0)[0] = 1.0f;
  b.pixel(1, 0)[2] = 2.0f;
  const PixelMask onlySecond{2, 1, {0, 1}};
  EXPECT_NEAR(rmse(a, b, onlySecond), std::sqrt(4.0 / 3.0), 1e-12);
  const PixelMask onlyFirst{2, 1, {1, 0}};
  EXPECT_NEAR(rmse(a, b, onlyFirst), std::sqrt(1.0 / 3.0), 1e-12);
  EXPECT_NEAR(psnr(a, b, onlyFirst), -20.0 * std::log10(std::sqrt(1.0 / 3.0)), 1e-9);
  // relMse against a black reference: d^2 / eps.
  EXPECT_NEAR(relMse(a, b, 1e-2, onlyFirst), 1.0 / 1e-2 / 3.0, 1e-6);
  EXPECT_NEAR(relMse(a, b, 1e-2, PixelMask{2, 1, {0, 0}}), 0.0, 0.0);
}
