// FLIP and HDR-FLIP (core/flip.h): each step against values worked out by hand from the papers'
// formulas and the published sRGB matrices, then whole-image behaviour the papers promise.
#include <algorithm>
#include <cmath>
#include <numeric>

#include <gtest/gtest.h>

#include "core/colormap.h"
#include "core/flip.h"
#include "core/image_io.h"

using namespace rayster;
using flip::Vec3;

namespace {

ImageF uniform(int w, int h, float r, float g, float b) {
  ImageF image = ImageF::make(w, h);
  for (size_t i = 0; i < image.rgba.size(); i += 4) {
    image.rgba[i] = r;
    image.rgba[i + 1] = g;
    image.rgba[i + 2] = b;
    image.rgba[i + 3] = 1.0f;
  }
  return image;
}

// A smooth colourful pattern, so features and colours both vary.
ImageF pattern(int w, int h) {
  ImageF image = ImageF::make(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = image.pixel(x, y);
      p[0] = 0.5f + 0.4f * std::sin(0.3f * static_cast<float>(x));
      p[1] = 0.5f + 0.4f * std::cos(0.2f * static_cast<float>(y));
      p[2] = static_cast<float>((x / 8 + y / 8) % 2) * 0.6f + 0.2f;
      p[3] = 1.0f;
    }
  return image;
}

void expectVec(const Vec3& got, const Vec3& want, double tolerance) {
  for (size_t i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], tolerance) << "component " << i;
}

}  // namespace

TEST(FlipColor, PixelsPerDegree) {
  // 0.7 m * (3840 px / 0.7 m) * pi / 180 = 3840 pi / 180.
  EXPECT_NEAR(pixelsPerDegree(0.7, 0.7, 3840), 3840.0 * 3.14159265358979 / 180.0, 1e-9);
  EXPECT_NEAR(pixelsPerDegree(0.7, 0.7, 3840), 67.02, 0.01);
}

TEST(FlipColor, WhiteIsTheReference) {
  // Row sums of the sRGB -> XYZ matrix.
  expectVec(flip::referenceWhite(),
            {0.4124564 + 0.3575761 + 0.1804375, 0.2126729 + 0.7151522 + 0.0721750, 0.0193339 + 0.1191920 + 0.9503041},
            1e-12);
  expectVec(flip::xyzToYcxcz(flip::referenceWhite()), {100.0, 0.0, 0.0}, 1e-9);
  expectVec(flip::xyzToLab(flip::referenceWhite()), {100.0, 0.0, 0.0}, 1e-9);
}

TEST(FlipColor, SrgbToLinearToXyzToYcxcz) {
  // sRGB 128: ((128/255 + 0.055) / 1.055)^2.4 = 0.2158605; grey, so XYZ = 0.2158605 * white, and
  // Yy = 116 * 0.2158605 - 16 = 9.03982 with no chroma.
  const double grey = srgbToLinear(128.0f / 255.0f);
  EXPECT_NEAR(grey, 0.2158605, 1e-6);
  expectVec(flip::xyzToYcxcz(flip::linearRgbToXyz({grey, grey, grey})), {9.03982, 0.0, 0.0}, 1e-4);

  // Pure red: XYZ = first column (0.4124564, 0.2126729, 0.0193339);
  // Yy = 116 * 0.2126729 / 1.0000001 - 16 = 8.67005
  // Cx = 500 * (0.4124564 / 0.95047 - 0.2126729 / 1.0000001) = 110.6385
  // Cz = 200 * (0.2126729 / 1.0000001 - 0.0193339 / 1.08883) = 38.9833
  const Vec3 redXyz = flip::linearRgbToXyz({1.0, 0.0, 0.0});
  expectVec(redXyz, {0.4124564, 0.2126729, 0.0193339}, 1e-12);
  expectVec(flip::xyzToYcxcz(redXyz), {8.67005, 110.6385, 38.9833}, 1e-3);

  // sRGB (255, 128, 0): linear (1, 0.2158605, 0);
  // X = 0.4124564 + 0.3575761 * 0.2158605 = 0.4896430, Y = 0.2126729 + 0.7151522 * 0.2158605 = 0.3670460,
  // Z = 0.0193339 + 0.1191920 * 0.2158605 = 0.0450627;
  // Yy = 116 * 0.367046 - 16 = 26.5773, Cx = 500 * (0.489643 / 0.95047 - 0.367046) = 74.0564,
  // Cz = 200 * (0.367046 - 0.0450627 / 1.08883) = 65.1319.
  const Vec3 orangeXyz = flip::linearRgbToXyz({srgbToLinear(1.0f), grey, srgbToLinear(0.0f)});
  expectVec(orangeXyz, {0.4896430, 0.3670460, 0.0450627}, 1e-6);
  expectVec(flip::xyzToYcxcz(orangeXyz), {26.5773, 74.0564, 65.1319}, 1e-3);
}

