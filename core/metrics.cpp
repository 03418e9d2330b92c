#include "core/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include <fmt/format.h>

#include "core/error.h"

namespace rayster {
namespace {

std::optional<std::string> checkSize(int width, int height, size_t values, int expectWidth, int expectHeight) {
  if (width <= 0 || height <= 0 || values == 0) return fmt::format("image is empty ({}x{})", width, height);
  if (values != static_cast<size_t>(width) * static_cast<size_t>(height) * 4)
    return fmt::format("image {}x{} has {} values, expected {}", width, height, values,
                       static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
  if (width != expectWidth || height != expectHeight)
    return fmt::format("image is {}x{}, expected {}x{}", width, height, expectWidth, expectHeight);
  return std::nullopt;
}

template <class T>
std::optional<std::string> rejectBlackOrUniform(const std::vector<T>& rgba) {
  bool anyNonZero = false;
  bool uniform = true;
  for (size_t i = 0; i < rgba.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) {
      if (rgba[i + c] != T(0)) anyNonZero = true;
      if (rgba[i + c] != rgba[c]) uniform = false;
    }
    if (anyNonZero && !uniform) return std::nullopt;
  }
  if (!anyNonZero) return std::string("image is all black");
  return fmt::format("image is uniform (every pixel is {}, {}, {})", rgba[0], rgba[1], rgba[2]);
}

// Black -> red -> yellow -> white, so small and large errors are distinguishable at a glance.
void heatColor(int diff, uint8_t* out) {
  const double t = std::min(1.0, static_cast<double>(diff) / kHeatmapFullScale) * 3.0;
  auto channel = [](double v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
  out[0] = channel(t);
  out[1] = channel(t - 1.0);
  out[2] = channel(t - 2.0);
  out[3] = 255;
}

}  // namespace

std::optional<std::string> rejectEmpty(const Image8& image, int expectWidth, int expectHeight) {
  if (auto reason = checkSize(image.width, image.height, image.rgba.size(), expectWidth, expectHeight)) return reason;
  return rejectBlackOrUniform(image.rgba);
}

std::optional<std::string> rejectEmpty(const ImageF& image, int expectWidth, int expectHeight) {
  if (auto reason = checkSize(image.width, image.height, image.rgba.size(), expectWidth, expectHeight)) return reason;
  for (size_t i = 0; i < image.rgba.size(); ++i) {
    if (!std::isfinite(image.rgba[i])) {
      const size_t p = i / 4;
      return fmt::format("image has a non-finite value at pixel ({}, {}) channel {}",
                         p % static_cast<size_t>(image.width), p / static_cast<size_t>(image.width), i % 4);
    }
  }
  return rejectBlackOrUniform(image.rgba);
}

ImageDiff compare(const Image8& a, const Image8& b, int tolerance) {
  RAYSTER_ASSERT(a.width == b.width && a.height == b.height, "compare() needs images of equal size");
  RAYSTER_ASSERT(a.rgba.size() == b.rgba.size(), "compare() needs images of equal size");
  ImageDiff diff;
  diff.heatmap = Image8::make(a.width, a.height);
  const size_t pixels = a.rgba.size() / 4;
  size_t within = 0;
  double sumSquared = 0;
  for (size_t p = 0; p < pixels; ++p) {
    int pixelMax = 0;
    for (size_t c = 0; c < 3; ++c) {
      const int d = std::abs(static_cast<int>(a.rgba[p * 4 + c]) - static_cast<int>(b.rgba[p * 4 + c]));
      pixelMax = std::max(pixelMax, d);
      sumSquared += static_cast<double>(d) * d;
    }
    diff.maxChannelDiff = std::max(diff.maxChannelDiff, pixelMax);
    if (pixelMax <= tolerance) ++within;
    heatColor(pixelMax, diff.heatmap.rgba.data() + p * 4);
  }
  if (pixels == 0) {
    diff.fractionWithinTolerance = 1.0;
    diff.psnr = std::numeric_limits<double>::infinity();
    return diff;
  }
  diff.fractionWithinTolerance = static_cast<double>(within) / static_cast<double>(pixels);
  diff.rmse = std::sqrt(sumSquared / (static_cast<double>(pixels) * 3.0)) / 255.0;
  diff.psnr = diff.rmse == 0 ? std::numeric_limits<double>::infinity() : -20.0 * std::log10(diff.rmse);
  return diff;
}

size_t PixelMask::count() const {
  size_t n = 0;
  for (uint8_t v : inside) n += v != 0;
  return n;
}

PixelMask maskFromImage(const Image8& image) {
  PixelMask mask;
  mask.width = image.width;
  mask.height = image.height;
  mask.inside.resize(image.rgba.size() / 4);
  for (size_t p = 0; p < mask.inside.size(); ++p)
    mask.inside[p] = (image.rgba[p * 4] | image.rgba[p * 4 + 1] | image.rgba[p * 4 + 2]) != 0;
  return mask;
}

namespace {
// Mean over covered pixels and rgb of term(reference value, test value).
template <class Term>
double maskedChannelMean(const ImageF& a, const ImageF& b, const PixelMask& mask, Term&& term) {
  RAYSTER_ASSERT(a.width == b.width && a.height == b.height, "metrics need images of equal size");
  RAYSTER_ASSERT(a.rgba.size() == b.rgba.size(), "metrics need images of equal size");
  RAYSTER_ASSERT(
      mask.empty() || (mask.width == a.width && mask.height == a.height && mask.inside.size() * 4 == a.rgba.size()),
      "the mask must match the images' size");
  const size_t pixels = a.rgba.size() / 4;
  double sum = 0;
  size_t counted = 0;
  for (size_t p = 0; p < pixels; ++p) {
    if (!mask.covers(p)) continue;
    ++counted;
    for (size_t c = 0; c < 3; ++c)
      sum += term(static_cast<double>(a.rgba[p * 4 + c]), static_cast<double>(b.rgba[p * 4 + c]));
  }
  return counted == 0 ? 0.0 : sum / (static_cast<double>(counted) * 3.0);
}
}  // namespace

double rmse(const ImageF& a, const ImageF& b, const PixelMask& mask) {
  return std::sqrt(maskedChannelMean(a, b, mask, [](double x, double y) { return (x - y) * (x - y); }));
}

double psnr(const ImageF& a, const ImageF& b, const PixelMask& mask) {
  const double error = rmse(a, b, mask);
  return error == 0 ? std::numeric_limits<double>::infinity() : -20.0 * std::log10(error);
}

double relMse(const ImageF& ref, const ImageF& test, double eps, const PixelMask& mask) {
  return maskedChannelMean(ref, test, mask, [eps](double r, double t) { return (t - r) * (t - r) / (r * r + eps); });
}

}  // namespace rayster
