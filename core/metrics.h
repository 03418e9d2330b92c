#pragma once
// Image checks used by every pixel test and by `rayster compare`.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"

namespace rayster {

// A reason why the image cannot be a real render (wrong size, empty, NaN/Inf, all black, uniform),
// or nullopt. Catches the classic false pass: a golden test comparing two black frames.
std::optional<std::string> rejectEmpty(const Image8& image, int expectWidth, int expectHeight);
std::optional<std::string> rejectEmpty(const ImageF& image, int expectWidth, int expectHeight);

struct ImageDiff {
  int maxChannelDiff = 0;              // 0..255
  double fractionWithinTolerance = 0;  // pixels whose 3 rgb diffs are all <= tolerance
  double rmse = 0;                     // on 0..1 values
  double psnr = 0;                     // dB, +inf if identical
  Image8 heatmap;                      // black -> red -> yellow -> white, white at diff >= kHeatmapFullScale
};

// Diffs above this are all "clearly wrong"; saturating there keeps small errors visible.
inline constexpr int kHeatmapFullScale = 16;

// RGB only (alpha is ignored: renders are opaque). Sizes must match.
ImageDiff compare(const Image8& a, const Image8& b, int tolerance);

// Which pixels a mean covers (`rayster compare --mask`). Empty: every pixel. Otherwise one byte per
// pixel, row-major like the images; nonzero means the pixel counts.
struct PixelMask {
  int width = 0, height = 0;
  std::vector<uint8_t> inside;

  bool empty() const { return inside.empty(); }
  bool covers(size_t pixel) const { return inside.empty() || inside[pixel] != 0; }
  size_t count() const;  // pixels that count (0 for an empty mask: use the image's size)
};
// A pixel counts when any of its rgb values is nonzero (alpha is ignored: masks are painted).
PixelMask maskFromImage(const Image8& image);

// These take the mean over the pixels `mask` covers (all when empty); a non-empty mask must match
// the images' size. With no pixel covered they return 0.
double rmse(const ImageF& a, const ImageF& b, const PixelMask& mask = {});  // rgb only
// Peak signal-to-noise ratio for a peak of 1: -20 log10(rmse), dB; +inf when identical.
double psnr(const ImageF& a, const ImageF& b, const PixelMask& mask = {});
// Relative MSE: mean over pixels and rgb of (t-r)^2 / (r^2 + eps). Scale-independent, so one
// budget works for dim and bright scenes; eps keeps black reference pixels from dominating.
inline constexpr double kRelMseEpsilon = 1e-2;
double relMse(const ImageF& ref, const ImageF& test, double eps = kRelMseEpsilon, const PixelMask& mask = {});

}  // namespace rayster