TEST(FlipColor, ConversionsInvert) {
  for (const Vec3& rgb : {Vec3{0.2, 0.5, 0.9}, Vec3{1.0, 0.0, 0.0}, Vec3{0.01, 0.02, 0.0}}) {
    expectVec(flip::xyzToLinearRgb(flip::linearRgbToXyz(rgb)), rgb, 1e-6);
    const Vec3 xyz = flip::linearRgbToXyz(rgb);
    expectVec(flip::ycxczToXyz(flip::xyzToYcxcz(xyz)), xyz, 1e-12);
  }
}

TEST(FlipColor, LabOfPrimaries) {
  // The textbook CIELAB (D65) values of the sRGB primaries.
  expectVec(flip::xyzToLab(flip::linearRgbToXyz({0.0, 1.0, 0.0})), {87.735, -86.183, 83.179}, 2e-3);
  expectVec(flip::xyzToLab(flip::linearRgbToXyz({0.0, 0.0, 1.0})), {32.297, 79.188, -107.860}, 2e-3);
}

TEST(FlipColor, HuntAndHyab) {
  // a*, b* scaled by L*/100.
  expectVec(flip::huntAdjust({50.0, 10.0, 20.0}), {50.0, 5.0, 10.0}, 1e-12);
  expectVec(flip::huntAdjust({0.0, 80.0, -30.0}), {0.0, 0.0, 0.0}, 1e-12);
  // |50 - 40| + sqrt((10 - 13)^2 + (20 - 24)^2) = 10 + 5.
  EXPECT_DOUBLE_EQ(flip::hyab({50.0, 10.0, 20.0}, {40.0, 13.0, 24.0}), 15.0);
  EXPECT_DOUBLE_EQ(flip::hyab({40.0, 13.0, 24.0}, {50.0, 10.0, 20.0}), 15.0);
  EXPECT_DOUBLE_EQ(flip::hyab({1.0, 2.0, 3.0}, {1.0, 2.0, 3.0}), 0.0);
}

TEST(FlipColor, MaxColorDifference) {
  // Hunt-adjusted green (87.735, -75.612, 72.977) and blue (32.297, 25.575, -34.835):
  // HyAB = 55.438 + sqrt(101.187^2 + 107.812^2) = 203.297; cmax = 203.297^0.7 = 41.275.
  EXPECT_NEAR(flip::maxColorDifference(), 41.275, 2e-3);
}

TEST(FlipColor, Redistribution) {
  const double cmax = flip::maxColorDifference();
  EXPECT_DOUBLE_EQ(flip::redistributeColorError(0.0, cmax), 0.0);
  // pc * cmax maps to pt; cmax to 1; linear on both sides.
  EXPECT_NEAR(flip::redistributeColorError(0.4 * cmax, cmax), 0.95, 1e-12);
  EXPECT_NEAR(flip::redistributeColorError(0.2 * cmax, cmax), 0.475, 1e-12);
  EXPECT_NEAR(flip::redistributeColorError(0.7 * cmax, cmax), 0.95 + 0.5 * 0.05, 1e-12);
  EXPECT_NEAR(flip::redistributeColorError(cmax, cmax), 1.0, 1e-12);
}

