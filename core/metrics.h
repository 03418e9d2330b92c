#pragma once
// Image checks used by every pixel test and by `rayster compare`.
#include <optional>
#include <string>

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

double rmse(const ImageF& a, const ImageF& b); // rgb only
// Relative MSE: mean over pixels and rgb of (t-r)^2 / (r^2 + eps). Scale-independent, so one
// budget works for dim and bright scenes; eps keeps black reference pixels from dominating.
double relMse(const ImageF& ref, const ImageF& test, double eps = 1e-2);

} // namespace rayster
