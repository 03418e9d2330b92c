#pragma once
// FLIP: a perceptual difference between a reference image and a test image, as a viewer flipping
// between the two would see it. Written from the papers, not from their code:
//  - LDR-FLIP: P. Andersson, J. Nilsson, T. Akenine-Möller, M. Oskarsson, K. Åström, M. D. Fairchild,
//    "FLIP: A Difference Evaluator for Alternating Images", Proc. ACM CGIT (HPG) 3(2), 2020.
//  - HDR-FLIP: P. Andersson, J. Nilsson, P. Shirley, T. Akenine-Möller, "Visualizing Errors in
//    Rendered High Dynamic Range Images", Eurographics 2021 short papers.
// Each pixel gets an error in [0, 1]; `rayster compare` reports the mean and draws the map with magma.
#include <array>
#include <cstddef>
#include <vector>

#include "core/image.h"
#include "core/metrics.h"

namespace rayster {

// Pixels per degree of visual angle for a viewer `distanceMeters` from a monitor `widthMeters` wide
// that shows `resolutionX` pixels across.
double pixelsPerDegree(double distanceMeters, double widthMeters, double resolutionX);
// The papers' observer: 0.7 m from a 0.7 m wide 3840-pixel monitor (67.02), rounded as they do.
inline constexpr double kDefaultPixelsPerDegree = 67.0;

// A per-pixel error image, row-major, top row first (like ImageF), values in [0, 1].
struct ErrorMap {
  int width = 0, height = 0;
  std::vector<float> values;

  float at(int x, int y) const { return values[static_cast<size_t>(y) * static_cast<size_t>(width) + x]; }
};

// LDR-FLIP of two linear-RGB images (PNGs are sRGB-decoded first). FLIP is defined on [0, 1]: rgb is
// clamped to it, alpha is ignored. Sizes must match; `ppd` must be positive.
ErrorMap flipLdr(const ImageF& reference, const ImageF& test, double ppd = kDefaultPixelsPerDegree);

// The exposure compensations (EV stops) HDR-FLIP tonemaps at: `count` evenly spaced from start to stop.
struct HdrExposures {
  double start = 0, stop = 0;
  int count = 0;
  double at(int i) const { return count < 2 ? start : start + (stop - start) * i / (count - 1); }
};
// The paper's automatic range from the reference's luminance: at `start` the brightest pixel and at
// `stop` the median pixel tonemap to 0.85; one exposure per stop, at least two. A black reference
// has no range ({0, 0, 2}); a median of 0 (mostly black) uses the median of the lit pixels instead.
HdrExposures hdrFlipExposures(const ImageF& reference);

struct HdrFlipResult {
  ErrorMap map;  // per pixel, the largest LDR-FLIP error over the exposures
  HdrExposures exposures;
};
// HDR-FLIP of two linear HDR images (negative values count as 0): both are exposed by 2^c and
// tonemapped for every exposure c, compared with LDR-FLIP, and the per-pixel maximum is kept.
HdrFlipResult flipHdr(const ImageF& reference, const ImageF& test, double ppd = kDefaultPixelsPerDegree);
HdrFlipResult flipHdr(const ImageF& reference, const ImageF& test, double ppd, const HdrExposures& exposures);

struct ErrorStats {
  double mean = 0, max = 0;
  size_t pixels = 0;  // pixels averaged (those the mask covers)
};
// Over the pixels `mask` covers (all when empty); a non-empty mask must match the map's size.
ErrorStats errorStats(const ErrorMap& map, const PixelMask& mask = {});

// The map drawn with the magma colour map (core/colormap.h): black-purple for 0, pale yellow for 1.
Image8 flipHeatmap(const ErrorMap& map);

// The pipeline's steps, public so tests can check them against hand-computed values.
namespace flip {
using Vec3 = std::array<double, 3>;

// Linear sRGB (Rec. 709 primaries, D65) <-> CIE XYZ, the IEC 61966-2-1 matrices.
Vec3 linearRgbToXyz(const Vec3& rgb);
Vec3 xyzToLinearRgb(const Vec3& xyz);
// The white all conversions below are relative to: XYZ of linear rgb (1, 1, 1).
Vec3 referenceWhite();
// YyCxCz, the linearised CIELAB opponent space the CSFs filter in:
// Yy = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn).
Vec3 xyzToYcxcz(const Vec3& xyz);
Vec3 ycxczToXyz(const Vec3& ycxcz);
Vec3 xyzToLab(const Vec3& xyz);  // CIELAB
// Hunt effect (chroma fades in the dark): a* and b* scaled by 0.01 L*.
Vec3 huntAdjust(const Vec3& lab);
// HyAB distance: |dL| + sqrt(da^2 + db^2).
double hyab(const Vec3& lab1, const Vec3& lab2);
// cmax: the (powered) HyAB distance between Hunt-adjusted green and blue, the largest in the gamut.
double maxColorDifference();
// Maps a powered HyAB difference to [0, 1]: the lower pc * cmax of the range onto [0, pt], the rest
// onto [pt, 1], so small differences are spread over most of the error scale.
double redistributeColorError(double poweredHyab, double cmax);

// Spatial contrast-sensitivity filter of channel 0 (Yy), 1 (Cx) or 2 (Cz): radius r, 2r + 1 taps per
// row, (2r + 1)^2 weights summing to 1, row-major.
std::vector<double> csfKernel(int channel, double ppd);
// Feature detectors on the achromatic channel: 1-D Gaussian (sum 1), its first and second derivatives
// (positive weights sum to 1, negative weights to -1), all of the same radius.
struct FeatureKernels {
  std::vector<double> gaussian, firstDerivative, secondDerivative;
};
FeatureKernels featureKernels(double ppd);

// HDR-FLIP's tonemapper, the ACES fit as a ratio of quadratics, clamped to [0, 1]; and its inverse on
// [0, 1) (the x >= 0 that maps to y).
double tonemap(double x);
double tonemapInverse(double y);
}  // namespace flip

}  // namespace rayster