TEST(FlipKernels, CsfKernelsSumToOneAndAreSymmetric) {
  // Radius 3 sigma of the widest Gaussian: ceil(3 * sqrt(0.04 / (2 pi^2)) * 67) = ceil(9.05) = 10.
  for (int c = 0; c < 3; ++c) {
    const std::vector<double> k = flip::csfKernel(c, 67.0);
    ASSERT_EQ(k.size(), 21u * 21u);
    EXPECT_NEAR(std::accumulate(k.begin(), k.end(), 0.0), 1.0, 1e-12);
    EXPECT_NEAR(k[0], k[21 * 21 - 1], 1e-15);
    EXPECT_NEAR(k[3], k[3 * 21], 1e-15);  // (3, 0) and (0, 3)
    EXPECT_EQ(std::max_element(k.begin(), k.end()) - k.begin(), 10 * 21 + 10);
  }
  // Chroma is blurred more than luminance: the centre weight is smaller.
  EXPECT_GT(flip::csfKernel(0, 67.0)[220], flip::csfKernel(1, 67.0)[220]);
  EXPECT_GT(flip::csfKernel(1, 67.0)[220], flip::csfKernel(2, 67.0)[220]);
}

TEST(FlipKernels, FeatureKernelsAreNormalised) {
  // sigma = 0.5 * 0.082 * 67 = 2.747 pixels, radius ceil(3 sigma) = 9.
  const flip::FeatureKernels k = flip::featureKernels(67.0);
  ASSERT_EQ(k.gaussian.size(), 19u);
  ASSERT_EQ(k.firstDerivative.size(), 19u);
  ASSERT_EQ(k.secondDerivative.size(), 19u);
  EXPECT_NEAR(std::accumulate(k.gaussian.begin(), k.gaussian.end(), 0.0), 1.0, 1e-12);
  for (const auto* d : {&k.firstDerivative, &k.secondDerivative}) {
    double positive = 0, negative = 0;
    for (double v : *d) (v > 0 ? positive : negative) += v;
    EXPECT_NEAR(positive, 1.0, 1e-12);
    EXPECT_NEAR(negative, -1.0, 1e-12);
  }
  EXPECT_NEAR(k.firstDerivative[9], 0.0, 1e-15);  // odd
  EXPECT_NEAR(k.firstDerivative[4], -k.firstDerivative[14], 1e-15);
  EXPECT_LT(k.secondDerivative[9], 0.0);  // a dip at the centre
  // The Gaussian's own shape: g(1) / g(0) = exp(-1 / (2 * 2.747^2)).
  EXPECT_NEAR(k.gaussian[10] / k.gaussian[9], std::exp(-1.0 / (2.0 * 2.747 * 2.747)), 1e-9);
}

TEST(FlipMap, IdenticalImagesAreZero) {
  const ImageF a = pattern(40, 30);
  const ErrorMap map = flipLdr(a, a);
  ASSERT_EQ(map.width, 40);
  ASSERT_EQ(map.values.size(), 40u * 30u);
  for (float v : map.values) EXPECT_EQ(v, 0.0f);
  EXPECT_EQ(errorStats(map).mean, 0.0);
}

TEST(FlipMap, WhiteDotOnBlackIsConcentratedAtTheDot) {
  const ImageF black = uniform(61, 61, 0, 0, 0);
  ImageF dot = black;
  dot.pixel(30, 30)[0] = dot.pixel(30, 30)[1] = dot.pixel(30, 30)[2] = 1.0f;
  const ErrorMap map = flipLdr(black, dot);
  const auto peak = std::max_element(map.values.begin(), map.values.end()) - map.values.begin();
  EXPECT_EQ(peak, 30 * 61 + 30);
  EXPECT_GT(map.at(30, 30), 0.5f);
  // Nothing reaches past the filters (CSF radius 10 + feature radius 9).
  for (int y = 0; y < 61; ++y)
    for (int x = 0; x < 61; ++x)
      if (std::max(std::abs(x - 30), std::abs(y - 30)) > 19) {
        ASSERT_EQ(map.at(x, y), 0.0f) << x << ", " << y;
      }
  // And it falls off with distance.
  EXPECT_GT(map.at(30, 30), map.at(33, 30));
  EXPECT_GT(map.at(33, 30), map.at(40, 30));
  EXPECT_GT(errorStats(map).mean, 0.0);
}

TEST(FlipMap, ConstantOffsetGivesAUniformMap) {
  const ErrorMap map = flipLdr(uniform(48, 40, 0.3f, 0.3f, 0.3f), uniform(48, 40, 0.4f, 0.4f, 0.4f));
  const auto [lo, hi] = std::minmax_element(map.values.begin(), map.values.end());
  EXPECT_GT(*lo, 0.0f);
  EXPECT_NEAR(*hi, *lo, 1e-5f);
  // No features in flat images, so the error is the colour term alone:
  // HyAB of Hunt-adjusted greys = |L*(0.3) - L*(0.4)|, then ^0.7 and redistributed.
  const double l3 = flip::xyzToLab(flip::linearRgbToXyz({0.3, 0.3, 0.3}))[0];
  const double l4 = flip::xyzToLab(flip::linearRgbToXyz({0.4, 0.4, 0.4}))[0];
  const double cmax = flip::maxColorDifference();
  EXPECT_NEAR(map.at(24, 20), flip::redistributeColorError(std::pow(l4 - l3, 0.7), cmax), 1e-4);

  // On a textured image the same offset gives a uniform map away from the borders too: FLIP of a
  // horizontal ramp vs the ramp + 0.1 only changes along x, so every column is constant.
  ImageF ramp = ImageF::make(64, 48), shifted = ImageF::make(64, 48);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) {
        ramp.pixel(x, y)[c] = 0.2f + 0.005f * static_cast<float>(x);
        shifted.pixel(x, y)[c] = ramp.pixel(x, y)[c] + 0.1f;
      }
  const ErrorMap rampMap = flipLdr(ramp, shifted);
  for (int x = 0; x < 64; ++x)
    for (int y = 1; y < 48; ++y) ASSERT_NEAR(rampMap.at(x, y), rampMap.at(x, 0), 1e-5f);
  for (int x = 20; x < 44; ++x) EXPECT_NEAR(rampMap.at(x, 10), rampMap.at(32, 10), 0.02f);  // slowly varying
}

TEST(FlipMap, SymmetricInItsInputs) {
  // Colour (HyAB of separately filtered images) and features (|difference|) are both symmetric.
  const ImageF a = pattern(40, 32);
  ImageF b = uniform(40, 32, 0.5f, 0.2f, 0.7f);
  const ErrorMap ab = flipLdr(a, b), ba = flipLdr(b, a);
  for (size_t i = 0; i < ab.values.size(); ++i) ASSERT_NEAR(ab.values[i], ba.values[i], 1e-5f);
  EXPECT_GT(errorStats(ab).mean, 0.05);
}

TEST(FlipMap, LargerErrorsScoreHigher) {
  const ImageF a = pattern(40, 32);
  ImageF slightly = a, badly = a;
  for (size_t i = 0; i < a.rgba.size(); i += 4) {
    slightly.rgba[i] = std::min(1.0f, a.rgba[i] + 0.02f);
    badly.rgba[i] = std::min(1.0f, a.rgba[i] + 0.3f);
  }
  EXPECT_LT(errorStats(flipLdr(a, slightly)).mean, errorStats(flipLdr(a, badly)).mean);
}

TEST(FlipMap, MaskRestrictsTheMean) {
  ErrorMap map{2, 2, {0.2f, 0.4f, 0.6f, 0.8f}};
  PixelMask mask{2, 2, {1, 0, 1, 0}};
  const ErrorStats s = errorStats(map, mask);
  EXPECT_EQ(s.pixels, 2u);
  EXPECT_NEAR(s.mean, 0.4, 1e-7);
  EXPECT_NEAR(s.max, 0.6, 1e-7);
  const ErrorStats all = errorStats(map);
  EXPECT_EQ(all.pixels, 4u);
  EXPECT_NEAR(all.mean, 0.5, 1e-7);
}

TEST(FlipHdr, TonemapperAndItsInverse) {
  EXPECT_EQ(flip::tonemap(0.0), 0.0);
  EXPECT_EQ(flip::tonemap(1e6), 1.0);  // clamped
  // y(1) = (0.9036 + 0.018) / (0.8748 + 0.354 + 0.14) = 0.67346.
  EXPECT_NEAR(flip::tonemap(1.0), (0.9036 + 0.018) / (0.8748 + 0.354 + 0.14), 1e-12);
  // (0.85 k3 - k0) x^2 + (0.85 k4 - k1) x + 0.85 k5 = 0: -0.16002 x^2 + 0.2829 x + 0.119 = 0, x = 2.11887.
  EXPECT_NEAR(flip::tonemapInverse(0.85), 2.11887, 1e-5);
  for (double y : {0.1, 0.5, 0.85, 0.99}) EXPECT_NEAR(flip::tonemap(flip::tonemapInverse(y)), y, 1e-12);
}

TEST(FlipHdr, ExposuresFromTheReference) {
  // Luminance 1 everywhere (grey 1: 0.2126 + 0.7152 + 0.0722) except one pixel of 16:
  // start = log2(2.11887 / 16) = -2.91670, stop = log2(2.11887 / 1) = 1.08330, count = ceil(4) = 4.
  ImageF image = uniform(5, 5, 1, 1, 1);
  image.pixel(2, 2)[0] = image.pixel(2, 2)[1] = image.pixel(2, 2)[2] = 16.0f;
  const HdrExposures e = hdrFlipExposures(image);
  EXPECT_NEAR(e.start, -2.91670, 1e-4);
  EXPECT_NEAR(e.stop, 1.08330, 1e-4);
  EXPECT_EQ(e.count, 4);
  EXPECT_NEAR(e.at(3), e.stop, 1e-12);
  // Mostly black: the median of the lit pixels stands in for a median of 0.
  ImageF dark = uniform(5, 5, 0, 0, 0);
  dark.pixel(0, 0)[1] = 2.0f;
  const HdrExposures d = hdrFlipExposures(dark);
  EXPECT_TRUE(std::isfinite(d.stop));
  EXPECT_GE(d.count, 2);
  EXPECT_EQ(hdrFlipExposures(uniform(3, 3, 0, 0, 0)).count, 2);
}

TEST(FlipHdr, DoubledExposureIsAnError) {
  ImageF ref = pattern(40, 32);
  for (size_t i = 0; i < ref.rgba.size(); i += 4) ref.rgba[i] *= 6.0f;  // some HDR range
  ImageF doubled = ref;
  for (size_t i = 0; i < doubled.rgba.size(); ++i)
    if (i % 4 != 3) doubled.rgba[i] *= 2.0f;
  const HdrFlipResult same = flipHdr(ref, ref);
  EXPECT_EQ(errorStats(same.map).max, 0.0);
  const HdrFlipResult r = flipHdr(ref, doubled);
  EXPECT_GE(r.exposures.count, 2);
  EXPECT_GT(errorStats(r.map).mean, 0.05);
  // The maximum over exposures is at least any single exposure's LDR-FLIP.
  auto exposed = [&](const ImageF& image, double c) {
    ImageF out = image;
    for (size_t i = 0; i < out.rgba.size(); ++i)
      if (i % 4 != 3) out.rgba[i] = static_cast<float>(flip::tonemap(std::exp2(c) * image.rgba[i]));
    return out;
  };
  const ErrorMap first = flipLdr(exposed(ref, r.exposures.start), exposed(doubled, r.exposures.start));
  for (size_t i = 0; i < first.values.size(); ++i) ASSERT_GE(r.map.values[i], first.values[i] - 1e-6f);
}

TEST(FlipHeatmap, MagmaEnds) {
  const auto& magma = magmaTable();
  // round(255 * matplotlib's first and last entries).
  EXPECT_EQ(magma[0], (Rgb8{0, 0, 4}));
  EXPECT_EQ(magma[255], (Rgb8{252, 253, 191}));
  EXPECT_EQ(magma[128], (Rgb8{183, 55, 121}));  // control point 0.716387, 0.214982, 0.475290
  // Perceptually ordered: luminance rises monotonically.
  double previous = -1;
  for (const Rgb8& c : magma) {
    const double y = 0.2126 * srgbToLinear(c[0] / 255.0f) + 0.7152 * srgbToLinear(c[1] / 255.0f) +
                     0.0722 * srgbToLinear(c[2] / 255.0f);
    EXPECT_GE(y, previous - 1e-4);
    previous = y;
  }
  const ErrorMap map{2, 1, {0.0f, 1.0f}};
  const Image8 heat = flipHeatmap(map);
  EXPECT_EQ(heat.pixel(0, 0)[2], 4);
  EXPECT_EQ(heat.pixel(1, 0)[0], 252);
  EXPECT_EQ(heat.pixel(1, 0)[3], 255);
}
